#include "impactlab/params_json.hpp"
#include "impactlab/json_text.hpp"
#include "impactlab/atomic_file.hpp"
#include "impactlab/input_file.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

namespace impactlab {

using nlohmann::json;

namespace {

[[noreturn]] void fail(const std::string& src, const std::string& msg) { throw ParamError(src + ": " + msg); }

double number(const json& j, const std::string& key, const std::string& src) {
    if (!j.is_number()) fail(src, "key '" + key + "': expected a number, got " + std::string(j.type_name()));
    const double v = j.get<double>();
    if (!std::isfinite(v)) fail(src, "key '" + key + "': must be a finite number");
    return v;
}

void check_keys(const json& obj, const std::set<std::string>& allowed, const std::string& prefix,
                const std::string& src) {
    for (auto it = obj.begin(); it != obj.end(); ++it)
        if (!allowed.count(it.key())) {
            std::string list;
            for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
            fail(src, "unknown key '" + prefix + it.key() + "' (allowed: " + list + ")");
        }
}

// Reads obj[key] into out if present; if absent and required, fails naming the key.
void read(const json& obj, const std::string& key, double& out, bool required, const std::string& prefix,
          const std::string& src) {
    if (!obj.contains(key)) {
        if (required) fail(src, "missing key '" + prefix + key + "'");
        return;
    }
    out = number(obj.at(key), prefix + key, src);
}

void read_coeffs(const json& obj, const std::string& key, std::array<double, 4>& out, bool required,
                 const std::string& src) {
    if (!obj.contains(key)) {
        if (required) fail(src, "missing key '" + key + "'");
        return;
    }
    const json& arr = obj.at(key);
    if (!arr.is_array() || arr.empty() || arr.size() > 4)
        fail(src, "key '" + key + "': expected an array of 1 to 4 numbers");
    out = {};
    for (std::size_t i = 0; i < arr.size(); ++i) out[i] = number(arr[i], key + "[" + std::to_string(i) + "]", src);
}

// A SAX pass that only tracks where it is ("impact.a_T", "b[0]"), to name the key at fault when the DOM
// parser stops with an error that carries only a byte position (an overflowing number, a syntax error).
class KeyPathSax : public nlohmann::json_sax<json> {
public:
    std::string path;   // the key path at the error
    std::string what;   // nlohmann's message
    std::size_t byte = 0;
    bool null() override { return value(); }
    bool boolean(bool) override { return value(); }
    bool number_integer(number_integer_t) override { return value(); }
    bool number_unsigned(number_unsigned_t) override { return value(); }
    bool number_float(number_float_t, const string_t&) override { return value(); }
    bool string(string_t&) override { return value(); }
    bool binary(binary_t&) override { return value(); }
    bool start_object(std::size_t) override {
        frames_.push_back({false, 0, "", {}});
        return true;
    }
    bool key(string_t& k) override {
        Frame& f = frames_.back();
        f.key = k;
        if (!f.seen.insert(k).second) {   // JSON allows it, nlohmann keeps the last: a typo nobody would see
            duplicate = key_path();
            return false;
        }
        return true;
    }
    bool end_object() override { return end(); }
    bool start_array(std::size_t) override {
        frames_.push_back({true, 0, "", {}});
        return true;
    }
    bool end_array() override { return end(); }
    bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& ex) override {
        byte = position;
        what = ex.what();
        path = key_path();
        return false;
    }
    std::string duplicate;   // the key path of a key given twice in one object

private:
    struct Frame { bool array; std::size_t index; std::string key; std::set<std::string> seen; };
    std::string key_path() const {
        std::string out;
        for (const auto& f : frames_) {
            if (f.array) {
                out.append("[").append(std::to_string(f.index)).append("]");
            } else if (!f.key.empty()) {
                if (!out.empty()) out.append(".");
                out.append(f.key);
            }
        }
        return out;
    }
    bool value() {
        if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
        return true;
    }
    bool end() {
        frames_.pop_back();
        return value();
    }
    std::vector<Frame> frames_;
};

std::string line_and_column(const std::string& text, std::size_t byte) {
    std::size_t line = 1, col = 1;
    for (std::size_t i = 0; i + 1 < byte && i < text.size(); ++i) {
        if (text[i] == '\n') {
            ++line;
            col = 1;
        } else {
            ++col;
        }
    }
    return "line " + std::to_string(line) + ", column " + std::to_string(col);
}

}  // namespace

