// Parameter files: every error path of the JSON loader names the file, the key or the position; save and
// load round-trip exactly; the "base" override form.
#include <doctest/doctest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "impactlab/params.hpp"
#include "impactlab/params_json.hpp"

using namespace impactlab;

namespace {

std::string error_of_text(const std::string& text, const std::string& source = "test.json") {
    try {
        params_from_json_text(text, source);
    } catch (const ParamError& e) {
        return e.what();
    }
    return "";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// A complete file without a base: every key given (A1H's values), one "key": value a field.
const std::vector<std::pair<std::string, std::string>>& full_fields() {
    static const std::vector<std::pair<std::string, std::string>> fields{
        {"name", "\"A1H\""},
        {"stiffness", "\"A1\""},
        {"m", "6.73766"},
        {"m0e", "0.025152"},
        {"k", "1115.2"},
        {"c", "12.373"},
        {"T", "1.2267"},
        {"eps", "1e-6"},
        {"a", "[-1763.5]"},
        {"b", "[4907.6]"},
        {"xI", "0"},
        {"impact", R"({"model": "H", "kappa0": 0.615, "kappa1": 0.135, "a_kappa": 0.6594, "Ti0": 6.2193e-3,
                       "Ti1": 4.0689e-3, "a_T": 2.1733})"},
    };
    return fields;
}

// The complete file less the key `skip`, with the impact object replaced by `impact_override` if given.
std::string compose(const std::string& skip = "", const std::string& impact_override = "") {
    std::string t = "{";
    bool first = true;
    for (const auto& [key, value] : full_fields()) {
        if (key == skip) continue;
        const std::string& v = key == "impact" && !impact_override.empty() ? impact_override : value;
        t += (first ? "\n  \"" : ",\n  \"") + key + "\": " + v;
        first = false;
    }
    return t + "\n}\n";
}

std::string full_text() { return compose(); }
std::string without(const std::string& key) { return compose(key); }

// Unique per process, so that suites running side by side (several build trees) do not collide.
std::filesystem::path temp_path(const std::string& name) {
    static const std::string tag = std::to_string(std::random_device{}());
    return std::filesystem::temp_directory_path() / ("impactlab_params_json_test_" + tag + "_" + name);
}

}  // namespace

TEST_CASE("JSON: a complete file parses to the same parameters") {
    const Params p = params_from_json_text(full_text(), "full.json");
    const Params q = make_version("A1H");
    CHECK(p.name == q.name);
    CHECK(p.m == q.m);
    CHECK(p.k == q.k);
    CHECK(p.a == q.a);
    CHECK(p.b == q.b);
    CHECK(p.impact == q.impact);
    CHECK(p.ip == q.ip);
}

TEST_CASE("JSON: malformed text reports line and column") {
    // Line 3, after `"m": 6.7,` a stray token.
    const std::string text = "{\n  \"base\": \"A1H\",\n  \"m\": 6.7 @,\n  \"k\": 1000\n}\n";
    const std::string msg = error_of_text(text, "broken.json");
    CAPTURE(msg);
    CHECK(contains(msg, "broken.json"));
    CHECK(contains(msg, "line 3"));
    CHECK(contains(msg, "column 12"));   // the '@' is the 12th character of line 3
    // Unterminated object: the error sits at the end of the text, on line 2.
    const std::string msg2 = error_of_text("{\n  \"base\": \"A1H\"", "cut.json");
    CAPTURE(msg2);
    CHECK(contains(msg2, "line 2"));
    // Not an object.
    CHECK(contains(error_of_text("[1, 2, 3]"), "object"));
    CHECK(contains(error_of_text(""), "line 1"));
}

TEST_CASE("JSON: a missing key is named") {
    for (const char* key : {"m", "m0e", "k", "c", "T", "eps", "a", "b", "xI", "impact"}) {
        const std::string msg = error_of_text(without(key));
        const std::string key_name = key;
        CAPTURE(key_name);
        CAPTURE(msg);
        CHECK(contains(msg, "test.json"));
        CHECK(contains(msg, "missing key '" + std::string(key) + "'"));
    }
    // An impact parameter missing without a base.
    const std::string msg = error_of_text(
        compose("", R"({"model": "H", "kappa0": 0.615, "kappa1": 0.135, "a_kappa": 0.6594, "Ti0": 6.2193e-3,
                       "Ti1": 4.0689e-3})"));
    CAPTURE(msg);
    CHECK(contains(msg, "missing key 'impact.a_T'"));
    // The impact object without its model.
    const std::string no_model = error_of_text(R"({"base": "A1H", "impact": {"kappa0": 0.5}})");
    CHECK(contains(no_model, "impact.model"));
}

