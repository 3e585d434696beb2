// The prescribed rotation: phi is the exact integral of omega, time_of_phase inverts it, next_knot.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "impactlab/drive.hpp"

using namespace impactlab;

namespace {

// int_{t0}^{t} omega by composite Simpson over a fine grid that has every knot as a node (exact for
// piecewise-linear omega up to rounding).
double integral_of_omega(const Drive& d, const std::vector<double>& knots, double t0, double t) {
    std::vector<double> nodes{t0};
    for (double k : knots)
        if (k > t0 && k < t) nodes.push_back(k);
    nodes.push_back(t);
    double sum = 0;
    for (std::size_t i = 0; i + 1 < nodes.size(); ++i) {
        const double a = nodes[i], b = nodes[i + 1];
        sum += (b - a) / 6.0 * (d.omega(a) + 4.0 * d.omega(0.5 * (a + b)) + d.omega(b));
    }
    return sum;
}

}  // namespace

TEST_CASE("constant drive: phi = phi0 + omega (t - t0), alpha = 0, no knots") {
    const Drive d(7.5, 2.0, 1.25);
    CHECK(d.omega(0.0) == 7.5);
    CHECK(d.omega(100.0) == 7.5);
    CHECK(d.alpha(3.0) == 0.0);
    CHECK(d.phi(2.0) == 1.25);
    CHECK(d.phi(6.0) == doctest::Approx(1.25 + 7.5 * 4.0).epsilon(1e-15));
    CHECK(d.phi(1.0) == doctest::Approx(1.25 - 7.5).epsilon(1e-15));   // before t0: the same line
    CHECK(d.time_of_phase(1.25 + 30.0) == doctest::Approx(6.0).epsilon(1e-15));
    CHECK(std::isinf(d.next_knot(2.0)));
    CHECK(std::isinf(d.next_knot(-5.0)) == false);   // t0 itself is a knot, ahead of -5
    CHECK(d.next_knot(-5.0) == 2.0);
    CHECK(d.t_begin() == 2.0);
    // A drive at rest never reaches a later phase.
    const Drive still(0.0);
    CHECK(still.time_of_phase(1.0) == std::numeric_limits<double>::infinity());
    CHECK_THROWS_AS(Drive(-1.0), std::invalid_argument);
    CHECK_THROWS_AS(Drive(std::nan("")), std::invalid_argument);
}

TEST_CASE("EF ramp: omega = 25.1 t / 2800, phi = 25.1 t^2 / 5600 exactly, then constant omega") {
    const Drive d = Drive::ef_ramp();
    const double a = 25.1 / 2800.0;
    for (double t : {0.0, 0.5, 13.0, 700.25, 1999.0, 2800.0}) {
        CAPTURE(t);
        CHECK(d.omega(t) == doctest::Approx(a * t).epsilon(1e-14));
        CHECK(d.phi(t) == doctest::Approx(0.5 * a * t * t).epsilon(1e-14));
        CHECK(d.alpha(t) == doctest::Approx(t < 2800.0 ? a : 0.0).epsilon(1e-14));
    }
    // After the ramp: constant 25.1 rad/s.
    CHECK(d.omega(3000.0) == doctest::Approx(25.1).epsilon(1e-14));
    CHECK(d.alpha(3000.0) == 0.0);
    CHECK(d.phi(3000.0) == doctest::Approx(0.5 * a * 2800.0 * 2800.0 + 25.1 * 200.0).epsilon(1e-14));
    CHECK(d.next_knot(0.0) == 2800.0);
    CHECK(d.next_knot(1000.0) == 2800.0);
    CHECK(std::isinf(d.next_knot(2800.0)));
    // Scaled ramp.
    const Drive s = Drive::ef_ramp(10.0, 100.0);
    CHECK(s.phi(100.0) == doctest::Approx(500.0).epsilon(1e-14));
}

