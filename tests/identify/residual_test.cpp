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
