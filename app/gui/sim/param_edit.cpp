#include "param_edit.hpp"

#include <cmath>

namespace impactlab::gui {

namespace {

struct RigKey {
    const char* key;
    const char* unit;
    double Params::*field;
};
constexpr RigKey kRigKeys[] = {{"m", "kg", &Params::m},       {"c", "N s/m", &Params::c}, {"k", "N/m", &Params::k},
                               {"T", "N", &Params::T},        {"m0e", "kg m", &Params::m0e},
                               {"eps", "m/s", &Params::eps}};

const RigKey* rig_key(const std::string& key) {
    for (const RigKey& r : kRigKeys)
        if (key == r.key) return &r;
    return nullptr;
}

}  // namespace

std::vector<EditableParam> editable_params(const Params& p) {
    std::vector<EditableParam> out;
    Params paper;
    try {
        paper = make_version(p.stiffness_id + p.impact->id);
    } catch (const ParamError&) {
        paper = p;   // a user's version: its own values are the reset
    }
    for (const RigKey& r : kRigKeys) out.push_back({r.key, r.unit, p.*r.field, paper.*r.field});
    for (std::size_t i = 0; i < p.impact->names.size() && p.impact->names[i]; ++i)
        out.push_back({p.impact->names[i], p.impact->units[i], p.ip[i], paper.ip[i]});
    return out;
}

bool set_param(Params& p, const std::string& key, double value, std::string& error) {
    Params np = p;
    try {
        if (const RigKey* r = rig_key(key)) np.*(r->field) = value;
        else set_impact_param(np, key, value);
        validate(np, "parameters");
    } catch (const ParamError& e) {
        // The core's reason alone: each caller names the key in its own words (the file's key, the flag), so
        // its "parameters: key 'KEY': " would say it twice. Another key's limit keeps that key's name.
        error = e.what();
        for (const std::string& lead : {std::string("parameters: "), "key '" + key + "': "})
            if (error.compare(0, lead.size(), lead) == 0) error.erase(0, lead.size());
        return false;
    }
    p = std::move(np);
    error.clear();
    return true;
}

bool params_edited(const Params& p) {
    for (const EditableParam& e : editable_params(p))
        if (e.value != e.paper) return true;
    return false;
}

}  // namespace impactlab::gui
