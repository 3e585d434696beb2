#include "session.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <set>
#include <sstream>

#include "impactlab/json_text.hpp"
#include "impactlab/atomic_file.hpp"
#include "impactlab/input_file.hpp"
#include "impactlab/params.hpp"
#include "window/layout.hpp"
#include "sim/param_edit.hpp"
#include "views/strip_keys.hpp"

namespace impactlab::gui {

using nlohmann::json;

json session_to_json(const Session& s) {
    json j;
    j["format"] = kSessionFormat;
    j["version"] = kSessionVersion;
    j["model"] = s.model;
    j["omega"] = s.omega;
    j["xI"] = s.xI;
    j["speed"] = s.speed;
    j["paused"] = s.paused;
    j["state"] = {{"t", s.t}, {"x", s.x}, {"v", s.v}, {"phi", s.phi}};
    json zoom = json::object();
    for (const SessionView& v : s.views) zoom[v.id] = {{"x", {v.x_lo, v.x_hi}}, {"y", {v.y_lo, v.y_hi}}};
    j["view"] = {{"theme", s.dark ? "dark" : "light"},
                 {"ui_scale", s.ui_scale},
                 {"trail_periods", s.trail_periods},
                 {"strip_window", s.strip_window},
                 {"poincare_phi0", s.poincare_phi0},
                 {"zoom", std::move(zoom)}};
    j["windows"] = {{"data", s.show_data}, {"help", s.show_help}};
    j["bifurcation"] = {{"protocol", s.bif_protocol}, {"steps", s.bif_steps}};
    j["data"] = s.data.empty() ? json(nullptr) : json(s.data);
    j["companion"] = {{"mode", s.companion}, {"ghost_impact", s.ghost_impact}};
    j["layout"] = {{"mode", s.presentation ? "presentation" : "normal"},
                   {"hidden", s.hidden},
                   {"maximised", s.maximised.empty() ? json(nullptr) : json(s.maximised)},
                   {"presentation_plot", s.presentation_plot},
                   {"magnify", {s.magnify, s.magnify_presentation}}};
    json params = json::object();
    for (const auto& [k, v] : s.params) params[k] = v;
    j["params"] = std::move(params);
    j["strip"] = s.strip;
    json orbits = json::array();
    for (const SessionOrbit& o : s.orbits) {
        json pts = json::array();
        for (const auto& [x, v] : o.points) pts.push_back({x, v});
        orbits.push_back({{"start", {o.x0, o.v0}}, {"points", std::move(pts)}});
    }
    j["clicker"] = {{"on", s.clicker}, {"orbits", std::move(orbits)}};
    return j;
}

namespace {

std::string fmt(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

// Reads one level of a session object, naming keys by their dotted path ("view.ui_scale") in errors.
class Reader {
public:
    Reader(const std::string& file, const json& obj, std::string prefix, std::initializer_list<const char*> keys)
        : file_(file), obj_(obj), prefix_(std::move(prefix)) {
        if (!obj_.is_object()) fail_at(prefix_, std::string("expected an object, got ") + obj_.type_name());
        for (const auto& item : obj_.items()) {
            bool known = false;
            for (const char* k : keys) known = known || item.key() == k;
            if (!known) {
                std::string all;
                for (const char* k : keys) all += (all.empty() ? "" : ", ") + std::string(k);
                fail(item.key(), "unknown key (known here: " + all + ")");
            }
        }
    }
    [[noreturn]] void fail(const std::string& key, const std::string& what) const { fail_at(path(key), what); }
    [[noreturn]] void fail_at(const std::string& key, const std::string& what) const {
        throw SessionError(file_ + ": key '" + key + "': " + what);
    }
    const json* find(const char* key) const {
        const auto it = obj_.find(key);
        return it == obj_.end() ? nullptr : &*it;
    }
    std::string path(const std::string& key) const { return prefix_.empty() ? key : prefix_ + "." + key; }

    void number(const char* key, double& out, double lo, double hi, const char* unit = "") const {
        const json* v = find(key);
        if (!v) return;
        if (!v->is_number()) fail(key, std::string("expected a number, got ") + v->type_name());
        const double d = v->get<double>();
        if (!std::isfinite(d) || d < lo || d > hi)
            fail(key, fmt(d) + " is out of range [" + fmt(lo) + ", " + fmt(hi) + "]" + unit);
        out = d;
    }
    void integer(const char* key, int& out, int lo, int hi) const {
        const json* v = find(key);
        if (!v) return;
        if (!v->is_number_integer()) fail(key, std::string("expected an integer, got ") + v->type_name());
        // Beyond long long the parser keeps it unsigned: name it as written, not as its wrapped value.
        if (v->is_number_unsigned() && v->get<unsigned long long>() > static_cast<unsigned long long>(hi))
            fail(key, std::to_string(v->get<unsigned long long>()) + " is out of range [" + std::to_string(lo) + ", " +
                          std::to_string(hi) + "]");
        const long long n = v->get<long long>();
        if (n < lo || n > hi)
            fail(key, std::to_string(n) + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
        out = static_cast<int>(n);
    }
    void boolean(const char* key, bool& out) const {
        const json* v = find(key);
        if (!v) return;
        if (!v->is_boolean()) fail(key, std::string("expected true or false, got ") + v->type_name());
        out = v->get<bool>();
    }
    // One of `choices`.
    void word(const char* key, std::string& out, const std::vector<std::string>& choices) const {
        const json* v = find(key);
        if (!v) return;
        if (!v->is_string()) fail(key, std::string("expected a string, got ") + v->type_name());
        const std::string s = v->get<std::string>();
        std::string all;
        for (const std::string& c : choices) {
            if (s == c) {
                out = s;
                return;
            }
            all += (all.empty() ? "" : ", ") + c;
        }
        fail(key, "'" + s + "' is not one of " + all);
    }
    // A [lo, hi] pair with lo < hi, both finite; `key` is the full path.
    void range(const json& v, const std::string& key, double& lo, double& hi) const {
        if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
            fail_at(key, "expected [lo, hi], two numbers");
        lo = v[0].get<double>();
        hi = v[1].get<double>();
        if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi)) {
            std::string what = "[";   // (appended, not "[" + ...: GCC 12's -Wrestrict false positive)
            what.append(fmt(lo)).append(", ").append(fmt(hi)).append("] is empty");
            fail_at(key, what);
        }
    }

private:
    const std::string& file_;
    const json& obj_;
    std::string prefix_;
};

// The sections of a session file, each checked and read into s in the order session_from_json calls them.
// The model version, by name.
void read_model(const Reader& top, const std::string& /*file*/, Session& s) {
    if (const json* m = top.find("model")) {
        if (!m->is_string()) top.fail("model", std::string("expected a string, got ") + m->type_name());
        const std::string name = m->get<std::string>();
        try {
            s.model = make_version(name).name;
        } catch (const ParamError&) {
            std::string all;
            for (const auto& n : version_names()) all += (all.empty() ? "" : ", ") + n;
            top.fail("model", "unknown model version '" + name + "' (one of " + all + ")");
        }
    }
}

// The cart's state: t, x, v and phi.
void read_state(const Reader& top, const std::string& file, Session& s) {
    if (const json* st = top.find("state")) {
        const Reader r(file, *st, "state", {"t", "x", "v", "phi"});
        r.number("t", s.t, 0.0, 1e9, " s");
        r.number("x", s.x, -0.05, 0.05, " m");
        r.number("v", s.v, -2.0, 2.0, " m/s");
        r.number("phi", s.phi, -1e12, 1e12, " rad");
    }
}

// The display settings and each plot's zoom.
void read_view(const Reader& top, const std::string& file, Session& s) {
    if (const json* vw = top.find("view")) {
        const Reader r(file, *vw, "view", {"theme", "ui_scale", "trail_periods", "strip_window", "poincare_phi0", "zoom"});
        std::string theme = s.dark ? "dark" : "light";
        r.word("theme", theme, {"dark", "light"});
        s.dark = theme == "dark";
        r.number("ui_scale", s.ui_scale, 0.5, 3.0);
        r.number("trail_periods", s.trail_periods, 1.0, 60.0);
        r.number("strip_window", s.strip_window, 0.5, 60.0, " s");
        r.number("poincare_phi0", s.poincare_phi0, 0.0, 2.0 * std::numbers::pi, " rad");
        if (const json* z = r.find("zoom")) {
            if (!z->is_object()) r.fail("zoom", std::string("expected an object, got ") + z->type_name());
            s.views.clear();
            for (const auto& item : z->items()) {
                const std::string key = "view.zoom." + item.key();
                if (item.key().empty()) r.fail_at(key, "a plot id is empty");
                const Reader p(file, item.value(), key, {"x", "y"});
                SessionView v;
                v.id = item.key();
                if (!p.find("x") || !p.find("y")) p.fail_at(key, "expected both \"x\" and \"y\"");
                p.range(*p.find("x"), p.path("x"), v.x_lo, v.x_hi);
                p.range(*p.find("y"), p.path("y"), v.y_lo, v.y_hi);
                s.views.push_back(std::move(v));
            }
        }
    }
}

// The floating windows open.
void read_windows(const Reader& top, const std::string& file, Session& s) {
    if (const json* w = top.find("windows")) {
        const Reader r(file, *w, "windows", {"data", "help"});
        r.boolean("data", s.show_data);
        r.boolean("help", s.show_help);
    }
}

// The bifurcation diagram's protocol and steps.
void read_bifurcation(const Reader& top, const std::string& file, Session& s) {
    if (const json* b = top.find("bifurcation")) {
        const Reader r(file, *b, "bifurcation", {"protocol", "steps"});
        r.word("protocol", s.bif_protocol, {"cf-up", "cf-down", "ef"});
        r.integer("steps", s.bif_steps, 10, 2000);
    }
}

// The companion cart's mode and the ghost's impact law.
void read_companion(const Reader& top, const std::string& file, Session& s) {
    if (const json* c = top.find("companion")) {
        const Reader r(file, *c, "companion", {"mode", "ghost_impact"});
        r.word("mode", s.companion, {"off", "twin", "ghost"});
        if (const json* g = r.find("ghost_impact")) {
            if (!g->is_string()) r.fail("ghost_impact", std::string("expected a string, got ") + g->type_name());
            const std::string id = g->get<std::string>();
            std::string all;
            bool known = false;
            for (const ImpactModel& m : impact_models()) {
                known = known || id == m.id;
                all += (all.empty() ? "" : ", ") + std::string(m.id);
            }
            if (!known) r.fail("ghost_impact", "'" + id + "' is not an impact law (one of " + all + ")");
            s.ghost_impact = id;
        }
    }
}

// The layout: mode, hidden and maximised panels, the presentation plot, the rig's magnification.
void read_layout(const Reader& top, const std::string& file, Session& s) {
    if (const json* l = top.find("layout")) {
        const Reader r(file, *l, "layout", {"mode", "hidden", "maximised", "presentation_plot", "magnify"});
        std::string mode = s.presentation ? "presentation" : "normal";
        r.word("mode", mode, {"normal", "presentation"});
        s.presentation = mode == "presentation";
        const std::string panels = "controls, " + panel_keys();
        if (const json* h = r.find("hidden")) {
            if (!h->is_array()) r.fail("hidden", std::string("expected an array of panel names, got ") + h->type_name());
            s.hidden.clear();
            for (const json& e : *h) {
                if (!e.is_string() || (e.get<std::string>() != "controls" && !panel_from_key(e.get<std::string>())))
                    r.fail("hidden", e.dump() + " is not a panel (one of " + panels + ")");
                s.hidden.push_back(e.get<std::string>());
            }
        }
        if (const json* m = r.find("maximised")) {
            if (m->is_null()) s.maximised.clear();
            else if (!m->is_string() || !panel_from_key(m->get<std::string>()))
                r.fail("maximised", m->dump() + " is not a panel (null, or one of " + panel_keys() + ")");
            else s.maximised = m->get<std::string>();
        }
        std::vector<std::string> plots;
        for (PanelId p : presentation_plots()) plots.emplace_back(panel_key(p));
        r.word("presentation_plot", s.presentation_plot, plots);
        if (const json* g = r.find("magnify")) {
            if (!g->is_array() || g->size() != 2 || !(*g)[0].is_number() || !(*g)[1].is_number())
                r.fail("magnify", "expected [normal, presentation], two numbers in [1, 10]");
            const double a = (*g)[0].get<double>(), b = (*g)[1].get<double>();
            constexpr double lo = RigMagnify::kMin, hi = RigMagnify::kMax;
            if (!(a >= lo && a <= hi && b >= lo && b <= hi))
                r.fail("magnify", "[" + fmt(a) + ", " + fmt(b) + "] is outside [" + fmt(lo) + ", " + fmt(hi) + "]");
            s.magnify = a;
            s.magnify_presentation = b;
        }
    }
}

// The edited parameters.
void read_params(const Reader& top, const std::string& /*file*/, Session& s) {
    if (const json* ps = top.find("params")) {
        // Each value as the Parameters panel would take it, on the session's model: the core's validate()
        // decides, and its words name the problem.
        if (!ps->is_object()) top.fail("params", std::string("expected an object of numbers, got ") + ps->type_name());
        Params p = make_version(s.model);
        std::vector<std::string> keys;
        for (const EditableParam& e : editable_params(p)) keys.push_back(e.key);
        s.params.clear();
        for (const auto& item : ps->items()) {
            const std::string key = "params." + item.key();
            if (std::find(keys.begin(), keys.end(), item.key()) == keys.end()) {
                std::string all;
                for (const std::string& k : keys) all += (all.empty() ? "" : ", ") + k;
                top.fail_at(key, "not a parameter of " + s.model + " (one of " + all + ")");
            }
            if (!item.value().is_number()) top.fail_at(key, std::string("expected a number, got ") + item.value().type_name());
            std::string error;
            if (!set_param(p, item.key(), item.value().get<double>(), error)) top.fail_at(key, error);
            s.params.emplace_back(item.key(), item.value().get<double>());
        }
    }
}

// The time strip's traces.
void read_strip(const Reader& top, const std::string& /*file*/, Session& s) {
    if (const json* st = top.find("strip")) {
        if (!st->is_array() || st->empty() || st->size() > 2)
            top.fail("strip", "expected one or two of x, v, E, F, drive");
        s.strip.clear();
        for (const json& e : *st) {
            const bool known = e.is_string() && std::find_if(std::begin(kStripKeys), std::end(kStripKeys), [&](const char* k) {
                                                    return e.get<std::string>() == k;
                                                }) != std::end(kStripKeys);
            if (!known) top.fail("strip", e.dump() + " is not one of x, v, E, F, drive");
            s.strip.push_back(e.get<std::string>());
        }
    }
}

// The Poincare clicker and its orbits.
void read_clicker(const Reader& top, const std::string& file, Session& s) {
    if (const json* c = top.find("clicker")) {
        const Reader r(file, *c, "clicker", {"on", "orbits"});
        r.boolean("on", s.clicker);
        if (const json* os = r.find("orbits")) {
            if (!os->is_array() || os->size() > kSessionMaxOrbits)
                r.fail("orbits", "expected an array of at most " + std::to_string(kSessionMaxOrbits) + " orbits");
            s.orbits.clear();
            auto point = [&](const json& v, const std::string& key, double& x, double& xv) {
                if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
                    r.fail_at(key, "expected [x, v], two numbers");
                x = v[0].get<double>();
                xv = v[1].get<double>();
                if (!(std::abs(x) <= 0.05) || !(std::abs(xv) <= 2.0))
                    r.fail_at(key, "[" + fmt(x) + ", " + fmt(xv) + "] is off the rail (|x| <= 0.05 m, |v| <= 2 m/s)");
            };
            for (std::size_t i = 0; i < os->size(); ++i) {
                const std::string key = "clicker.orbits." + std::to_string(i);
                const Reader o(file, (*os)[i], key, {"start", "points"});
                SessionOrbit orbit;
                if (!o.find("start")) o.fail_at(key, "expected \"start\"");
                point(*o.find("start"), o.path("start"), orbit.x0, orbit.v0);
                if (const json* pts = o.find("points")) {
                    if (!pts->is_array() || pts->size() > kSessionMaxOrbitPoints)
                        o.fail("points", "expected an array of at most " + std::to_string(kSessionMaxOrbitPoints) + " [x, v]");
                    for (std::size_t k = 0; k < pts->size(); ++k) {
                        double x = 0, v = 0;
                        point((*pts)[k], o.path("points") + "." + std::to_string(k), x, v);
                        orbit.points.emplace_back(x, v);
                    }
                }
                s.orbits.push_back(std::move(orbit));
            }
        }
    }
}

// The measured data's file.
void read_data(const Reader& top, const std::string& file, Session& s) {
    if (const json* d = top.find("data")) {
        if (d->is_null()) s.data.clear();
        else if (!d->is_string()) top.fail("data", std::string("expected a file name or null, got ") + d->type_name());
        else {
            std::string path = d->get<std::string>();
            // A relative name is relative to the session file's folder (as save_session writes it), so the session
            // opens from any working directory; one found only from here (an older session) is taken too.
            namespace fs = std::filesystem;
            if (!path.empty() && fs::path(path).is_relative() && !file.empty()) {
                const fs::path beside = (fs::path(file).parent_path() / path).lexically_normal();
                std::error_code ec;
                if (fs::exists(beside, ec) || !fs::exists(path, ec)) path = beside.string();
            }
            if (!path.empty()) try {
                    check_input_file(path);
                } catch (const InputFileError& e) {
                    top.fail("data", "cannot read '" + printable(path, 200) + "': " + e.reason);
                }
            s.data = path;
        }
    }
}
}  // namespace

Session session_from_json(const json& j, const Session& base, const std::string& file) {
    if (!j.is_object() || !j.contains("format"))
        throw SessionError(file + ": not a session file (a JSON object with \"format\": \"" + kSessionFormat +
                           "\" expected)");
    const Reader top(file, j, "",
                     {"format", "version", "model", "omega", "xI", "speed", "paused", "state", "view", "windows",
                      "bifurcation", "data", "companion", "layout", "params", "strip", "clicker"});
    if (!j["format"].is_string() || j["format"].get<std::string>() != kSessionFormat)
        top.fail("format", std::string("expected \"") + kSessionFormat + "\"");
    int version = kSessionVersion;
    top.integer("version", version, 1, 1000000);
    if (version != kSessionVersion)
        top.fail("version", std::to_string(version) + " is not supported (this program reads version " +
                                std::to_string(kSessionVersion) + ")");
    Session s = base;
    read_model(top, file, s);
    top.number("omega", s.omega, 0.0, 30.0, " rad/s");
    top.number("xI", s.xI, -0.02, 0.02, " m");
    top.number("speed", s.speed, 0.01, 100.0);
    top.boolean("paused", s.paused);
    read_state(top, file, s);
    read_view(top, file, s);
    read_windows(top, file, s);
    read_bifurcation(top, file, s);
    read_companion(top, file, s);
    read_layout(top, file, s);
    read_params(top, file, s);
    read_strip(top, file, s);
    read_clicker(top, file, s);
    read_data(top, file, s);
    return s;
}

namespace {
// The document built in one SAX pass, each key given twice in one object noted. (nlohmann's callback parser,
// used before, scans the whole parent at every closed object: 400k "{}" took 40 s.)
class UniqueKeysDom : public nlohmann::json_sax<json> {
public:
    json root;
    std::string duplicate;   // the first key given twice in one object
    std::string what;        // the parser's message at an error
    std::size_t byte = 0;    // where (1-based, as json::parse_error::byte)
    int error_id = 0;        // nlohmann's exception id: 406 is a number beyond a double
    bool null() override { return put(nullptr); }
    bool boolean(bool v) override { return put(v); }
    bool number_integer(number_integer_t v) override { return put(v); }
    bool number_unsigned(number_unsigned_t v) override { return put(v); }
    bool number_float(number_float_t v, const string_t&) override { return put(v); }
    bool string(string_t& v) override { return put(std::move(v)); }
    bool binary(binary_t& v) override { return put(json::binary(std::move(v))); }
    bool start_object(std::size_t) override { return open(json::object()); }
    bool key(string_t& k) override {
        if (duplicate.empty() && stack_.back()->contains(k)) duplicate = k;
        key_ = std::move(k);
        return true;
    }
    bool end_object() override { return close(); }
    bool start_array(std::size_t) override { return open(json::array()); }
    bool end_array() override { return close(); }
    bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& ex) override {
        byte = position;
        what = ex.what();
        error_id = ex.id;
        return false;
    }

private:
    // Only the innermost open value changes, so the pointers to the outer ones on the stack stay valid.
    json* place(json v) {
        if (stack_.empty()) {
            root = std::move(v);
            return &root;
        }
        json& top = *stack_.back();
        if (top.is_array()) {
            top.push_back(std::move(v));
            return &top.back();
        }
        json& slot = top[key_];
        slot = std::move(v);
        return &slot;
    }
    bool put(json v) {
        place(std::move(v));
        return true;
    }
    bool open(json v) {
        stack_.push_back(place(std::move(v)));
        return true;
    }
    bool close() {
        stack_.pop_back();
        return true;
    }
    std::vector<json*> stack_;
    std::string key_;
};
}  // namespace

