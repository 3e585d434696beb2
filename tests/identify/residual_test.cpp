// The equation error (core/src/identify/residual.cpp): on data the model made it sits at the noise floor;
// a force the model lacks shows in it as that force, averaged by the kernel; an effect's column is the
// residual's derivative in the effect's parameter.
#include <doctest/doctest.h>

#include <cmath>

#include "fit_cases.hpp"
#include "identify/internal.hpp"

namespace id = impactlab::identify;
namespace dt = impactlab::identify::detail;

TEST_CASE("residual: noise floor for the true model, the missing force otherwise, and the effect's column") {
    id::Model truth = id::resolve_fit_model("A1H", id::Forcing::Unbalance);
    id::apply_effect(truth, "constant_force", {{"F0", -0.3}});
    const id::MeasuredData data = id::synthesize(truth, id::test::short_run(7));
    const id::Model given = id::resolve_fit_model("A1H", id::Forcing::Unbalance);
    std::vector<std::string> notes;
    const dt::Prep pr = dt::prepare(data, given, id::FitOptions{}, notes);
    REQUIRE(pr.rows.size() > 100);

    std::vector<double> pw;
    Eigen::VectorXd r_true, r_given;
    dt::residual(pr, truth, r_true, pw);
    dt::residual(pr, given, r_given, pw);
    const double floor = truth.p.m * pr.sigma_x * pr.K.noise_gain;
    const double rms_true = std::sqrt(r_true.squaredNorm() / static_cast<double>(r_true.size()));
    CHECK(rms_true < 2.0 * floor);
    CHECK(rms_true > 0.5 * floor);
    // Without the force the residual is the force itself: m x'' - F_model = F0.
    CHECK(r_given.mean() == doctest::Approx(-0.3).epsilon(0.02));

    // The column of F0 is dR/dF0 with the sign of a regressor (X = -dR/dp): R_given - F0 X = R_true.
    REQUIRE(truth.p.effects.size() == 1);
    Eigen::VectorXd X(r_given.size());
    dt::effect_column(pr, truth, truth.p.effects[0], 0, 1e-3, X, pw);
    CHECK(X.mean() == doctest::Approx(1.0).epsilon(1e-9));
    CHECK((r_given + 0.3 * X - r_true).cwiseAbs().maxCoeff() < 1e-9);
}

// A least-squares pass evaluates the residual through ResidualCache, which re-evaluates only the force effect
// whose parameters moved: its values must be residual()'s bit for bit, whatever moves (one effect, two, a
// sensor's map, a base parameter) and back.
TEST_CASE("residual: the cache of a least-squares pass gives residual()'s values bit for bit") {
    id::Model truth = id::resolve_fit_model("A1H", id::Forcing::Unbalance);
    id::apply_effect(truth, "constant_force", {{"F0", -0.3}});
    const id::MeasuredData data = id::synthesize(truth, id::test::short_run(7));
    for (const char* sensor : {"sensor_offset", "sensor_curvature"}) {
        CAPTURE(sensor);
        id::Model m = id::resolve_fit_model("A1H", id::Forcing::Unbalance);
        std::vector<std::string> notes;
        const dt::Prep pr = dt::prepare(data, m, id::FitOptions{}, notes);
        id::apply_effect(m, "constant_force", {{"F0", -0.2}});
        id::apply_effect(m, "quadratic_damping", {{"cq", 1.5}});
        id::apply_effect(m, sensor, {});
        REQUIRE(m.p.effects.size() == 3);
        std::vector<dt::Knob> knobs = {{&m.p.effects[0].p[0], 1e-3, -10, 10, "F0"},
                                       {&m.p.effects[1].p[0], 1e-3, 0, 100, "cq"},
                                       {&m.p.effects[2].p[0], 1e-6, -1, 1, sensor},
                                       {&m.p.k, 1e-3, 0, 1e5, "k"}};
        dt::ResidualCache cache(pr, m, knobs);
        std::vector<double> pw;
        Eigen::VectorXd r_cache, r_plain;
        // Each entry moves the knobs to these offsets from their starts (the steps of a Jacobian, a trial point).
        const std::vector<std::vector<double>> moves = {{0, 0, 0, 0},    {1e-3, 0, 0, 0}, {0, 0, 0, 0},    {0, 2e-3, 0, 0},
                                                        {0.1, 0.5, 0, 0}, {0.1, 0.6, 0, 0}, {0.1, 0.5, 1e-5, 0}, {0.1, 0.5, 1e-5, 3.0},
                                                        {0.2, 0.5, 1e-5, 3.0}, {0.2, 0.5, 1e-5, 3.0}};
        const std::vector<double> start = {m.p.effects[0].p[0], m.p.effects[1].p[0], m.p.effects[2].p[0], m.p.k};
        for (const auto& mv : moves) {
            for (std::size_t k = 0; k < knobs.size(); ++k) *knobs[k].value = start[k] + mv[k];
            cache.eval(r_cache);
            dt::residual(pr, m, r_plain, pw);
            REQUIRE(r_cache.size() == r_plain.size());
            CHECK((r_cache.array() == r_plain.array()).all());
        }
    }
}

TEST_CASE("residual: a record at rest or of noise alone is refused, saying which; a nanometre motion in metres is not") {
    const id::Model duffing = id::resolve_fit_model("duffing", id::Forcing::Input);
    auto record = [](double amplitude, double noise) {
        id::MeasuredData d;
        d.source = "rec.csv";
        unsigned s = 99;
        for (int i = 0; i < 4000; ++i) {
            const double t = i * 1e-3;
            s = s * 1664525u + 1013904223u;
            d.t.push_back(t);
            d.x.push_back(2.0 + amplitude * std::cos(60.0 * t) * std::exp(-0.5 * t) + noise * (static_cast<double>(s >> 8) / 16777216.0 - 0.5));
            d.u.push_back(0.0);
            d.line.push_back(i + 2);
        }
        d.free_run = true;
        return d;
    };
    std::vector<std::string> notes;
    auto refusal = [&](const id::MeasuredData& d) {
        try {
            (void)dt::prepare(d, duffing, id::FitOptions{}, notes);
        } catch (const id::DataError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(refusal(record(0.0, 0.0)).find("rec.csv: x does not move") != std::string::npos);
    CHECK(refusal(record(0.0, 1e-3)).find("the speed stays within the noise") != std::string::npos);
    // 3 nm swinging about 2 m, 3 pm of noise: its speeds, all below a rig's 1 um/s, still move.
    CHECK(refusal(record(3e-9, 3e-12)).empty());
    // A cart pushed along the rail (x = 0.4 t^2) never oscillates: no period of its own to judge a model over.
    id::MeasuredData pushed = record(0.0, 0.0);
    for (std::size_t i = 0; i < pushed.size(); ++i) pushed.x[i] = 0.4 * pushed.t[i] * pushed.t[i] + 1e-4 * std::sin(12345.678 * static_cast<double>(i));
    CHECK(refusal(pushed).find("rec.csv: the free run does not oscillate") != std::string::npos);
}
