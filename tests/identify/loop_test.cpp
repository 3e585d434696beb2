// The loop of impactlab fit on synthetic records (20 s each, so the suite stays fast): every library effect
// is traced to itself and the simulation error falls at least fivefold; A1H data analysed with A1G trace to
// the finite impact duration; noise alone yields nothing; a force outside the library is located by the
// generic fit; the report is written.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>
#include <chrono>
#include <string>
#include <vector>
#include <utility>

#include "impactlab/identify.hpp"
#include "impactlab/simulator.hpp"
#include "fit_cases.hpp"

namespace id = impactlab::identify;
using id::test::analyse;
using id::test::short_run;
using impactlab::EffectForce;
using impactlab::EffectLaw;
using impactlab::ForceContext;

namespace {


id::Model a1h() { return id::resolve_fit_model("A1H", id::Forcing::Unbalance); }

// The part of a shooting error above the sensor noise: what the model gets wrong.
double excess(double rms, double sigma) { return std::sqrt(std::max(0.0, rms * rms - sigma * sigma)); }

double param(const id::FoundEffect& f, const std::string& name) {
    for (const auto& [n, v] : f.parameters)
        if (n == name) return v;
    FAIL("no parameter " << name);
    return 0;
}


struct Case {
    const char* id;
    std::vector<std::pair<std::string, double>> values;
    const char* check;   // parameter whose value is compared (first value given), or nullptr
};

}  // namespace

TEST_CASE("loop: every library effect is traced to itself and the error falls fivefold") {
    const std::vector<Case> cases{
        {"constant_force", {{"F0", -0.3}}, "F0"},
        {"quadratic_damping", {{"cq", 4.0}}, "cq"},
        {"magnet_offset", {{"d", 3e-4}}, "d"},
        {"even_stiffness", {{"k2", 3000.0}}, "k2"},
        {"linear_stiffness", {{"dk", 20.0}}, "dk"},
        {"viscous_damping", {{"dc", 1.5}}, "dc"},
        {"coulomb_friction", {{"dT", 0.3}}, "dT"},
        {"stribeck_friction", {{"Fs", 0.5}, {"vs", 0.02}}, "Fs"},
        {"phase_offset", {{"delta", 0.05}}, "delta"},
        {"unbalance_scale", {{"s", 0.05}}, "s"},
        {"sensor_offset", {{"o", 3e-4}}, "o"},
        {"sensor_gain", {{"g", 1.03}}, "g"},
        {"bumper_offset", {{"dx", 5e-4}}, "dx"},
        {"restitution", {{"kappa0", 0.4}}, "kappa0"},
        {"tangential_unbalance", {{"scale", 1.0}}, "scale"},
    };
    for (const Case& c : cases) {
        CAPTURE(std::string(c.id));
        id::Model truth = a1h();
        id::apply_effect(truth, c.id, c.values);
        id::SynthOptions so = short_run(7);
        // An impact-law effect is seen only at the impacts: the held-out check needs a score of them.
        if (std::string(c.id) == "restitution") {
            so.duration = 60.0;
            id::steps_profile({9.0, 16.0}, 29.0, 2.0, so.knot_t, so.knot_omega);
        }
        if (std::string(c.id) == "tangential_unbalance") {   // needs the motor to change speed
            so.knot_t.clear();
            so.knot_omega.clear();
            for (int k = 0; k <= 10; ++k) {
                so.knot_t.push_back(2.0 * k);
                so.knot_omega.push_back(k % 2 ? 18.0 : 8.0);
            }
        }
        const id::FitReport r = analyse(truth, so);
        REQUIRE_FALSE(r.effects_found.empty());
        CHECK(r.effects_found.front().id == c.id);
        CHECK(r.effects_found.front().explained_fraction > 0.1);
        CHECK(r.effects_found.front().z > 5.0);
        CHECK_FALSE(r.effects_found.front().sentence.empty());
        if (c.check) {
            const double truth_value = c.values.front().second;
            CHECK(param(r.effects_found.front(), c.check) == doctest::Approx(truth_value).epsilon(0.1));
        }
        const double before = excess(r.error_before.shooting_rms_1_m, r.sigma_x);
        const double after = excess(r.error_after.shooting_rms_1_m, r.sigma_x);
        CHECK(before >= 5.0 * after);
        CHECK(r.error_after.shooting_rms_10_m < r.error_before.shooting_rms_10_m);
        // Kept by the held-out check: it lowers the simulation error on data its parameters never saw.
        CHECK(r.effects_found.front().validation_gain > 0.0);
        CHECK(r.effects_found.front().validation_z >= 3.0);
        CHECK(r.validation_rms_after_m < r.validation_rms_before_m);
    }
}