TEST_CASE("piecewise-linear drive: phi is the exact integral of omega, time_of_phase its inverse") {
    const std::vector<double> t{1.0, 3.0, 3.5, 10.0, 12.0, 20.0};
    const std::vector<double> w{0.0, 8.0, 8.0, 20.0, 2.0, 5.0};
    const double phi0 = 0.75;
    const Drive d = Drive::piecewise_linear(t, w, phi0);
    // Before the first knot: omega constant (here 0), phi = phi0.
    CHECK(d.omega(0.0) == 0.0);
    CHECK(d.phi(0.5) == phi0);
    for (double tt = 1.0; tt <= 25.0; tt += 0.173) {
        CAPTURE(tt);
        const double expect = phi0 + integral_of_omega(d, t, 1.0, tt);
        CHECK(d.phi(tt) == doctest::Approx(expect).epsilon(1e-13));
        // omega is the linear interpolation through the knots.
        if (tt < 20.0) {
            std::size_t i = 0;
            while (t[i + 1] <= tt) ++i;
            const double lin = w[i] + (w[i + 1] - w[i]) * (tt - t[i]) / (t[i + 1] - t[i]);
            CHECK(d.omega(tt) == doctest::Approx(lin).epsilon(1e-13));
            CHECK(d.alpha(tt) == doctest::Approx((w[i + 1] - w[i]) / (t[i + 1] - t[i])).epsilon(1e-13));
        } else {
            CHECK(d.omega(tt) == 5.0);
        }
        // phi' = omega, by a central difference away from the knots.
        const double h = 1e-5;
        bool near_knot = false;
        for (double k : t) near_knot |= std::abs(tt - k) < 2 * h;
        if (!near_knot) CHECK((d.phi(tt + h) - d.phi(tt - h)) / (2 * h) == doctest::Approx(d.omega(tt)).epsilon(1e-7));
    }
    // time_of_phase inverts phi to 1e-12 s wherever omega > 0.
    double worst = 0;
    for (double tt = 1.001; tt <= 25.0; tt += 0.0371) {
        const double back = d.time_of_phase(d.phi(tt));
        worst = std::max(worst, std::abs(back - tt));
    }
    MESSAGE("time_of_phase(phi(t)) - t: worst " << worst << " s");
    CHECK(worst < 1e-12);
    // And phi(time_of_phase(phase)) = phase on a grid of phases, sections included.
    for (int n = 1; n < 60; ++n) {
        const double phase = 2 * std::numbers::pi * n * 0.5 + phi0;
        const double ts = d.time_of_phase(phase);
        CAPTURE(n);
        REQUIRE(std::isfinite(ts));
        CHECK(d.phi(ts) == doctest::Approx(phase).epsilon(1e-14));
    }
    // Knots.
    CHECK(d.next_knot(0.0) == 1.0);
    CHECK(d.next_knot(1.0) == 3.0);   // strictly after
    CHECK(d.next_knot(3.2) == 3.5);
    CHECK(d.next_knot(11.999) == 12.0);
    CHECK(d.next_knot(12.0) == 20.0);
    CHECK(std::isinf(d.next_knot(20.0)));
    CHECK(d.t_begin() == 1.0);
}

TEST_CASE("piecewise-linear drive rejects bad profiles") {
    CHECK_THROWS_AS(Drive::piecewise_linear({}, {}), std::invalid_argument);
    CHECK_THROWS_AS(Drive::piecewise_linear({0.0, 1.0}, {1.0}), std::invalid_argument);
    CHECK_THROWS_AS(Drive::piecewise_linear({0.0, 0.0}, {1.0, 2.0}), std::invalid_argument);
    CHECK_THROWS_AS(Drive::piecewise_linear({0.0, 1.0}, {1.0, -2.0}), std::invalid_argument);
    CHECK_THROWS_AS(Drive::piecewise_linear({0.0, 1.0}, {1.0, std::numeric_limits<double>::infinity()}),
                    std::invalid_argument);
}

TEST_CASE("time_of_phase of a phase reached at the end of a stop (omega = 0 at a knot) is finite") {
    // omega drops linearly to 0 at t = 2, stays 0 until t = 3, then rises again. phi(2) = phi(3) = 1.
    const Drive d = Drive::piecewise_linear({0.0, 2.0, 3.0, 4.0}, {1.0, 0.0, 0.0, 1.0});
    REQUIRE(d.phi(2.0) == doctest::Approx(1.0).epsilon(1e-15));
    REQUIRE(d.phi(3.0) == doctest::Approx(1.0).epsilon(1e-15));
    // phi first reaches 1 at t = 2 (documented: "the time at which phi reaches phase"); any time in [2, 3]
    // would be defensible, +inf is not.
    const double t = d.time_of_phase(1.0);
    CHECK(t >= 2.0);
    CHECK(t <= 3.0);
    // Just past the plateau the inverse is fine.
    CHECK(d.time_of_phase(1.0 + 1e-8) == doctest::Approx(3.0 + std::sqrt(2e-8)).epsilon(1e-12));
}