TEST_CASE("JSON: an unknown key is named, at the top, in impact and in an effect") {
    const std::string top = error_of_text(R"({"base": "A1H", "mass": 7})");
    CAPTURE(top);
    CHECK(contains(top, "unknown key 'mass'"));
    const std::string imp = error_of_text(R"({"base": "A1H", "impact": {"model": "H", "kappa2": 0.1}})");
    CAPTURE(imp);
    CHECK(contains(imp, "impact.kappa2"));
    // A Hunt-Crossley key given to a rigid law.
    CHECK(contains(error_of_text(R"({"base": "A1H", "impact": {"model": "H", "kI": 1e8}})"), "impact.kI"));
    const std::string eff =
        error_of_text(R"({"base": "A1H", "effects": [{"id": "constant_force", "F0": 1, "F1": 2}]})");
    CAPTURE(eff);
    CHECK(contains(eff, "effects[0].F1"));
}

TEST_CASE("JSON: a wrong type is named") {
    const std::string s = error_of_text(R"({"base": "A1H", "m": "heavy"})");
    CAPTURE(s);
    CHECK(contains(s, "'m'"));
    CHECK(contains(s, "number"));
    CHECK(contains(error_of_text(R"({"base": "A1H", "a": 5})"), "'a'"));
    CHECK(contains(error_of_text(R"({"base": "A1H", "a": [1, "x"]})"), "a[1]"));
    CHECK(contains(error_of_text(R"({"base": "A1H", "a": [1, 2, 3, 4, 5]})"), "'a'"));
    CHECK(contains(error_of_text(R"({"base": "A1H", "b": []})"), "'b'"));
    CHECK(contains(error_of_text(R"({"base": 7})"), "'base'"));
    CHECK(contains(error_of_text(R"({"base": "A1H", "name": 3})"), "'name'"));
    CHECK(contains(error_of_text(R"({"base": "A1H", "impact": "H"})"), "'impact'"));
    CHECK(contains(error_of_text(R"({"base": "A1H", "impact": {"model": "H", "Ti0": true}})"), "impact.Ti0"));
    CHECK(contains(error_of_text(R"({"base": "A1H", "effects": {"id": "constant_force"}})"), "'effects'"));
    CHECK(contains(error_of_text(R"({"base": "A1H", "effects": [{"F0": 1}]})"), "effects[0]"));
    CHECK(contains(error_of_text(R"({"base": "A1H", "xI": null})"), "'xI'"));
}

// nlohmann-json has no NaN or Infinity literals: a non-finite number in a file is an overflowing literal.
// Its parser throws json::out_of_range (406) for it, not json::parse_error.
TEST_CASE("JSON: non-finite numbers are refused as a ParamError naming the file and the key") {
    struct Case {
        const char* text;
        const char* key;
    };
    const Case cases[] = {
        {R"({"base": "A1H", "k": 1e999})", "'k'"},
        {R"({"base": "A1H", "impact": {"model": "H", "a_T": -1e999}})", "impact.a_T"},
        {R"({"base": "A1H", "b": [1e400]})", "b[0]"},
    };
    for (const auto& c : cases) {
        const std::string text = c.text;
        CAPTURE(text);
        std::string msg;
        try {
            params_from_json_text(c.text, "inf.json");
            FAIL("accepted a non-finite number");
        } catch (const ParamError& e) {
            msg = e.what();
        } catch (const std::exception& e) {
            FAIL_CHECK("not a ParamError: " << std::string(e.what()));
            continue;
        }
        CAPTURE(msg);
        CHECK(contains(msg, "inf.json"));
        CHECK(contains(msg, c.key));
    }
}