TEST_CASE("loop: A1H data analysed with A1G trace to the finite impact duration") {
    id::SynthOptions so = short_run(7);
    so.duration = 60.0;
    id::steps_profile({9.0, 16.0}, 29.0, 2.0, so.knot_t, so.knot_omega);
    const id::FitReport r = analyse(a1h(), so, "A1G");
    REQUIRE_FALSE(r.effects_found.empty());
    CHECK(r.effects_found.front().id == "impact_duration");
    CHECK(param(r.effects_found.front(), "Ti0") == doctest::Approx(6e-3).epsilon(0.15));
    CHECK(r.error_after.impact.duration_rms_s < 0.2 * r.error_before.impact.duration_rms_s);
    CHECK(excess(r.error_before.shooting_rms_1_m, r.sigma_x) >= 5.0 * excess(r.error_after.shooting_rms_1_m, r.sigma_x));
}

TEST_CASE("loop: noise alone yields no effect on any version, and the model written is the model given") {
    // Every paper version and the other rigid combinations, a periodic and a chaotic plateau with impacts.
    for (const char* version : {"A1C", "A1C1", "A3C", "A1G", "A1H", "A3G", "A3H"}) {
        for (unsigned seed : {7u, 11u}) {
            CAPTURE(version);
            CAPTURE(seed);
            const id::Model truth = id::resolve_fit_model(version, id::Forcing::Unbalance);
            const id::FitReport r = analyse(truth, short_run(seed), version);
            CHECK(r.effects_found.empty());
            CHECK(r.after.p.name == truth.p.name);
            CHECK(r.after.p.effects.empty());
            CHECK(r.after.p.xI == truth.p.xI);
            CHECK(r.after.p.impact == truth.p.impact);
            CHECK(r.after.p.ip == truth.p.ip);
            CHECK(r.error_after.shooting_rms_1_m == doctest::Approx(r.error_before.shooting_rms_1_m));
            CHECK(r.error_before.shooting_rms_1_m < 2.0 * r.sigma_x);
        }
    }
}

TEST_CASE("loop: a model with a force it lacks is never handed back worse (an injected false candidate is turned down)") {
    // Analyse A1H noise with a library restricted to one candidate and a threshold so low that the residual
    // stage proposes it: the held-out simulation error must turn it down.
    const id::MeasuredData d = id::synthesize(a1h(), short_run(13));
    id::FitOptions fo;
    fo.plots = false;
    fo.z_threshold = 0.0;
    fo.min_gain = 0.0;
    fo.generic = false;
    fo.only = {"quadratic_damping", "constant_force", "even_stiffness"};
    const id::FitReport r = id::run_fit(d, a1h(), fo);
    CHECK(r.effects_found.empty());
    CHECK_FALSE(r.effects_rejected.empty());
    for (const auto& e : r.effects_rejected) CHECK_FALSE(e.reason.empty());
    CHECK(r.after.p.effects.empty());
    CHECK(r.validation_rms_after_m == doctest::Approx(r.validation_rms_before_m));
}

namespace {
// A force the library does not know: a bump in the rail around x0 = -8 mm, 0.4 N high, 2 mm wide.
EffectForce rail_bump(const double* p, const ForceContext& c) {
    const double u = (c.x - p[1]) / p[2], g = p[0] * std::exp(-u * u);
    return {g, -2.0 * u / p[2] * g, 0.0, 0.0};
}
const EffectLaw kRailBump{"rail_bump", "a bump in the rail", {"A", "x0", "w", nullptr}, {"N", "m", "m", nullptr},
                          {0.4, -0.008, 0.002}, rail_bump};
}  // namespace

TEST_CASE("loop: a force outside the library is located by the generic fit") {
    id::Model truth = a1h();
    truth.p.effects.push_back({&kRailBump, kRailBump.defaults});
    const id::FitReport r = analyse(truth, short_run(5));
    REQUIRE_FALSE(r.effects_found.empty());
    // A generic force of x, over the whole travel or on the bump's feature: which of the two explains more of a
    // bump 2 mm wide is a near tie that the last bits of libm decide; both locate it in x.
    const std::string& first = r.effects_found.front().id;
    CHECK((first == "unexplained_x" || first == "unexplained_x_local"));
    CHECK(r.effects_found.front().explained_fraction > 0.5);
    CHECK(r.error_after.residual_rms_N < 0.5 * r.error_before.residual_rms_N);
    CHECK(r.error_after.shooting_rms_1_m < 0.5 * r.error_before.shooting_rms_1_m);
}

