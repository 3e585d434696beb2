// The force laws of Eq. (1)-(3): equilibria and wells of A1/A3, slopes against finite differences, the
// potential against closed forms and quadrature, the bearing resistance and the unbalance.
#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "impactlab/forces.hpp"
#include "impactlab/params.hpp"

using namespace impactlab;

namespace {

// Bisection on a sign change of f over [a, b], to the last bit.
double bisect(const std::function<double(double)>& f, double a, double b) {
    double fa = f(a);
    REQUIRE(fa * f(b) < 0);
    for (int i = 0; i < 200; ++i) {
        const double m = 0.5 * (a + b);
        if (m <= a || m >= b) break;
        const double fm = f(m);
        if ((fm < 0) == (fa < 0)) {
            a = m;
            fa = fm;
        } else {
            b = m;
        }
    }
    return 0.5 * (a + b);
}

// Every root of F_SA on (0, 0.1] m, found by a scan plus bisection (F_SA is odd: the negative roots mirror).
std::vector<double> positive_roots(const Params& p) {
    std::vector<double> roots;
    const auto F = [&](double x) { return spring_magnet(p, x).F; };
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        const double a = 1e-7 + 0.1 * i / n, b = 1e-7 + 0.1 * (i + 1) / n;
        if (F(a) * F(b) < 0) roots.push_back(bisect(F, a, b));
    }
    return roots;
}

// Composite Simpson of F_SA on [0, x] (an independent check of the Gauss-Legendre potential).
double simpson_potential(const Params& p, double x) {
    const int n = 20000;
    const double h = x / n;
    double s = spring_magnet(p, 0).F + spring_magnet(p, x).F;
    for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * spring_magnet(p, i * h).F;
    return s * h / 3.0;
}

}  // namespace

TEST_CASE("A1: wells at +/-10.88 mm, 0.0163 J deep, ~11 rad/s, hilltop at x = 0") {
    const Params p = make_version("A1H");
    const auto roots = positive_roots(p);
    REQUIRE(roots.size() == 1);
    const double xw = roots[0];
    MESSAGE("A1 well at x = +/-" << xw * 1e3 << " mm");
    CHECK(std::abs(xw - 10.88e-3) < 0.01e-3);
    // Closed form: k + a1 / (1 + b2 x^2) = 0.
    CHECK(xw == doctest::Approx(std::sqrt((-p.a[0] / p.k - 1.0) / p.b[0])).epsilon(1e-12));
    // Odd force: the left well mirrors the right one.
    CHECK(std::abs(spring_magnet(p, -xw).F) < 1e-9);
    CHECK(spring_magnet(p, -xw).F == doctest::Approx(-spring_magnet(p, xw).F).epsilon(1e-12));

    const double stiff = spring_magnet(p, xw).dF;
    CHECK(stiff > 0);                                   // stable
    CHECK(spring_magnet(p, -xw).dF == doctest::Approx(stiff).epsilon(1e-12));
    CHECK(spring_magnet(p, 0.0).F == 0.0);
    CHECK(spring_magnet(p, 0.0).dF < 0);                // hilltop
    CHECK(spring_magnet(p, 0.0).dF == doctest::Approx(p.k + p.a[0]).epsilon(1e-12));

    const double depth = spring_magnet_potential(p, 0.0) - spring_magnet_potential(p, xw);
    const double w0 = std::sqrt(stiff / p.m);
    MESSAGE("A1 well depth " << depth << " J, small-oscillation frequency " << w0 << " rad/s");
    CHECK(depth == doctest::Approx(0.0163).epsilon(0.01).scale(0));   // within 1 %
    CHECK(w0 == doctest::Approx(11.0).epsilon(0.05).scale(0));
    // Both wells equally deep.
    CHECK(spring_magnet_potential(p, -xw) == doctest::Approx(spring_magnet_potential(p, xw)).epsilon(1e-12));
}

