#include "model_file.hpp"

#include <nlohmann/json.hpp>

#include "impactlab/params.hpp"
#include "impactlab/params_json.hpp"
#include "sim/param_edit.hpp"

namespace impactlab::gui {

GuiModel gui_model_from_file(const std::string& path) {
    Params p;
    try {
        p = load_params(path);
    } catch (const ParamError& e) {
        throw ModelFileError(e.what());
    }
    GuiModel g;
    g.name = p.name;
    g.version = p.stiffness_id + std::string(p.impact ? p.impact->id : "");
    Params v;
    try {
        v = make_version(g.version);
    } catch (const ParamError&) {
        throw ModelFileError(path + ": key 'stiffness': the visualiser runs the versions A1 and A3 with a bumper law, not '" +
                             g.version + "'");
    }
    // The panel's parameters, each set as typing it would (the core's validate() already passed the file).
    const std::vector<EditableParam> want = editable_params(p);
    for (const EditableParam& e : editable_params(v)) {
        for (const EditableParam& w : want)
            if (w.key == e.key && w.value != e.value) {
                std::string error;
                if (!set_param(v, w.key, w.value, error)) throw ModelFileError(path + ": key '" + w.key + "': " + error);
                g.params.emplace_back(w.key, w.value);
            }
    }
    if (!(std::abs(p.xI) <= 0.02))
        throw ModelFileError(path + ": key 'xI': the visualiser's bumper moves within +-0.02 m");
    v.xI = g.xI = p.xI;
    // What is left must be the file exactly: any other difference is named, never dropped.
    v.name = p.name;
    const nlohmann::json a = nlohmann::json::parse(params_to_json_text(p)), b = nlohmann::json::parse(params_to_json_text(v));
    for (const auto& item : a.items())
        if (!b.contains(item.key()) || b[item.key()] != item.value())
            throw ModelFileError(path + ": key '" + item.key() + "': the visualiser cannot show this value (it runs " + g.version +
                                 " with the Parameters panel's keys and x_I only)");
    return g;
}

}  // namespace impactlab::gui
