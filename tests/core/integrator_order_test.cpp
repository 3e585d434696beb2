// The steppers' order of convergence against an exact solution (Boost.Odeint's practice): the error at a
// fixed time with steps h and h/2 falls by 2^p for a method of order p. A coefficient typo in RODAS4 or
// Dormand-Prince leaves every other test passing at tight tolerances and shows here as a lower order.
#include <doctest/doctest.h>

#include <cmath>

#include "impactlab/rosenbrock.hpp"

using impactlab::DenseStep;
using impactlab::Mat2;
using impactlab::Vec2;

namespace {

// x'' = -4 x + 3 cos t from x = 1, v = 0: exactly x = cos t, v = -sin t. The forcing makes the system
// non-autonomous, so RODAS4's df/dt term is exercised too.
struct Forced {
    Vec2 rhs(double t, const Vec2& y) const { return {y[1], -4.0 * y[0] + 3.0 * std::cos(t)}; }
    void jacobian(double t, const Vec2&, Mat2& J, Vec2& dfdt) const {
        J << 0.0, 1.0, -4.0, 0.0;
        dfdt << 0.0, -3.0 * std::sin(t);
    }
};
Vec2 exact(double t) { return {std::cos(t), -std::sin(t)}; }

constexpr double kEnd = 2.0;

// Error at kEnd of n fixed steps; `implicit`: RODAS4, else Dormand-Prince.
double global_error(int n, bool implicit) {
    const Forced sys;
    const double h = kEnd / n;
    Vec2 y = exact(0.0);
    Vec2 f = sys.rhs(0.0, y);
    DenseStep s;
    for (int i = 0; i < n; ++i) {
        const double t = i * h;
        if (implicit) {
            s.take(sys, t, y, h);
        } else {
            s.take_explicit(sys, t, y, h, f);
            f = s.f1;
        }
        y = s.y1;
    }
    return (y - exact(kEnd)).norm();
}

// The observed order between n and 2n steps.
double order(int n, bool implicit) { return std::log2(global_error(n, implicit) / global_error(2 * n, implicit)); }

// Local error of the dense output at the middle of one step of length h from the exact state.
double dense_error(double h) {
    const Forced sys;
    DenseStep s;
    s.take(sys, 0.3, exact(0.3), h);
    return (s.at(0.3 + 0.5 * h) - exact(0.3 + 0.5 * h)).norm();
}

}  // namespace

TEST_CASE("RODAS4 converges with order 4 on a forced linear oscillator") {
    for (int n : {20, 40, 80}) {
        CAPTURE(n);
        CHECK(order(n, true) == doctest::Approx(4.0).epsilon(0.08));
    }
    CHECK(global_error(160, true) < 1e-7);
}

TEST_CASE("Dormand-Prince converges with order 5 on the same problem") {
    for (int n : {10, 20, 40}) {
        CAPTURE(n);
        CHECK(order(n, false) == doctest::Approx(5.0).epsilon(0.08));
    }
}

TEST_CASE("RODAS4's dense output is third order: its local error at mid-step falls by about 2^4 per halving") {
    const double r = std::log2(dense_error(0.2) / dense_error(0.1));
    CHECK(r > 3.6);
    CHECK(r < 4.6);
}