TEST_CASE("JSON: values out of range are refused, naming the key") {
    const std::string mass = error_of_text(R"({"base": "A1H", "m": -2})");
    CAPTURE(mass);
    CHECK(contains(mass, "'m'"));
    CHECK(contains(mass, "[0.001, 10000] kg"));
    const std::string kappa = error_of_text(R"({"base": "A1H", "impact": {"model": "H", "kappa0": 1.3}})");
    CAPTURE(kappa);
    CHECK(contains(kappa, "impact.kappa0"));
    CHECK(contains(kappa, "[0, 1]"));
    CHECK(contains(error_of_text(R"({"base": "A1G", "impact": {"model": "G", "kappa1": 1.01}})"), "impact.kappa1"));
    CHECK(contains(error_of_text(R"({"base": "A1H", "c": -0.1})"), "'c'"));
    CHECK(contains(error_of_text(R"({"base": "A1H", "eps": 0})"), "'eps'"));
    CHECK(contains(error_of_text(R"({"base": "A1H", "xI": 1.0})"), "'xI'"));
    CHECK(contains(error_of_text(R"({"base": "A1C", "impact": {"model": "C", "kI": -5}})"), "impact.kI"));
}

TEST_CASE("JSON: magnitudes that stalled the integrator are refused with the key and the range") {
    struct Case { const char* text; const char* key; const char* why; };
    const Case cases[] = {
        {R"({"base": "A1G", "m": 1e-20})", "'m'", "[0.001, 10000] kg"},
        {R"({"base": "A1G", "m": 1e-12})", "'m'", "[0.001, 10000] kg"},
        {R"({"base": "A1H", "eps": 1e-300})", "'eps'", "[1e-09, 0.01] m/s"},
        {R"({"base": "A1H", "eps": 1e-20})", "'eps'", "[1e-09, 0.01] m/s"},
        {R"({"base": "A1C1", "impact": {"model": "C1", "b": 1e308}})", "impact.b", "[0, 10000]"},
        {R"({"base": "A1C", "impact": {"model": "C", "n2": 1e-12}})", "impact.n2", "[1, 3]"},
        {R"({"base": "A1H", "effects": [{"id": "stribeck_friction", "Fs": 1e308, "vs": 0.01}]})", "effects.stribeck_friction",
         "no law on the rig exceeds"},
        {R"({"base": "A1H", "effects": [{"id": "unexplained_phi", "a1": 0, "b1": 0, "a2": 0, "b2": 9e18, "a3": 0, "b3": 0}]})", "effects.unexplained_phi",
         "no law on the rig exceeds"},
        {R"({"base": "A1H", "a": [1e12]})", "'a'", "no law on the rig exceeds"},
        {R"({"base": "A1H", "m0e": 50})", "'m0e'", "[0, 10] kg m"},
    };
    for (const Case& c : cases) {
        const std::string msg = error_of_text(c.text);
        CAPTURE(c.text);
        CAPTURE(msg);
        CHECK(contains(msg, c.key));
        CHECK(contains(msg, c.why));
    }
    // The edges of the ranges are accepted.
    CHECK_NOTHROW(params_from_json_text(R"({"base": "A1H", "m": 0.001, "eps": 1e-9})", "edge.json"));
    CHECK_NOTHROW(params_from_json_text(R"({"base": "A1C", "impact": {"model": "C", "n1": 3, "n3": 2}})", "edge.json"));
}

TEST_CASE("JSON: unknown impact model, base version and effect id are named") {
    const std::string im = error_of_text(R"({"base": "A1H", "impact": {"model": "Z"}})");
    CAPTURE(im);
    CHECK(contains(im, "impact.model"));
    CHECK(contains(im, "'Z'"));
    const std::string base = error_of_text(R"({"base": "B7"})");
    CAPTURE(base);
    CHECK(contains(base, "'base'"));
    CHECK(contains(base, "B7"));
    const std::string eff = error_of_text(R"({"base": "A1H", "effects": [{"id": "warp_drive"}]})");
    CAPTURE(eff);
    CHECK(contains(eff, "effects[0].id"));
    CHECK(contains(eff, "warp_drive"));
}

