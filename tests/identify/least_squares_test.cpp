// Ceres' bounded Levenberg-Marquardt over named knobs (core/src/identify/least_squares.cpp): a nonlinear fit
// reaches the truth, a bound holds, the Jacobian handed back is the forward-difference one; Huber loss does
// not yet keep an outlier from pulling the fit.
#include <doctest/doctest.h>

#include <cmath>

#include "identify/internal.hpp"

namespace dt = impactlab::identify::detail;

namespace {

// y = a exp(-b t) sampled at 50 points, with one outlier if asked.
struct Decay {
    double a = 1.0, b = 1.0;
    bool outlier = false;
    double operator()(Eigen::VectorXd& R) const {
        R.resize(50);
        for (int i = 0; i < 50; ++i) {
            const double t = 0.1 * i;
            double y = 3.0 * std::exp(-0.7 * t);
            if (outlier && i == 10) y += 5.0;
            R[i] = a * std::exp(-b * t) - y;
        }
        return R.squaredNorm();
    }
};

dt::StepFn relative_step() {
    return [](const dt::Knob& k, double v) { return std::max(std::abs(v) * 1e-7, k.step); };
}

}  // namespace

TEST_CASE("least_squares: a two-parameter decay is fitted exactly and its Jacobian is dR/dknob") {
    Decay f;
    std::vector<dt::Knob> knobs{{&f.a, 1e-8, -10, 10, "a"}, {&f.b, 1e-8, 0, 10, "b"}};
    Eigen::VectorXd R;
    Eigen::MatrixXd J;
    const dt::LsqSummary s = dt::least_squares(knobs, [&](Eigen::VectorXd& r) { return f(r); }, relative_step(), {}, R, &J);
    CHECK(f.a == doctest::Approx(3.0).epsilon(1e-6));
    CHECK(f.b == doctest::Approx(0.7).epsilon(1e-6));
    CHECK(s.final_cost < 1e-12);
    CHECK(s.final_cost < s.initial_cost);
    REQUIRE(J.rows() == 50);
    REQUIRE(J.cols() == 2);
    const double t = 0.1 * 20;
    CHECK(J(20, 0) == doctest::Approx(std::exp(-0.7 * t)).epsilon(1e-4));
    CHECK(J(20, 1) == doctest::Approx(-3.0 * t * std::exp(-0.7 * t)).epsilon(1e-4));
}

TEST_CASE("least_squares: a bound holds where the unbounded optimum lies beyond it") {
    Decay f;
    std::vector<dt::Knob> knobs{{&f.a, 1e-8, -10, 10, "a"}, {&f.b, 1e-8, 1.0, 10, "b"}};   // truth b = 0.7 < 1
    Eigen::VectorXd R;
    dt::least_squares(knobs, [&](Eigen::VectorXd& r) { return f(r); }, relative_step(), {}, R);
    CHECK(f.b == doctest::Approx(1.0));
    CHECK(R.squaredNorm() > 1e-3);
}

// The Huber option acts on each sample: one wild sample is down-weighted, not the summed square (a
// monotone map of the plain cost, with the same minimum).
TEST_CASE("least_squares: Huber loss keeps one outlier from pulling the fit") {
    Decay plain, robust;
    plain.outlier = robust.outlier = true;
    Eigen::VectorXd R;
    std::vector<dt::Knob> kp{{&plain.a, 1e-8, -10, 10, "a"}, {&plain.b, 1e-8, 0, 10, "b"}};
    dt::least_squares(kp, [&](Eigen::VectorXd& r) { return plain(r); }, relative_step(), {}, R);
    std::vector<dt::Knob> kr{{&robust.a, 1e-8, -10, 10, "a"}, {&robust.b, 1e-8, 0, 10, "b"}};
    dt::LsqOptions o;
    o.huber_delta = 0.1;
    o.max_iterations = 100;
    dt::least_squares(kr, [&](Eigen::VectorXd& r) { return robust(r); }, relative_step(), o, R);
    CHECK(std::abs(robust.a - 3.0) < 0.2 * std::abs(plain.a - 3.0));
    CHECK(robust.a == doctest::Approx(3.0).epsilon(0.01));
}
