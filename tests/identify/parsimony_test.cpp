// Named physics before curve fits: a generic smooth force is named only where no library effect, alone or
// with one other fitted jointly, explains as much within the scatter.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "fit_cases.hpp"
#include "impactlab/identify.hpp"

namespace id = impactlab::identify;
using id::test::analyse;
using id::test::named;
using id::test::short_run;

namespace {

bool generic(const id::FitReport& r) {
    return std::any_of(r.effects_found.begin(), r.effects_found.end(),
                       [&](const id::FoundEffect& f) { return f.id.rfind("unexplained", 0) == 0; });
}
double param(const id::FitReport& r, const std::string& effect, const std::string& p) {
    for (const auto& f : r.effects_found)
        if (f.id == effect)
            for (const auto& [k, v] : f.parameters)
                if (k == p) return v;
    return NAN;
}

}  // namespace

TEST_CASE("parsimony: a direction-dependent rolling resistance is a constant force plus Coulomb friction, not a function of v") {
    // Resistance 0.3 N stronger than the model's in each direction, and 0.2 N more towards -x: exactly
    // constant_force + coulomb_friction, which a smooth function of v alone also fits.
    id::Model truth = id::resolve_fit_model("A1H", id::Forcing::Unbalance);
    id::apply_effect(truth, "constant_force", {{"F0", -0.2}});
    id::apply_effect(truth, "coulomb_friction", {{"dT", 0.3}});
    const id::FitReport r = analyse(truth, short_run(3));
    CHECK(named(r, "constant_force"));
    CHECK(named(r, "coulomb_friction"));
    CHECK_FALSE(generic(r));
    CHECK(param(r, "constant_force", "F0") == doctest::Approx(-0.2).epsilon(0.05));
    CHECK(param(r, "coulomb_friction", "dT") == doctest::Approx(0.3).epsilon(0.05));
    CHECK(r.error_after.shooting_rms_1_m < 1.5 * r.sigma_x);
}

TEST_CASE("parsimony: a magnet offset is named magnet_offset, not a six-parameter function of x") {
    for (const double d : {3e-4, 1e-3}) {
        CAPTURE(d);
        id::Model truth = id::resolve_fit_model("A1G", id::Forcing::Unbalance);
        id::apply_effect(truth, "magnet_offset", {{"d", d}});
        const id::FitReport r = analyse(truth, short_run(5), "A1G");
        REQUIRE_FALSE(r.effects_found.empty());
        CHECK(r.effects_found.front().id == "magnet_offset");
        CHECK_FALSE(generic(r));
        CHECK(param(r, "magnet_offset", "d") == doctest::Approx(d).epsilon(0.05));
    }
}