Params params_from_json_text(const std::string& text, const std::string& src) {
    json j;
    try {
        j = json::parse(text);
    } catch (const json::exception& e) {
        // Parse again with a SAX pass to learn where: line, column and the key being read.
        KeyPathSax where;
        json::sax_parse(text, &where);
        // The SAX pass stops at a duplicate key before it reaches the syntax error: report that first.
        if (!where.duplicate.empty()) fail(src, "key '" + where.duplicate + "' appears twice (JSON would keep the last silently)");
        if (where.what.empty()) {   // the SAX pass saw no error: take the parser's own position
            const auto* pe = dynamic_cast<const json::parse_error*>(&e);
            where.byte = pe ? pe->byte : 0;
            where.what = e.what();
        }
        std::string msg = line_and_column(text, where.byte) + ": ";
        if (where.what.find("number overflow") != std::string::npos)
            msg += "key '" + where.path + "': the number is out of range (not finite)";
        else
            msg += "invalid JSON" + (where.path.empty() ? std::string() : " at key '" + where.path + "'") + " (" +
                   where.what + ")";
        fail(src, msg);
    }
    if (!j.is_object()) fail(src, "expected a JSON object at the top level");
    {
        KeyPathSax keys;
        json::sax_parse(text, &keys);
        if (!keys.duplicate.empty()) fail(src, "key '" + keys.duplicate + "' appears twice (JSON would keep the last silently)");
    }
    check_keys(j, {"name", "base", "stiffness", "m", "m0e", "k", "c", "T", "eps", "a", "b", "xI", "input_gain", "x_extent", "impact",
                   "effects"},
               "", src);

    // "base": start from a built-in version and override what the file gives; otherwise every key is required.
    Params p;
    bool required = true;
    if (j.contains("base")) {
        if (!j["base"].is_string()) fail(src, "key 'base': expected a version name such as \"A1H\"");
        try {
            p = make_version(j["base"].get<std::string>());
        } catch (const ParamError& e) {
            fail(src, std::string("key 'base': ") + e.what());
        }
        required = false;
    }
    if (j.contains("name")) {
        if (!j["name"].is_string()) fail(src, "key 'name': expected a string");
        p.name = j["name"].get<std::string>();
    } else if (!required) {
        p.name = j["base"].get<std::string>() + "*";
    } else {
        p.name = "custom";
    }
    if (j.contains("stiffness")) {
        if (!j["stiffness"].is_string()) fail(src, "key 'stiffness': expected a string");
        p.stiffness_id = j["stiffness"].get<std::string>();
        std::string known = duffing_stiffness().id;
        for (const auto& st : stiffness_sets()) known += ", " + std::string(st.id);
        if (!find_stiffness(p.stiffness_id))
            fail(src, "key 'stiffness': unknown label '" + p.stiffness_id + "' (known: " + known + ")");
    }
    read(j, "m", p.m, required, "", src);
    read(j, "m0e", p.m0e, required, "", src);
    read(j, "k", p.k, required, "", src);
    read(j, "c", p.c, required, "", src);
    read(j, "T", p.T, required, "", src);
    read(j, "eps", p.eps, required, "", src);
    read_coeffs(j, "a", p.a, required, src);
    read_coeffs(j, "b", p.b, required, src);
    read(j, "xI", p.xI, required, "", src);
    read(j, "input_gain", p.input_gain, false, "", src);   // optional: 0 (no sampled input) by default
    read(j, "x_extent", p.x_extent, false, "", src);       // optional: 0 (the rail) by default

    if (j.contains("impact")) {
        const json& im = j["impact"];
        if (!im.is_object()) fail(src, "key 'impact': expected an object with \"model\" and its parameters");
        if (!im.contains("model") || !im["model"].is_string()) fail(src, "missing key 'impact.model' (C, C1, G, H or none)");
        const std::string model = im["model"].get<std::string>();
        const ImpactModel* law = find_impact(model);
        if (!law) fail(src, "key 'impact.model': unknown impact model '" + model + "' (known: C, C1, G, H, none)");
        const bool same_law = p.impact == law;
        p.impact = law;
        if (!same_law) p.ip = law->defaults;
        std::set<std::string> allowed{"model"};
        for (std::size_t i = 0; i < kMaxLawParams && law->names[i]; ++i) allowed.insert(law->names[i]);
        check_keys(im, allowed, "impact.", src);
        // Without a base, or when the file switches the law, each of its parameters must be given.
        for (std::size_t i = 0; i < kMaxLawParams && law->names[i]; ++i)
            read(im, law->names[i], p.ip[i], required || !same_law, "impact.", src);
    } else if (required) {
        fail(src, "missing key 'impact'");
    }

    if (j.contains("effects")) {
        const json& ef = j["effects"];
        if (!ef.is_array()) fail(src, "key 'effects': expected an array of objects");
        p.effects.clear();
        for (std::size_t n = 0; n < ef.size(); ++n) {
            const std::string where = "effects[" + std::to_string(n) + "]";
            const json& e = ef[n];
            if (!e.is_object() || !e.contains("id") || !e["id"].is_string())
                fail(src, "key '" + where + "': expected an object with a string \"id\"");
            EffectInstance* inst = nullptr;
            try {
                inst = &add_effect(p, e["id"].get<std::string>());
            } catch (const ParamError& err) {
                fail(src, "key '" + where + ".id': " + err.what());
            }
            std::set<std::string> allowed{"id"};
            for (std::size_t i = 0; i < kMaxLawParams && inst->law->names[i]; ++i) allowed.insert(inst->law->names[i]);
            check_keys(e, allowed, where + ".", src);
            for (std::size_t i = 0; i < kMaxLawParams && inst->law->names[i]; ++i)
                read(e, inst->law->names[i], inst->p[i], true, where + ".", src);
        }
    }
    validate(p, src);
    return p;
}

