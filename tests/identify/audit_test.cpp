// Cases from an adversarial audit of the measured-data loop (records the recovery matrix and the null check
// do not cover), each a failure once seen and fixed; 20 s records so each case stays within a few seconds.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "impactlab/identify.hpp"
#include "fit_cases.hpp"

namespace id = impactlab::identify;
using id::test::analyse;
using id::test::named;
using id::test::short_run;

namespace {


}  // namespace

TEST_CASE("audit: two force effects at once are both kept, whichever the validation tries first") {
    // Validated alone, a phase offset's per-fold refit soaks up the even stiffness not yet in the model and its
    // held-out fall looked too small; it was turned down for good, leaving a model 10x the noise. It is now
    // tried again once the even stiffness is in.
    id::Model truth = id::resolve_fit_model("A1G", id::Forcing::Unbalance);
    id::apply_effect(truth, "even_stiffness", {{"k2", 3000.0}});
    id::apply_effect(truth, "phase_offset", {{"delta", 0.05}});
    const id::FitReport r = analyse(truth, short_run(1), "A1G");
    CHECK(r.effects_found.size() == 2);
    CHECK(named(r, "even_stiffness"));
    CHECK(named(r, "phase_offset"));
    CHECK(r.validation_rms_after_m < 1.5 * r.sigma_x);
    CHECK(r.error_after.shooting_rms_1_m < 1.5 * r.sigma_x);
}

TEST_CASE("audit: a baseline fit never hands back parameters worse than those given, and keeps a real improvement") {
    // At 200 Hz the equation error's fit of the baseline is biased: it moved A1H's parameters to a model whose
    // shooting error was ten times the sensor noise, and handed that back. It must now beat the parameters
    // given on held-out windows, or they stay.
    const id::Model a1h = id::resolve_fit_model("A1H", id::Forcing::Unbalance);
    id::FitOptions fo;
    fo.plots = false;
    fo.fit_baseline = true;
    id::SynthOptions so = short_run(1);
    so.rate = 200.0;
    const id::MeasuredData coarse = id::synthesize(a1h, so);
    const id::FitReport r = id::run_fit(coarse, a1h, fo);
    CHECK(r.effects_found.empty());
    CHECK(r.after.p.c == a1h.p.c);
    CHECK(r.after.p.T == a1h.p.T);
    CHECK(r.after.p.k == a1h.p.k);
    CHECK(r.error_after.shooting_rms_1_m <= 1.01 * id::evaluate_model(coarse, a1h, fo).shooting_rms_1_m);
    // A3 data fitted from A1's parameters: the fitted baseline is far better than the one given, and stays.
    const id::MeasuredData a3 = id::synthesize(id::resolve_fit_model("A3H", id::Forcing::Unbalance), short_run(1));
    const id::FitReport r3 = id::run_fit(a3, a1h, fo);
    CHECK(r3.baseline == id::Baseline::Fit);
    CHECK(r3.error_after.shooting_rms_1_m < 0.1 * id::evaluate_model(a3, a1h, fo).shooting_rms_1_m);
}

TEST_CASE("audit: test rows of a chaotic record are judged within the predictability horizon, not by a free run") {
    // With the true effect found, the free run over a chaotic test part still ended further from the data than
    // the model without it (another trajectory, whatever the model): the only test error reported said the
    // model handed back was worse. The test rows' shooting error within the horizon says it is not.
    id::Model truth = id::resolve_fit_model("A1H", id::Forcing::Unbalance);
    id::apply_effect(truth, "constant_force", {{"F0", -0.05}});
    id::SynthOptions so;
    so.duration = 15.0;
    so.knot_omega = {16.0};
    const id::MeasuredData fit_part = id::synthesize(truth, so);
    so.x0 = -0.0105;
    so.seed = 2;
    const id::MeasuredData test_part = id::synthesize(truth, so);
    id::FitOptions fo;
    fo.plots = false;
    const id::FitReport r = id::run_fit(fit_part, id::resolve_fit_model("A1H", id::Forcing::Unbalance), fo, &test_part);
    REQUIRE(r.effects_found.size() == 1);
    CHECK(r.effects_found.front().id == "constant_force");
    REQUIRE(r.error_before.test_shooting_rms_m > 0);
    CHECK(r.error_after.test_shooting_rms_m < 0.3 * r.error_before.test_shooting_rms_m);
    CHECK(r.error_after.test_shooting_rms_m < 1.5 * r.sigma_x);
    const bool noted = std::any_of(r.notes.begin(), r.notes.end(), [](const std::string& n) { return n.find("drifts onto another") != std::string::npos; });
    CHECK(noted == (r.error_after.test_simulation_rms_m > r.error_before.test_simulation_rms_m));
    CHECK(id::report_json_text(r).find("test_shooting_rms_m") != std::string::npos);
}

