// Narrow features the library has no name for: a bump in the rail 2 mm wide. The residual shows it in a few
// bins of x; the local generic term puts its knots there, follows it to near the noise, and no named effect
// is claimed for it. A record without one shows no feature, so the local terms are never offered there.
// A spring rate that cycles in time is found at its period, followed by the cycling generic term, and named
// no drift.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"
#include "fit_cases.hpp"
#include "identify/internal.hpp"
#include "impactlab/identify.hpp"

namespace id = impactlab::identify;
using impactlab::EffectForce;
using impactlab::EffectLaw;
using impactlab::ForceContext;
using id::test::named;
using id::test::short_run;

namespace {

// A hill in the rail at x0, U = A exp(-((x - x0)/w)^2): F = -dU/dx (p: A [J], x0 [m], w [m]). Never screened.
EffectForce rail_bump(const double* p, const ForceContext& c) {
    const double u = (c.x - p[1]) / p[2], g = std::exp(-u * u);
    const double F = 2.0 * p[0] * u / p[2] * g;
    const double dF = 2.0 * p[0] / (p[2] * p[2]) * g * (1.0 - 2.0 * u * u);
    return {F, dF, 0.0, 0.0};
}

EffectLaw rail_bump_law() {
    return EffectLaw{"test_rail_bump", "a hill in the rail", {"A", "x0", "w", nullptr}, {"J", "m", "m", nullptr}, {0.0, 0.0, 1e-3},
                     rail_bump};
}

// The data prepared for the model m, with the features of m's residual located (what run_fit does first).
id::detail::Prep features_of(const id::MeasuredData& d, const id::Model& m) {
    std::vector<std::string> notes;
    id::FitOptions o;
    id::detail::Prep pr = id::detail::prepare(d, m, o, notes);
    Eigen::VectorXd R;
    std::vector<double> pw;
    id::detail::residual(pr, m, R, pw);
    id::detail::locate_features(pr, m, R);
    return pr;
}

}  // namespace

TEST_CASE("features: a 2 mm bump in the rail is followed by the local generic term, and nothing named is claimed") {
    const impactlab::effects::ScopedEffectLaw added(rail_bump_law());
    id::Model truth = id::resolve_fit_model("A1H", id::Forcing::Unbalance);
    const double x0 = -0.008, w = 0.001;
    id::apply_effect(truth, "test_rail_bump", {{"A", 1.2e-4}, {"x0", x0}, {"w", w}});
    const id::MeasuredData data = id::synthesize(truth, short_run(5));
    id::FitOptions fo;
    fo.plots = false;
    const id::FitReport r = id::run_fit(data, id::resolve_fit_model("A1H", id::Forcing::Unbalance), fo);
    CAPTURE(r.verdict);
    for (const auto& e : r.effects_found) CAPTURE(e.id);
    CHECK(named(r, "unexplained_x_local"));
    for (const auto& e : r.effects_found) CHECK(e.id.rfind("unexplained_", 0) == 0);
    CAPTURE(r.error_before.shooting_rms_1_m);
    CAPTURE(r.error_after.shooting_rms_1_m);
    MESSAGE("rail bump: 1-period shooting ", r.error_before.shooting_rms_1_m, " -> ", r.error_after.shooting_rms_1_m, " m, noise ",
            r.sigma_x);
    CHECK(r.error_after.shooting_rms_1_m < 0.3 * r.error_before.shooting_rms_1_m);
    CHECK(r.error_after.shooting_rms_1_m < 3.0 * r.sigma_x);
}

TEST_CASE("features: records without a narrow feature show none") {
    for (const char* version : {"A1H", "A1C", "A3G"}) {
        CAPTURE(version);
        const id::Model m = id::resolve_fit_model(version, id::Forcing::Unbalance);
        const id::MeasuredData d = id::synthesize(m, short_run(6));
        const id::detail::Prep pr = features_of(d, m);
        CHECK_FALSE(pr.x_feature.found());
        CHECK_FALSE(pr.v_feature.found());
        CHECK_FALSE(pr.cycle.found());
    }
}

namespace {
// A friction bump the library's Stribeck law does not have the shape of: -sign(v) Fb exp(-|v|/vs), smoothed
// at v = 0 like the model's dry friction (p: Fb [N], vs [m/s]). Never screened.
EffectForce exp_bump(const double* p, const ForceContext& c) {
    const double e = 1e-4, s2 = c.v * c.v + e * e, r = std::sqrt(s2), sg = c.v / r, dsg = e * e / (s2 * r);
    const double a = std::abs(c.v), g = std::exp(-a / p[1]);
    const double F = -p[0] * sg * g, dF = -p[0] * (dsg * g - sg * g * (c.v >= 0 ? 1.0 : -1.0) / p[1]);
    return {F, 0.0, dF, 0.0};
}
EffectLaw exp_bump_law() {
    return EffectLaw{"test_exp_bump", "a friction bump", {"Fb", "vs", nullptr}, {"N", "m/s", nullptr}, {0.0, 0.01}, exp_bump};
}
}  // namespace