TEST_CASE("loop: the report holds what scripts read, and the model file loads") {
    id::Model truth = a1h();
    id::apply_effect(truth, "constant_force", {{"F0", -0.3}});
    const id::MeasuredData d = id::synthesize(truth, short_run(3));
    id::FitOptions fo;
    const id::FitReport r = id::run_fit(d, a1h(), fo);
    const auto dir = std::filesystem::temp_directory_path() / "impactlab_fit_report_test";
    std::filesystem::remove_all(dir);
    id::write_report(r, dir.string(), true);
    for (const char* f : {"report.json", "report.md", "model_after.json", "residual_x.png", "residual_v.png", "residual_phi.png",
                          "x_t.png"})
        CHECK(std::filesystem::exists(dir / f));
    std::ifstream in(dir / "report.json");
    const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const char* key : {"\"effects_found\"", "\"explained_fraction\"", "\"parameters\"", "\"sentence\"", "\"error_before\"",
                            "\"error_after\"", "\"residual_rms_N\"", "\"shooting_rms_1_m\"", "\"shooting_rms_10_m\"",
                            "\"constant_force\"", "\"gate\"", "\"passed\"", "\"remainder\"", "\"data_horizon\"",
                            "\"shooting_rms_judge_m\""})
        CHECK(json.find(key) != std::string::npos);
    // The markdown says how the gate decided and prints the errors it compared.
    std::ifstream md_in(dir / "report.md");
    const std::string md((std::istreambuf_iterator<char>(md_in)), std::istreambuf_iterator<char>());
    CHECK(md.find("## The final gate") != std::string::npos);
    CHECK(md.find("Passed: added constant_force") != std::string::npos);
    CHECK(md.find("the model given") != std::string::npos);
    CHECK(r.gate.empty());
    CHECK(r.gate_passed.rfind("added constant_force", 0) == 0);
    const id::Model after = id::resolve_fit_model((dir / "model_after.json").string(), id::Forcing::Unbalance);
    REQUIRE(after.p.effects.size() == 1);
    CHECK(after.p.effects[0].p[0] == doctest::Approx(-0.3).epsilon(0.05));
    // Evaluating the model from the file reproduces the loop's "after" errors.
    const id::ErrorSummary e = id::evaluate_model(d, after, fo);
    CHECK(e.residual_rms_N == doctest::Approx(r.error_after.residual_rms_N).epsilon(1e-3));
    CHECK(e.shooting_rms_1_m == doctest::Approx(r.error_after.shooting_rms_1_m).epsilon(1e-3));
    std::filesystem::remove_all(dir);
}

TEST_CASE("synth: exact stops, noise and quantisation as asked") {
    id::SynthOptions so = short_run(1);
    so.duration = 2.0;
    const id::MeasuredData d = id::synthesize(a1h(), so);
    REQUIRE(d.size() == 2001);
    CHECK(d.t[1] == doctest::Approx(1e-3));
    for (double x : d.x) CHECK(std::abs(x / 1e-6 - std::round(x / 1e-6)) < 1e-6);
    const double q = 2 * 3.141592653589793 / 4096;
    for (double p : d.phi) CHECK(std::abs(p / q - std::round(p / q)) < 1e-6);
    CHECK(d.meta.at("model") == "A1H");
}

TEST_CASE("recovery matrix (subset): an effect injected into a compliant and a rigid version is named first, within 3 sigma") {
    // The whole matrix is `impactlab recovery` (README); here a friction and a bumper effect on
    // A1C1 (a compliant bumper with its flat tops) and A1G.
    for (const char* version : {"A1C1", "A1G"}) {
        for (const auto& c : id::recovery_cases({version})) {
            if (c.effect != "stribeck_friction" && c.effect != "bumper_offset") continue;
            CAPTURE(version);
            CAPTURE(c.effect);
            const id::RecoveryResult r = id::run_recovery(c, 40.0, 3);
            CHECK(r.first == c.effect);
            CHECK(r.within);
            CHECK(r.rms_after_m < 0.5 * r.rms_before_m);
        }
    }
}

