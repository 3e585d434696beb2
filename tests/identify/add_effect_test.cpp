// Adding a force effect is one file plus one registry line. This file plays the one file (a force law with
// its fit hint and its sentence, as in core/src/effects/) and the ScopedEffectLaw plays the registry line;
// nothing else is told of the effect, yet the catalogue lists it, a model takes it by name, synth
// simulates it and the fit screens, selects and estimates it.
#include <doctest/doctest.h>

#include <cmath>

#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"
#include "fit_cases.hpp"

namespace id = impactlab::identify;
using impactlab::EffectForce;
using impactlab::EffectLaw;
using impactlab::ForceContext;

namespace {

// A cubic drag, F = -c3 v^3 [N s^3/m^3]: a law the library does not have.
EffectForce cubic_drag(const double* p, const ForceContext& c) { return {-p[0] * c.v * c.v * c.v, 0.0, -3.0 * p[0] * c.v * c.v, 0.0}; }

std::string describe(const double* p, const double* s, const impactlab::EffectReportContext&) {
    return "a cubic drag, c3 = " + impactlab::effects::pm(p[0], s[0]) + " N s^3/m^3";
}

EffectLaw cubic_drag_law() {
    EffectLaw l{"test_cubic_drag", "a drag growing with the cube of the speed, -c3 v^3", {"c3", nullptr}, {"N s^3/m^3", nullptr}, {0.0},
                cubic_drag};
    l.fit = impactlab::effects::hint({0}, {10.0});
    l.describe = describe;
    return l;
}

}  // namespace

TEST_CASE("an effect added as one law and one registry entry is simulated, screened and found by the fit") {
    const std::size_t catalogue_before = id::effect_catalogue().size();
    CHECK(impactlab::find_effect("test_cubic_drag") == nullptr);
    {
        const impactlab::effects::ScopedEffectLaw added(cubic_drag_law());
        REQUIRE(impactlab::find_effect("test_cubic_drag") != nullptr);
        REQUIRE(id::find_catalogue_effect("test_cubic_drag") != nullptr);
        CHECK(id::effect_catalogue().size() == catalogue_before + 1);

        id::Model truth = id::resolve_fit_model("A1H", id::Forcing::Unbalance);
        id::apply_effect(truth, "test_cubic_drag", {{"c3", 200.0}});
        REQUIRE(truth.p.effects.size() == 1);
        const id::MeasuredData data = id::synthesize(truth, id::test::short_run(3));

        // Only the new effect is offered, so what is tested is that the fit sees it, not the library's choice.
        id::FitOptions fo;
        fo.plots = false;
        fo.only = {"test_cubic_drag"};
        const id::FitReport r = id::run_fit(data, id::resolve_fit_model("A1H", id::Forcing::Unbalance), fo);
        REQUIRE(r.effects_found.size() == 1);
        CHECK(r.effects_found[0].id == "test_cubic_drag");
        REQUIRE(r.effects_found[0].parameters.size() == 1);
        CHECK(r.effects_found[0].parameters[0].second == doctest::Approx(200.0).epsilon(0.05));
        CHECK(r.effects_found[0].sentence.rfind("a cubic drag, c3 = ", 0) == 0);
        CHECK(r.error_after.shooting_rms_1_m < 0.5 * r.error_before.shooting_rms_1_m);
    }
    CHECK(impactlab::find_effect("test_cubic_drag") == nullptr);
    CHECK(id::effect_catalogue().size() == catalogue_before);
}
