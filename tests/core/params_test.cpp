// Model versions as data: the registries, make_version, validate, impact parameters, effects.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "impactlab/params.hpp"

using namespace impactlab;

namespace {

// The message of the ParamError that f throws ("" if none).
template <class F>
std::string error_of(F&& f) {
    try {
        f();
    } catch (const ParamError& e) {
        return e.what();
    }
    return "";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("a stiffness law's kind is on its row: Table 1's on the rig, the plain Duffing law in data units") {
    CHECK(stiffness_kind(make_version("A1H")) == StiffnessKind::Rig);
    CHECK(stiffness_kind(make_version("A3none")) == StiffnessKind::Rig);
    Params d = make_version("A1none");
    d.stiffness_id = "duffing";
    CHECK(stiffness_kind(d) == StiffnessKind::DataUnits);
    for (const StiffnessSet& s : stiffness_sets()) CHECK(s.kind == StiffnessKind::Rig);   // no version is in data units
    REQUIRE(find_stiffness("duffing") == &duffing_stiffness());
}

TEST_CASE("make_version reads Table 1 and the impact tables (MODEL.md)") {
    const Params a1h = make_version("A1H");
    CHECK(a1h.name == "A1H");
    CHECK(a1h.stiffness_id == "A1");
    CHECK(a1h.m == 6.73766);
    CHECK(a1h.m0e == 0.025152);
    CHECK(a1h.k == 1115.2);
    CHECK(a1h.c == 12.373);
    CHECK(a1h.T == 1.2267);
    CHECK(a1h.eps == 1e-6);
    CHECK(a1h.a[0] == -1763.5);
    CHECK(a1h.a[1] == 0.0);
    CHECK(a1h.b[0] == 4907.6);
    CHECK(a1h.b[1] == 0.0);
    CHECK(a1h.xI == 0.0);
    REQUIRE(a1h.impact != nullptr);
    CHECK(std::string(a1h.impact->id) == "H");
    CHECK(a1h.rigid());
    CHECK(impact_param(a1h, "kappa0") == 0.6150);
    CHECK(impact_param(a1h, "kappa1") == 0.1350);
    CHECK(impact_param(a1h, "a_kappa") == 0.6594);
    CHECK(impact_param(a1h, "Ti0") == doctest::Approx(6.2193e-3).epsilon(1e-15));
    CHECK(impact_param(a1h, "Ti1") == doctest::Approx(4.0689e-3).epsilon(1e-15));
    CHECK(impact_param(a1h, "a_T") == 2.1733);

    const Params a3c = make_version("A3C");
    CHECK(a3c.m0e == 0.02476);
    CHECK(a3c.k == 1149.9);
    CHECK(a3c.c == 13.324);
    CHECK(a3c.T == 1.1002);
    CHECK(a3c.a[0] == -1982.3);
    CHECK(a3c.a[1] == -4.1578e6);
    CHECK(a3c.b[0] == 10578.0);
    CHECK(a3c.b[1] == -0.044258);
    CHECK_FALSE(a3c.rigid());
    CHECK(impact_param(a3c, "kI") == 2.3983e8);
    CHECK(impact_param(a3c, "b") == 0.8485);
    CHECK(impact_param(a3c, "n1") == 1.5);
    CHECK(impact_param(a3c, "n2") == 1.5);
    CHECK(impact_param(a3c, "n3") == 0.18667);

    const Params a1c1 = make_version("A1C1");   // not A1C + "1"
    CHECK(std::string(a1c1.impact->id) == "C1");
    CHECK(impact_param(a1c1, "kI") == 1e12);
    CHECK(impact_param(a1c1, "b") == 0.84208);
    CHECK(impact_param(a1c1, "n3") == 0.18619);

    const Params a1g = make_version("A1G");
    CHECK(impact_param(a1g, "kappa0") == 0.6242);
    CHECK(impact_param(a1g, "kappa1") == 0.0);
    CHECK(impact_param(a1g, "a_kappa") == 0.5061);
    CHECK(impact_param(a1g, "Ti0") == 0.0);
}

TEST_CASE("version_names: the paper's five first, then every XY combination, each valid") {
    const auto names = version_names();
    REQUIRE(names.size() == stiffness_sets().size() * impact_models().size());
    CHECK(names[0] == "A1C");
    CHECK(names[1] == "A1C1");
    CHECK(names[2] == "A3C");
    CHECK(names[3] == "A1G");
    CHECK(names[4] == "A1H");
    for (const auto& n : names) {
        CAPTURE(n);
        CHECK(std::count(names.begin(), names.end(), n) == 1);
        const Params p = make_version(n);
        CHECK(p.name == n);
        CHECK_NOTHROW(validate(p, n));
    }
    const std::string msg = error_of([] { make_version("A2H"); });
    CHECK(contains(msg, "A2H"));
    CHECK(contains(msg, "A1C1"));   // lists the known versions
    CHECK_THROWS_AS(make_version("A1"), ParamError);
    CHECK_THROWS_AS(make_version("A1X"), ParamError);
    CHECK_THROWS_AS(make_version(""), ParamError);
}

TEST_CASE("validate names the source and the key of every bad value") {
    struct Case {
        const char* key;
        void (*spoil)(Params&);
    };
    const Case cases[] = {
        {"'m'", [](Params& p) { p.m = 0.0; }},
        {"'m'", [](Params& p) { p.m = -1.0; }},
        {"'m0e'", [](Params& p) { p.m0e = -0.1; }},
        {"'k'", [](Params& p) { p.k = std::numeric_limits<double>::infinity(); }},
        {"'c'", [](Params& p) { p.c = -1.0; }},
        {"'T'", [](Params& p) { p.T = std::nan(""); }},
        {"'eps'", [](Params& p) { p.eps = 0.0; }},
        {"'a[1]'", [](Params& p) { p.a[1] = std::nan(""); }},
        {"'b[0]'", [](Params& p) { p.b[0] = -std::numeric_limits<double>::infinity(); }},
        {"'b'", [](Params& p) { p.b[0] = -1000.0; }},   // 1 - 1000 x^2 vanishes at |x| = 0.0316 m
        {"'xI'", [](Params& p) { p.xI = 0.5; }},
        {"'impact.kappa0'", [](Params& p) { set_impact_param(p, "kappa0", 1.2); }},
        {"'impact.kappa1'", [](Params& p) { set_impact_param(p, "kappa1", -0.1); }},
        {"'impact.a_kappa'", [](Params& p) { set_impact_param(p, "a_kappa", -1.0); }},
        {"'impact.Ti1'", [](Params& p) { set_impact_param(p, "Ti1", -1e-3); }},
        {"'impact.Ti0'", [](Params& p) { set_impact_param(p, "Ti0", 2.0); }},
    };
    for (const auto& c : cases) {
        Params p = make_version("A1H");
        c.spoil(p);
        const std::string msg = error_of([&] { validate(p, "my-source"); });
        const std::string key = c.key;
        CAPTURE(key);
        CAPTURE(msg);
        CHECK(contains(msg, "my-source"));
        CHECK(contains(msg, c.key));
    }
    const Case compliant[] = {
        {"'impact.kI'", [](Params& p) { set_impact_param(p, "kI", 0.0); }},
        {"'impact.b'", [](Params& p) { set_impact_param(p, "b", -0.5); }},
        {"'impact.n1'", [](Params& p) { set_impact_param(p, "n1", 0.5); }},
        {"'impact.n3'", [](Params& p) { set_impact_param(p, "n3", std::nan("")); }},
    };
    for (const auto& c : compliant) {
        Params p = make_version("A1C");
        c.spoil(p);
        const std::string msg = error_of([&] { validate(p, "src"); });
        CAPTURE(msg);
        CHECK(contains(msg, c.key));
    }
    Params none = make_version("A1H");
    none.impact = nullptr;
    CHECK(contains(error_of([&] { validate(none, "src"); }), "impact"));
}

TEST_CASE("validate: values inside their ranges that overflow the force law are refused, naming the key") {
    // A3's b = 1e308: the denominator is finite and positive, but its square (in the slope) is not, and
    // the run would stall on x = NaN.
    Params p = make_version("A3C");
    p.b[0] = 1e308;
    CHECK(error_of([&] { validate(p, "b.json"); }).find("b.json: key 'b': makes the denominator of F_SA overflow") == 0);
    p = make_version("A3C");
    p.b[3] = 1e300;
    CHECK(error_of([&] { validate(p, "b.json"); }).find("key 'b'") != std::string::npos);
    // Huge a: a force beyond any rig, or a slope that overflows.
    p = make_version("A3C");
    p.a[3] = 1e308;
    CHECK(error_of([&] { validate(p, "a.json"); }).find("key 'a'") != std::string::npos);
    CHECK(error_of([&] { validate(make_version("A3C"), "ok"); }).empty());
}

TEST_CASE("impact parameters by name; unknown names are refused") {
    Params p = make_version("A1G");
    set_impact_param(p, "kappa0", 0.5);
    CHECK(impact_param(p, "kappa0") == 0.5);
    CHECK(p.ip[0] == 0.5);
    const std::string msg = error_of([&] { impact_param(p, "kI"); });
    CHECK(contains(msg, "'kI'"));
    CHECK(contains(msg, "'G'"));
    CHECK_THROWS_AS(set_impact_param(p, "nope", 1.0), ParamError);
}

TEST_CASE("effects: the registry and add_effect") {
    CHECK(find_effect("constant_force") != nullptr);
    CHECK(find_effect("quadratic_damping") != nullptr);
    CHECK(find_effect("tangential_unbalance") != nullptr);
    CHECK(find_effect("no_such_effect") == nullptr);
    Params p = make_version("A1H");
    EffectInstance& e = add_effect(p, "constant_force");
    e.p[0] = 0.7;
    REQUIRE(p.effects.size() == 1);
    CHECK(p.effects[0].p[0] == 0.7);
    CHECK(p.effects[0].law == find_effect("constant_force"));
    const std::string msg = error_of([&] { add_effect(p, "gravity_well"); });
    CHECK(contains(msg, "gravity_well"));
    CHECK(contains(msg, "constant_force"));   // the known ones are listed
    p.effects[0].p[0] = std::nan("");
    CHECK(contains(error_of([&] { validate(p, "src"); }), "effects.constant_force.F0"));
}