TEST_CASE("A3: two symmetric stable wells and a hilltop at x = 0") {
    const Params p = make_version("A3G");
    const auto roots = positive_roots(p);
    REQUIRE(roots.size() == 1);
    const double xw = roots[0];
    const double stiff = spring_magnet(p, xw).dF;
    const double depth = -spring_magnet_potential(p, xw);
    MESSAGE("A3 well at x = +/-" << xw * 1e3 << " mm, depth " << depth << " J, omega0 " << std::sqrt(stiff / p.m)
                                 << " rad/s");
    CHECK(std::abs(spring_magnet(p, xw).F) < 1e-9);
    CHECK(std::abs(spring_magnet(p, -xw).F) < 1e-9);
    CHECK(stiff > 0);
    CHECK(spring_magnet(p, 0.0).dF < 0);
    CHECK(depth > 0);
    // Plausibility: a well a few millimetres out, like A1's.
    CHECK(xw > 3e-3);
    CHECK(xw < 30e-3);
}

TEST_CASE("spring_magnet slope matches a central difference (A1, A3, all coefficients)") {
    Params p = make_version("A3H");
    p.a = {-1982.3, -4.1578e6, 3.0e9, -1.0e12};
    p.b = {10578.0, 2.0e6, 1.0e9, 3.0e12};
    for (const Params& q : {make_version("A1H"), make_version("A3H"), p}) {
        for (double x : {-0.03, -0.011, -0.002, 0.0, 0.001, 0.0105, 0.02, 0.05}) {
            const double h = 1e-7;
            const double fd = (spring_magnet(q, x + h).F - spring_magnet(q, x - h).F) / (2 * h);
            CAPTURE(x);
            CHECK(spring_magnet(q, x).dF == doctest::Approx(fd).epsilon(1e-6).scale(1.0));
        }
    }
}

TEST_CASE("spring_magnet_potential: closed form for A1, Simpson for A3, V(0) = 0") {
    const Params a1 = make_version("A1H");
    for (double x : {-0.04, -0.02, -0.01088, -0.003, 0.0, 0.005, 0.015, 0.03}) {
        // V(x) = k x^2/2 + a1/(2 b2) ln(1 + b2 x^2).
        const double exact = 0.5 * a1.k * x * x + a1.a[0] / (2 * a1.b[0]) * std::log1p(a1.b[0] * x * x);
        CAPTURE(x);
        CHECK(std::abs(spring_magnet_potential(a1, x) - exact) < 1e-12);
    }
    const Params a3 = make_version("A3H");
    for (double x : {-0.03, -0.01, 0.004, 0.02}) {
        CAPTURE(x);
        CHECK(std::abs(spring_magnet_potential(a3, x) - simpson_potential(a3, x)) < 1e-11);
    }
    CHECK(spring_magnet_potential(a3, 0.0) == 0.0);
}

TEST_CASE("bearing resistance F_R = c v + T v / sqrt(v^2 + eps^2) and its slope") {
    const Params p = make_version("A1H");
    CHECK(resistance(p, 0.0).F == 0.0);
    CHECK(resistance(p, 0.0).dF == doctest::Approx(p.c + p.T / p.eps).epsilon(1e-12));
    for (double v : {-1.0, -1e-3, -3e-6, 1e-6, 2e-5, 0.1, 2.0}) {
        const double expect = p.c * v + p.T * v / std::sqrt(v * v + p.eps * p.eps);
        CAPTURE(v);
        CHECK(resistance(p, v).F == doctest::Approx(expect).epsilon(1e-13));
        CHECK(resistance(p, -v).F == doctest::Approx(-expect).epsilon(1e-13));   // odd
        const double h = std::abs(v) * 1e-6;
        const double fd = (resistance(p, v + h).F - resistance(p, v - h).F) / (2 * h);
        CHECK(resistance(p, v).dF == doctest::Approx(fd).epsilon(1e-5));
    }
    // Far from v = 0 the dry part saturates at T.
    CHECK(resistance(p, 1.0).F == doctest::Approx(p.c + p.T).epsilon(1e-9));
}

TEST_CASE("unbalance forcing m0e omega^2 sin(phi)") {
    const Params p = make_version("A1G");
    CHECK(unbalance_force(p, 0.5 * std::numbers::pi, 10.0) == doctest::Approx(p.m0e * 100.0).epsilon(1e-15));
    CHECK(unbalance_force(p, 1.5 * std::numbers::pi, 10.0) == doctest::Approx(-p.m0e * 100.0).epsilon(1e-15));
    CHECK(std::abs(unbalance_force(p, 2 * std::numbers::pi, 7.0)) < 1e-15);
    CHECK(unbalance_force(p, 0.3, 12.0) == doctest::Approx(p.m0e * 144.0 * std::sin(0.3)).epsilon(1e-15));
}