Session parse_session(const std::string& text, const Session& base, const std::string& file) {
    // One pass: the document and its duplicate keys (a key given twice would silently keep one of them).
    UniqueKeysDom dom;
    if (!json::sax_parse(text, &dom)) {
        if (dom.error_id == 406)   // a number beyond a double (1e999)
            throw SessionError(file + ": a number is out of range (" + dom.what + ")");
        // The line and column of the byte where parsing stopped (byte is 1-based).
        std::size_t line = 1, col = 1;
        for (std::size_t i = 0; i + 1 < dom.byte && i < text.size(); ++i) {
            if (text[i] == '\n') {
                ++line;
                col = 1;
            } else {
                ++col;
            }
        }
        std::string what = dom.what;
        if (const auto p = what.find(": syntax error"); p != std::string::npos) what = what.substr(p + 2);
        else if (const auto q = what.find("] "); q != std::string::npos) what = what.substr(q + 2);
        throw SessionError(file + ": line " + std::to_string(line) + ", column " + std::to_string(col) +
                           ": not valid JSON (" + what + ")");
    }
    if (!dom.duplicate.empty()) throw SessionError(file + ": key '" + printable(dom.duplicate, 200) + "' appears twice in one object");
    return session_from_json(dom.root, base, file);
}

Session load_session(const std::string& path, const Session& base) {
    std::string text;
    try {
        text = read_input_file(path);
    } catch (const InputFileError& e) {
        throw SessionError(e.what());
    }
    return parse_session(text, base, path);
}

std::string session_text(const Session& s) { return json_dump(session_to_json(s), 2) + "\n"; }   // names in any bytes

void save_session(const Session& s, const std::string& path) {
    if (path.empty()) throw SessionError("session: no file name given");
    // Whole or not at all, every write checked; any failure (a full disk, a name in any bytes) is a
    // SessionError, the one kind the GUI's save catches.
    // A relative data file name (relative to the working directory) is saved relative to the session file's
    // folder: the session then opens from any working directory, and the pair can move together.
    Session saved = s;
    if (!saved.data.empty() && std::filesystem::path(saved.data).is_relative()) {
        namespace fs = std::filesystem;
        std::error_code ec;
        const fs::path rel = fs::proximate(fs::absolute(saved.data, ec), fs::absolute(path, ec).parent_path(), ec);
        if (!ec && !rel.empty()) saved.data = rel.string();
    }
    try {
        write_file_whole(path, session_text(saved));
    } catch (const std::exception& e) {
        throw SessionError(printable(e.what()));
    }
}

}  // namespace impactlab::gui