TEST_CASE("recovery matrix (subset): a sensor offset and a magnet offset are findings, their shapes resolved") {
    // On 60 s of clean data a generic force of x beside either stands out of the noise on a remainder of
    // 0.1-0.2 % of the equation error they leave: no other shape, so the law is named and is a finding.
    for (const auto& [version, effect] : {std::pair<const char*, const char*>{"A1H", "sensor_offset"}, {"A1G", "magnet_offset"}}) {
        for (const auto& c : id::recovery_cases({version})) {
            if (c.effect != effect) continue;
            CAPTURE(version);
            CAPTURE(c.effect);
            const id::RecoveryResult r = id::run_recovery(c, 60.0, 1);
            CHECK(r.first == c.effect);
            CHECK(r.named_first);   // not marked "its shape not resolved"
            CHECK(r.recovered());
        }
    }
}

TEST_CASE("duffing forced by u: noise alone yields nothing, the model written reproduces the fit through the core simulator") {
    // y'' + d y' + k y + k3 y^3 = gain u with a random-phase multisine u, simulated on the core Simulator
    // (a Drive with the sampled input, impact model "none"), noise on y.
    id::Model truth = id::resolve_fit_model("duffing", id::Forcing::Input);
    truth.p.k = 4.0e4;     // about 32 Hz
    truth.p.c = 20.0;
    truth.p.a[1] = 2.0e6;  // a hardening cubic
    truth.p.input_gain = 2000.0;   // y of about 10 mm against 0.1 mm of noise
    const double rate = 500.0, duration = 40.0;
    const auto n = static_cast<std::size_t>(duration * rate) + 1;
    std::vector<double> u(n, 0.0);
    for (int k = 1; k <= 40; ++k) {
        const double f = 0.5 * k, ph = std::fmod(1.7 * k * k, 6.283185307179586);
        for (std::size_t i = 0; i < n; ++i) u[i] += 0.05 * std::sin(6.283185307179586 * f * static_cast<double>(i) / rate + ph);
    }
    impactlab::Drive drive(0.0);
    drive.set_input(0.0, 1.0 / rate, u);
    impactlab::Simulator sim;
    impactlab::State s;
    id::MeasuredData d;
    d.source = "duffing-synth";
    std::mt19937_64 rng(5);
    std::normal_distribution<double> noise(0.0, 1e-4);
    for (std::size_t i = 0; i < n; ++i) {
        const double t = static_cast<double>(i) / rate;
        sim.advance(truth.p, drive, s, t);
        d.t.push_back(t);
        d.x.push_back(s.x + noise(rng));
        d.u.push_back(u[i]);
        d.line.push_back(static_cast<long>(i) + 2);
    }
    id::FitOptions fo;
    fo.plots = false;
    fo.fit_baseline = true;
    id::Model start = id::resolve_fit_model("duffing", id::Forcing::Input);
    start.p.k = 3.5e4;
    start.p.c = 15.0;
    start.p.input_gain = 1600.0;
    const id::FitReport r = id::run_fit(d, start, fo);
    CHECK(r.effects_found.empty());
    CHECK(r.after.p.input_gain == doctest::Approx(2000.0).epsilon(0.05));
    CHECK(r.after.p.k == doctest::Approx(4.0e4).epsilon(0.05));
    CHECK(r.after.p.impact->kind == impactlab::ImpactKind::None);
    CHECK_MESSAGE(r.verdict.find("at its noise floor") != std::string::npos, r.verdict);
    // The written model is the whole model: read back, it gives the same simulation error.
    const auto dir = std::filesystem::temp_directory_path() / "impactlab_duffing_report_test";
    std::filesystem::remove_all(dir);
    id::write_report(r, dir.string(), false);
    const id::Model back = id::resolve_fit_model((dir / "model_after.json").string(), id::Forcing::Input);
    CHECK(back.p.input_gain == doctest::Approx(r.after.p.input_gain));
    const id::ErrorSummary e = id::evaluate_model(d, back, fo);
    CHECK(e.simulation_rms_m == doctest::Approx(r.error_after.simulation_rms_m).epsilon(1e-3));
    CHECK(e.simulation_rms_m < 2e-4);
    std::filesystem::remove_all(dir);
}