TEST_CASE("audit: an impact-law effect kept is the one validated, refitted against the model it joins") {
    // A1G data analysed with A1C: the bumper offset turned down at first was kept on the second try with the
    // shift the impact stage had fitted against another model, not the one validated; the model handed back
    // simulated three times worse than the validation said (15.9 um against 5.1 um), with a shift that,
    // refitted, was 6 +/- 6 um.
    id::SynthOptions so = short_run(1);
    so.duration = 40.0;
    id::steps_profile({9.0, 16.0}, 19.0, 2.0, so.knot_t, so.knot_omega);
    const id::FitReport r = analyse(id::resolve_fit_model("A1G", id::Forcing::Unbalance), so, "A1C");
    REQUIRE_FALSE(r.effects_found.empty());
    for (const auto& f : r.effects_found) {
        CAPTURE(f.id);
        CHECK(f.evidence == id::Evidence::ImpactLaw);
        if (f.id == "bumper_offset") CHECK(std::abs(f.parameters.front().second) >= 5.0 * f.sigma.front().second);
    }
    CHECK(r.error_after.shooting_rms_1_m < 0.5 * r.error_before.shooting_rms_1_m);
    CHECK(r.error_after.shooting_rms_1_m < 1.5 * r.validation_rms_after_m);
}

TEST_CASE("audit: with a fitted baseline, the effects join the base parameters refitted with them") {
    // A left-well and a right-well run with an even stiffness, baseline fitted: the base parameters fitted
    // without the effect had bent the spring rate (k = 886 N/m for 1115) to absorb it, and the effect fitted
    // jointly with the base was then added to those stale values: 0.22 mm of shooting error (70x the noise),
    // where the given model with the effect reaches the noise.
    id::Model truth = id::resolve_fit_model("A1H", id::Forcing::Unbalance);
    truth.p.xI = 0.05;   // the bumper out of the way: the right well is free
    id::apply_effect(truth, "even_stiffness", {{"k2", 4000.0}});
    id::Model model = id::resolve_fit_model("A1H", id::Forcing::Unbalance);
    model.p.xI = 0.05;
    std::vector<id::MeasuredData> runs;
    for (double x0 : {-0.01, 0.01}) {
        id::SynthOptions so = short_run(x0 < 0 ? 1 : 2);
        so.x0 = x0;
        runs.push_back(id::synthesize(truth, so));
    }
    id::FitOptions fo;
    fo.plots = false;
    fo.fit_baseline = true;
    const id::FitReport r = id::run_fit(id::join_records(runs), model, fo);
    REQUIRE(r.effects_found.size() == 1);
    CHECK(r.effects_found.front().id == "even_stiffness");
    CHECK(r.after.p.k == doctest::Approx(truth.p.k).epsilon(0.01));
    CHECK(r.error_after.shooting_rms_1_m < 1.5 * r.sigma_x);
}