TEST_CASE("JSON: the base override form") {
    const Params p = params_from_json_text(
        R"({"base": "A1C1", "m": 7.5, "xI": -0.002, "impact": {"model": "C1", "b": 0.5},
            "effects": [{"id": "constant_force", "F0": 0.25}]})",
        "over.json");
    const Params base = make_version("A1C1");
    CHECK(p.name == "A1C1*");   // a base without a name is marked as modified
    CHECK(p.m == 7.5);
    CHECK(p.xI == -0.002);
    CHECK(p.k == base.k);
    CHECK(p.a == base.a);
    CHECK(p.impact == base.impact);
    CHECK(impact_param(p, "b") == 0.5);
    CHECK(impact_param(p, "kI") == impact_param(base, "kI"));   // untouched law parameters stay
    REQUIRE(p.effects.size() == 1);
    CHECK(p.effects[0].p[0] == 0.25);
    // A file that switches the law must give each of the new law's parameters.
    const std::string sw = error_of_text(R"({"base": "A1C", "impact": {"model": "G", "kappa0": 0.5}})");
    CAPTURE(sw);
    CHECK(contains(sw, "missing key 'impact.kappa1'"));
    // "a" given with fewer coefficients: the rest are zero.
    const Params q = params_from_json_text(R"({"base": "A3H", "name": "mine", "a": [-1900]})", "a.json");
    CHECK(q.name == "mine");
    CHECK(q.a[0] == -1900.0);
    CHECK(q.a[1] == 0.0);
    CHECK(q.b == make_version("A3H").b);
}

TEST_CASE("JSON: save and load round-trip exactly, for every version and with effects") {
    for (const auto& name : version_names()) {
        Params p = make_version(name);
        p.xI = -1.234567890123e-3;
        p.m0e = 0.1 / 3.0;
        if (name == "A3C1") {
            add_effect(p, "quadratic_damping").p[0] = 1.0 / 7.0;
            add_effect(p, "constant_force").p[0] = -0.3;
        }
        const auto path = temp_path(name + ".json");
        save_params(p, path.string());
        const Params q = load_params(path.string());
        std::filesystem::remove(path);
        CAPTURE(name);
        CHECK(q.name == p.name);
        CHECK(q.stiffness_id == p.stiffness_id);
        CHECK(q.m == p.m);
        CHECK(q.m0e == p.m0e);
        CHECK(q.k == p.k);
        CHECK(q.c == p.c);
        CHECK(q.T == p.T);
        CHECK(q.eps == p.eps);
        CHECK(q.a == p.a);
        CHECK(q.b == p.b);
        CHECK(q.xI == p.xI);
        CHECK(q.impact == p.impact);
        CHECK(q.ip == p.ip);
        REQUIRE(q.effects.size() == p.effects.size());
        for (std::size_t i = 0; i < p.effects.size(); ++i) {
            CHECK(q.effects[i].law == p.effects[i].law);
            CHECK(q.effects[i].p == p.effects[i].p);
        }
        // And the text itself is stable.
        CHECK(params_to_json_text(q) == params_to_json_text(p));
    }
}

TEST_CASE("JSON files: not found names the path; resolve_model takes names and .json paths") {
    const std::string missing = temp_path("does_not_exist.json").string();
    std::string msg;
    try {
        load_params(missing);
    } catch (const ParamError& e) {
        msg = e.what();
    }
    CAPTURE(msg);
    CHECK(contains(msg, missing));
    CHECK_THROWS_AS(resolve_model(missing), ParamError);
    CHECK(resolve_model("A3C1").name == "A3C1");
    CHECK_THROWS_AS(resolve_model("nonexistent"), ParamError);
    // A file with a parse error names itself.
    const auto bad = temp_path("bad.json");
    {
        std::ofstream out(bad);
        out << "{\"base\": \"A1H\", \"k\": }";
    }
    try {
        resolve_model(bad.string());
        FAIL("expected a ParamError");
    } catch (const ParamError& e) {
        CHECK(contains(e.what(), bad.string()));
        CHECK(contains(e.what(), "line 1"));
    }
    std::filesystem::remove(bad);
    // Saving into a missing directory names the path.
    const std::string nowhere = temp_path("no_such_dir/out.json").string();
    try {
        save_params(make_version("A1H"), nowhere);
        FAIL("expected a ParamError");
    } catch (const ParamError& e) {
        CHECK(contains(e.what(), nowhere));
    }
}

TEST_CASE("JSON: a directory given as a parameter file is named as such (not basic_filebuf::underflow)") {
    const auto dir = std::filesystem::temp_directory_path() / "impactlab_dir_model.json";
    std::filesystem::create_directories(dir);
    std::string msg;
    try {
        (void)load_params(dir.string());
    } catch (const ParamError& e) {
        msg = e.what();
    }
    std::filesystem::remove(dir);
    CAPTURE(msg);
    CHECK(contains(msg, "not a parameter file: is a directory"));
}