TEST_CASE("several runs, one model: a left-well and a right-well run give both wells and their asymmetry") {
    // An even stiffness makes the wells differ; the bumper is moved out of the way so the right well is free.
    id::Model truth = a1h();
    truth.p.xI = 0.05;
    id::apply_effect(truth, "even_stiffness", {{"k2", 4000.0}});
    id::Model model = a1h();
    model.p.xI = 0.05;
    std::vector<id::MeasuredData> runs;
    for (double x0 : {-0.011, 0.011}) {
        id::SynthOptions so = short_run(x0 < 0 ? 21 : 22);
        so.x0 = x0;
        id::steps_profile({6.0, 8.0}, 9.0, 2.0, so.knot_t, so.knot_omega);
        runs.push_back(id::synthesize(truth, so));
        runs.back().source = x0 < 0 ? "left" : "right";
    }
    const id::MeasuredData both = id::join_records(runs);
    REQUIRE(both.run_starts.size() == 2);
    CHECK(both.t[both.run_starts[1]] == doctest::Approx(both.t[both.run_starts[1] - 1] + 1e-3));
    id::FitOptions fo;
    fo.plots = false;
    const id::FitReport r = id::run_fit(both, model, fo);
    CHECK(r.runs == 2);
    REQUIRE_FALSE(r.effects_found.empty());
    CHECK(r.effects_found.front().id == "even_stiffness");
    const double k2 = param(r.effects_found.front(), "k2");
    CHECK(std::abs(k2 - 4000.0) <= 3.0 * r.effects_found.front().sigma.front().second + 1e-9);
    const id::WellReport& w = r.wells_after;
    REQUIRE(w.wells.size() == 2);
    CHECK(w.run_wells == std::vector<std::string>{"left", "right"});
    // -k2 x^2 pulls both wells towards -x: the left one deepens, the right one gets shallower.
    CHECK(w.wells[0].depth > w.wells[1].depth);
    CHECK(w.depth_asym < 0);
    CHECK(w.sdepth_asym > 0);
    CHECK(std::abs(w.depth_asym) > 10 * w.sdepth_asym);
    // The symmetric baseline has equal wells.
    REQUIRE(r.wells_before.wells.size() == 2);
    CHECK(r.wells_before.depth_asym == doctest::Approx(0.0).epsilon(1e-9).scale(1e-3));
}

TEST_CASE("several runs: runs with different forcing or rates are refused, naming the run") {
    id::MeasuredData a = id::synthesize(a1h(), short_run(1)), b = a;
    a.source = "a.csv";
    b.source = "b.csv";
    b.u = b.phi;
    b.phi.clear();
    CHECK_THROWS_WITH_AS(id::join_records({a, b}), doctest::Contains("b.csv"), id::DataError);
    id::MeasuredData c = a;
    c.source = "c.csv";
    for (auto& t : c.t) t *= 2.0;
    CHECK_THROWS_WITH_AS(id::join_records({a, c}), doctest::Contains("c.csv: sample step"), id::DataError);
    CHECK_THROWS_AS(id::join_records({}), id::DataError);
}

TEST_CASE("fit session: stages in order, progress to 1, and a cancel stops the fit with FitCancelled") {
    const id::MeasuredData d = id::synthesize(a1h(), short_run(3));
    id::FitOptions fo;
    fo.plots = false;
    id::FitProgress progress;
    const id::FitReport r = id::run_fit(d, a1h(), fo, nullptr, &progress);
    CHECK(progress.fraction.load() == doctest::Approx(1.0));
    CHECK(progress.stage.load() == static_cast<int>(id::FitStage::Errors));
    for (int s = 0; s < static_cast<int>(id::FitStage::Count); ++s)
        CHECK(std::string(id::fit_stage_name(static_cast<id::FitStage>(s))) != "?");
    // Cancelled from another thread while it runs: it stops early, with nothing returned.
    id::FitProgress stop;
    std::thread watcher([&] {
        while (stop.stage.load() < static_cast<int>(id::FitStage::Baseline)) std::this_thread::yield();
        stop.cancel.store(true);
    });
    const auto t0 = std::chrono::steady_clock::now();
    CHECK_THROWS_AS(id::run_fit(d, a1h(), fo, nullptr, &stop), id::FitCancelled);
    watcher.join();
    CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < r.runtime_s + 1.0);
    CHECK(stop.fraction.load() < 1.0);
}