TEST_CASE("audit: a wrong cart mass is named as such, alone, with the mass within 3 sigma") {
    // Data made with m 5 % low read as sensor_gain + unexplained_x + viscous_damping, 3 % high as
    // unbalance_scale + phase_offset + unexplained_x + coulomb_friction: no candidate moved m (a force law
    // cannot take the acceleration). cart_mass is screened by the residual's m x'' column and validated.
    for (const double scale : {0.95, 1.03}) {
        CAPTURE(scale);
        id::Model truth = id::resolve_fit_model("A1H", id::Forcing::Unbalance);
        truth.p.m *= scale;
        const id::Model a1h = id::resolve_fit_model("A1H", id::Forcing::Unbalance);
        const id::FitReport r = analyse(truth, short_run(1), "A1H");
        REQUIRE(r.effects_found.size() == 1);
        const id::FoundEffect& f = r.effects_found.front();
        REQUIRE(f.id == "cart_mass");
        REQUIRE(f.parameters.size() == 1);
        REQUIRE(f.sigma.size() == 1);
        CHECK(std::abs(a1h.p.m + f.parameters.front().second - truth.p.m) <= 3.0 * f.sigma.front().second);
        CHECK(r.after.p.m == doctest::Approx(truth.p.m).epsilon(1e-3));
        CHECK(r.after.p.effects.empty());
        CHECK(r.validation_rms_after_m < 1.5 * r.sigma_x);
    }
}

TEST_CASE("audit: x read 3 ms late is a sensor delay, not a phase offset; undelayed data name none") {
    // A late sensor read as phase_offset + unexplained_phi: at one omega a lag is a phase offset -omega tau, but
    // across the steps the offset grows with omega, which a constant offset cannot follow. The record here is
    // made undelayed and x shifted by three samples against t and phi (not by the law being tested).
    const id::Model a1h = id::resolve_fit_model("A1H", id::Forcing::Unbalance);
    const id::MeasuredData d = id::synthesize(a1h, short_run(1));
    id::FitOptions fo;
    fo.plots = false;
    const id::FitReport r0 = id::run_fit(d, a1h, fo);
    CHECK_FALSE(named(r0, "sensor_delay"));
    CHECK(r0.effects_found.empty());
    const std::size_t lag = 3;   // samples at 1 kHz
    id::MeasuredData late = d;
    late.t.erase(late.t.begin(), late.t.begin() + lag);
    late.phi.erase(late.phi.begin(), late.phi.begin() + lag);
    late.line.erase(late.line.begin(), late.line.begin() + lag);
    late.x.resize(late.t.size());
    const id::FitReport r = id::run_fit(late, a1h, fo);
    REQUIRE(r.effects_found.size() == 1);
    const id::FoundEffect& f = r.effects_found.front();
    REQUIRE(f.id == "sensor_delay");
    CHECK(std::abs(f.parameters.front().second - 3e-3) <= 3.0 * f.sigma.front().second);
    CHECK(r.validation_rms_after_m < 1.5 * r.sigma_x);
}

TEST_CASE("audit: a curved sensor scale (x read as x + s x^2) is named sensor_curvature, not a gain error") {
    // 30 um at 15 mm: a sensor gain absorbs its linear part over a one-sided range and the equation error
    // reaches its floor, so only the curve itself may be named; the noise floor is claimed only with it.
    const id::Model a1h = id::resolve_fit_model("A1H", id::Forcing::Unbalance);
    id::SynthOptions so = short_run(11);
    so.duration = 40.0;
    id::steps_profile({9.0, 16.0}, 19.0, 2.0, so.knot_t, so.knot_omega);
    id::MeasuredData d = id::synthesize(a1h, so);
    for (double& x : d.x) x += 0.133 * x * x;
    id::FitOptions fo;
    fo.plots = false;
    const id::FitReport r = id::run_fit(d, a1h, fo);
    REQUIRE(r.effects_found.size() == 1);
    const id::FoundEffect& f = r.effects_found.front();
    CHECK(f.id == "sensor_curvature");
    CHECK(std::abs(f.parameters.front().second - 0.133) <= 3.0 * f.sigma.front().second);
    CHECK(r.error_after.shooting_rms_1_m < 1.25 * r.sigma_x);
    // Without the curve in the library the verdict must not claim the floor.
    fo.exclude = {"sensor_curvature"};
    const id::FitReport g = id::run_fit(d, a1h, fo);
    CHECK_MESSAGE(g.verdict.find("at its noise floor") == std::string::npos, g.verdict);
    CHECK(g.verdict.find("misses something") != std::string::npos);
}