Params load_params(const std::string& path) {
    std::string text;
    try {
        text = read_input_file(path);
    } catch (const InputFileError& e) {
        throw ParamError(e.path + ": not a parameter file: " + e.reason);
    }
    return params_from_json_text(text, path);
}

std::string params_to_json_text(const Params& p) {
    json j;
    j["name"] = p.name;
    j["stiffness"] = p.stiffness_id;
    j["m"] = p.m;
    j["m0e"] = p.m0e;
    j["k"] = p.k;
    j["c"] = p.c;
    j["T"] = p.T;
    j["eps"] = p.eps;
    j["a"] = json::array();
    j["b"] = json::array();
    for (double v : p.a) j["a"].push_back(v);
    for (double v : p.b) j["b"].push_back(v);
    j["xI"] = p.xI;
    if (p.input_gain != 0.0) j["input_gain"] = p.input_gain;
    if (p.x_extent != 0.0) j["x_extent"] = p.x_extent;
    json im;
    im["model"] = p.impact->id;
    for (std::size_t i = 0; i < kMaxLawParams && p.impact->names[i]; ++i) im[p.impact->names[i]] = p.ip[i];
    j["impact"] = im;
    j["effects"] = json::array();
    for (const auto& e : p.effects) {
        json ej;
        ej["id"] = e.law->id;
        for (std::size_t i = 0; i < kMaxLawParams && e.law->names[i]; ++i) ej[e.law->names[i]] = e.p[i];
        j["effects"].push_back(ej);
    }
    return json_dump(std::move(j), 2) + "\n";
}

void save_params(const Params& p, const std::string& path) {
    // Whole or not at all: a failed write keeps an old parameter file.
    try {
        write_file_whole(path, params_to_json_text(p));
    } catch (const std::runtime_error& e) {
        throw ParamError(e.what());
    }
}

Params resolve_model(const std::string& name_or_path) {
    const bool is_file = name_or_path.size() > 5 && name_or_path.substr(name_or_path.size() - 5) == ".json";
    return is_file ? load_params(name_or_path) : make_version(name_or_path);
}

}  // namespace impactlab