// Its shape is not the library's Stribeck law, but its class is: a named Stribeck friction explains as much
// as the local generic term in v, so the named one is chosen, and it takes most of the error.
TEST_CASE("features: a friction bump near v = 0 of a shape the library lacks is named a Stribeck friction") {
    const impactlab::effects::ScopedEffectLaw added(exp_bump_law());
    id::Model truth = id::resolve_fit_model("A1H", id::Forcing::Unbalance);
    id::apply_effect(truth, "test_exp_bump", {{"Fb", 0.15}, {"vs", 0.01}});
    const id::MeasuredData data = id::synthesize(truth, short_run(5));
    id::FitOptions fo;
    fo.plots = false;
    const id::FitReport r = id::run_fit(data, id::resolve_fit_model("A1H", id::Forcing::Unbalance), fo);
    CAPTURE(r.verdict);
    CAPTURE(r.error_before.shooting_rms_1_m);
    CAPTURE(r.error_after.shooting_rms_1_m);
    REQUIRE(r.effects_found.size() == 1);
    CHECK(r.effects_found[0].id == "stribeck_friction");
    CHECK(r.error_after.shooting_rms_1_m < 0.4 * r.error_before.shooting_rms_1_m);
    // The shape it could not follow is not called noise.
    CHECK(r.verdict.find("misses something") != std::string::npos);
}

namespace {
// A spring rate that cycles: F = -dk sin(2 pi t / P) x (p: dk [N/m], P [s]). Never screened.
EffectForce cycling_k(const double* p, const ForceContext& c) {
    const double w = 2.0 * impactlab::effects::kPi / p[1], s = std::sin(w * c.t);
    return {-p[0] * s * c.x, -p[0] * s, 0.0, -p[0] * w * std::cos(w * c.t) * c.x};
}
EffectLaw cycling_k_law() {
    return EffectLaw{"test_cycling_k", "a spring rate that cycles", {"dk", "P", nullptr}, {"N/m", "s", nullptr}, {0.0, 1.0}, cycling_k};
}
double param(const id::FoundEffect& e, const std::string& name) {
    for (const auto& [n, v] : e.parameters)
        if (n == name) return v;
    return NAN;
}
}  // namespace

TEST_CASE("features: a spring rate cycling with a 5 s period is found at its period and followed, no drift named") {
    const impactlab::effects::ScopedEffectLaw added(cycling_k_law());
    id::Model truth = id::resolve_fit_model("A1H", id::Forcing::Unbalance);
    const double dk = 40.0, P = 5.0;   // 3.6 % of k
    id::apply_effect(truth, "test_cycling_k", {{"dk", dk}, {"P", P}});
    const id::MeasuredData data = id::synthesize(truth, short_run(5));
    const id::Model given = id::resolve_fit_model("A1H", id::Forcing::Unbalance);
    {
        const id::detail::Prep pr = features_of(data, given);
        REQUIRE(pr.cycle.found());
        CHECK(pr.cycle.period == doctest::Approx(P).epsilon(0.05));   // the grid's spacing at 5 s over 20 s
    }
    id::FitOptions fo;
    fo.plots = false;
    const id::FitReport r = id::run_fit(data, given, fo);
    CAPTURE(r.verdict);
    CAPTURE(r.error_before.shooting_rms_1_m);
    CAPTURE(r.error_after.shooting_rms_1_m);
    REQUIRE(r.effects_found.size() == 1);
    const id::FoundEffect& e = r.effects_found[0];
    CHECK(e.id == "unexplained_x_cycle");
    CHECK(param(e, "P") == doctest::Approx(P).epsilon(0.01));
    // -dk sin(w t) = -(a sin + b cos) at t0 = 0: a = dk, b = 0.
    CHECK(std::hypot(param(e, "a"), param(e, "b")) == doctest::Approx(dk).epsilon(0.1));
    CHECK(e.sentence.find("cycles in time") != std::string::npos);
    CHECK(r.error_after.shooting_rms_1_m < 0.3 * r.error_before.shooting_rms_1_m);
    CHECK(r.error_after.shooting_rms_1_m < 2.0 * r.sigma_x);
}