TEST_CASE("chaotic double well forced by u: the baseline is recovered, stays bistable, and nothing is invented") {
    // Holmes' forced double well x'' + 0.25 x' - x + x^3/L^2 = 0.3 L cos t (L = 10 mm): chaotic, crossing
    // between the wells. The baseline starts 20 % off and is fitted; the record cannot be free-run.
    id::Model truth = id::resolve_fit_model("duffing", id::Forcing::Input);
    truth.p.k = -1.0;
    truth.p.c = 0.25;
    truth.p.a[1] = 1e4;
    truth.p.input_gain = 0.003;
    id::SynthOptions so;
    so.rate = 20.0;
    so.duration = 600.0;
    so.noise = 1e-5;
    so.quantum = 0.0;
    so.x0 = 0.01;
    so.input_dt = 0.05;
    for (int i = 0; i <= 12000; ++i) so.input.push_back(std::cos(0.05 * i));
    so.knot_t = {0.0};
    so.knot_omega = {0.0};
    const id::MeasuredData d = id::synthesize(truth, so);
    int crossings = 0;
    for (std::size_t i = 1; i < d.size(); ++i) crossings += (d.x[i - 1] < 0) != (d.x[i] < 0);
    REQUIRE(crossings > 10);   // chaotic: it hops between the wells
    id::Model start = truth;
    start.p.k = -0.8;
    start.p.c = 0.2;
    start.p.a[1] = 8e3;
    start.p.input_gain = 0.0025;
    id::FitOptions fo;
    fo.plots = false;
    fo.fit_baseline = true;
    fo.fit_params = {"c", "k", "a3", "gain"};
    const id::FitReport r = id::run_fit(d, start, fo);
    CHECK(r.effects_found.empty());
    CHECK(r.after.p.k == doctest::Approx(-1.0).epsilon(0.02));
    CHECK(r.after.p.c == doctest::Approx(0.25).epsilon(0.05));
    CHECK(r.after.p.a[1] == doctest::Approx(1e4).epsilon(0.02));
    CHECK(r.after.p.input_gain == doctest::Approx(0.003).epsilon(0.02));
    CHECK(r.wells_after.wells.size() == 2);
    // The equation error is at its floor (within 1.7 times it: the floor is itself an estimate, and the ratio is
    // 1.53 with processor features masked, below 1.5 without); the verdict also asks the shooting error to be at the sensor
    // noise, which parameters 1-2 % off do not reach over a period of a chaotic record, and says so.
    CHECK(r.error_after.residual_rms_N <= 1.7 * r.noise_floor_N);
    CHECK_FALSE(r.verdict.empty());
    CHECK(r.horizon_periods > 0);
    // The same record with the input's polarity reversed: the gain comes out negative, nothing else changes.
    id::MeasuredData flipped = d;
    for (double& u : flipped.u) u = -u;
    const id::FitReport rf = id::run_fit(flipped, start, fo);
    CHECK(rf.effects_found.empty());
    CHECK(rf.after.p.input_gain == doctest::Approx(-0.003).epsilon(0.02));
    CHECK(rf.after.p.k == doctest::Approx(-1.0).epsilon(0.02));
}

TEST_CASE("fit refuses implausible positions with a hint, before any fitting") {
    id::SynthOptions so = short_run(5);
    so.duration = 4.0;
    id::MeasuredData d = id::synthesize(a1h(), so);
    id::FitOptions fo;
    fo.plots = false;
    // Millimetres read as metres: beyond the rail, with the --x-scale hint.
    id::MeasuredData mm = d;
    for (double& x : mm.x) x *= 1e3;
    std::string msg;
    try {
        id::run_fit(mm, a1h(), fo);
    } catch (const id::DataError& e) {
        msg = e.what();
    }
    CAPTURE(msg);
    CHECK(msg.find("beyond the rail's travel") != std::string::npos);
    CHECK(msg.find("--x-scale 1e-3") != std::string::npos);
    // A record that lives beyond the bumper (its sign flipped): another geometry, refused with the options.
    id::MeasuredData flipped = d;
    for (double& x : flipped.x) x = -x;
    msg.clear();
    try {
        id::evaluate_model(flipped, a1h(), fo);
    } catch (const id::DataError& e) {
        msg = e.what();
    }
    CAPTURE(msg);
    CHECK(msg.find("beyond the bumper at xI = 0") != std::string::npos);
    CHECK(msg.find("--xI") != std::string::npos);
    // The same flipped record is fine for a model without a bumper.
    CHECK_NOTHROW(id::evaluate_model(flipped, id::resolve_fit_model("A1none", id::Forcing::Unbalance), fo));
}
