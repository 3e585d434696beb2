// Periodic orbits and their monodromy: a linear forced oscillator against the closed form; impacting orbits
// of every impact version against finite differences of the map.
#include <doctest/doctest.h>

#include <Eigen/LU>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "analysis/tangent.hpp"
#include "impactlab/analysis.hpp"
#include "impactlab/params.hpp"

using namespace impactlab;
using namespace impactlab::analysis;

namespace {

// m x'' + c x' + k x = m0e omega^2 sin(omega t): no magnets, no dry friction, no bumper.
Params linear_oscillator() {
    Params p = make_version("A1none");
    p.a = {0, 0, 0, 0};
    p.b = {0, 0, 0, 0};
    p.T = 0;
    return p;
}

double max_rel_diff(const Mat2& A, const Mat2& B) {
    // Entries compared in the scaled variables (x / 1 cm, v / 0.1 m/s), relative to the largest.
    Mat2 D = Mat2::Zero();
    D(0, 0) = 1.0 / kXScale;
    D(1, 1) = 1.0 / kVScale;
    const Mat2 As = D * A * D.inverse(), Bs = D * B * D.inverse();
    return (As - Bs).cwiseAbs().maxCoeff() / std::max(1e-12, Bs.cwiseAbs().maxCoeff());
}

}  // namespace

TEST_CASE("analysis: Floquet multipliers of a linear forced oscillator match exp(A T)") {
    const Params p = linear_oscillator();
    const double omega = 9.0, T = 2 * std::numbers::pi / omega;
    const Orbit o = find_orbit(p, omega, Vec2(0.0, 0.0));
    REQUIRE(o.converged);
    // Closed form: eigenvalues of A = [[0, 1], [-k/m, -c/m]] give mu = exp(lambda T).
    const double zeta = p.c / (2 * p.m), wd = std::sqrt(p.k / p.m - zeta * zeta);
    const std::complex<double> mu(std::exp(-zeta * T) * std::cos(wd * T), std::exp(-zeta * T) * std::sin(wd * T));
    CHECK(std::abs(std::abs(o.floquet.mu[0]) - std::abs(mu)) < 1e-8);
    CHECK(std::abs(o.floquet.mu[0] - mu) < 1e-7);
    CHECK(std::abs(o.floquet.mu[0] - std::conj(o.floquet.mu[1])) < 1e-9);
    CHECK(o.floquet.stable);
    // The orbit itself: the steady response X sin(omega t - delta).
    const double F = p.m0e * omega * omega;
    const double den = std::hypot(p.k - p.m * omega * omega, p.c * omega);
    const double X = F / den, delta = std::atan2(p.c * omega, p.k - p.m * omega * omega);
    CHECK(o.y[0] == doctest::Approx(X * std::sin(-delta)).epsilon(1e-7));
    CHECK(o.y[1] == doctest::Approx(X * omega * std::cos(-delta)).epsilon(1e-7));
}

TEST_CASE("analysis: the monodromy of impacting orbits matches finite differences of the map") {
    const Tolerances tight = analysis_tolerances(1e-11);
    for (const char* name : {"A1C", "A1C1", "A1G", "A1H"}) {
        CAPTURE(name);
        const Params p = make_version(name);
        // omega = 16: the chaotic range, where orbits hit the bumper; any point of the attractor will do.
        Vec2 y0 = settle(p, 16.0, Vec2(left_well(p), 0.0), 30, analysis_tolerances(1e-9));
        MapResult r = poincare_map(p, 16.0, y0, 1, true, tight);
        for (int i = 0; i < 50 && r.impacts == 0; ++i) {
            y0 = r.y;
            r = poincare_map(p, 16.0, y0, 1, true, tight);
        }
        REQUIRE(r.impacts > 0);
        const Mat2 fd = monodromy_fd(p, 16.0, y0, 1, tight, 1e-6);
        // Rigid: the saltation matrices are exact, the tangent agrees to the map's own accuracy. Compliant:
        // the contact pieces are made consistent with the flow at their step ends (9e-6 for A1C, 3e-5 for
        // A1C1; 1e-4..2e-5 before, integrated along the dense output alone).
        CHECK(max_rel_diff(r.M, fd) < (p.rigid() ? 1e-5 : 1e-4));
    }
}

TEST_CASE("analysis: A1C's impacting period-1 multipliers at 16 rad/s do not depend on Newton's start") {
    // Each start converges through its own step sequence, so the steps straddle the deepest point of the
    // impact (v = 0, where the damping jumps) differently; the multipliers must not follow them.
    const Params p = make_version("A1C");
    const Vec2 y_star(-0.0181917787647, -0.106773006494);
    const Vec2 offsets[] = {Vec2(0, 0), Vec2(1e-4, 1e-3), Vec2(-2e-4, -1e-3), Vec2(5e-5, -2e-3), Vec2(-3e-5, 5e-4),
                            Vec2(3e-13, -7e-13)};
    std::vector<Orbit> found;
    for (const Vec2& d : offsets) {
        const Orbit o = find_orbit(p, 16.0, y_star + d);
        CAPTURE(d[0]);
        REQUIRE(o.converged);
        CHECK(o.impacts == 1);
        CHECK(scaled_norm(o.y - y_star) < 1e-7);
        found.push_back(o);
    }
    for (const Orbit& o : found) {
        CHECK(std::abs(o.floquet.mu[0] - found[0].floquet.mu[0]) < 1e-6 * std::abs(found[0].floquet.mu[0]));
        CHECK(std::abs(o.floquet.mu[1] - found[0].floquet.mu[1]) < 1e-6);
    }
    // And they are the map's: central differences at rtol 1e-12 give 1.8535655 (h = 1e-4 and 1e-5 agree to 1e-7).
    CHECK(found[0].floquet.mu[0].real() == doctest::Approx(1.8535655).epsilon(3e-5));
}

TEST_CASE("analysis: Newton started on a slow orbit's noise floor (multiplier -0.992) says converged, not stalled") {
    // A1H at 22.1973 rad/s, just above the period-1 doubling at 22.1473: started from where the simulator
    // settled (the visualiser's section point), the map's residual there is noise (1.1e-9 > 10 rtol) that
    // no step lowers, and Newton used to give up on an orbit it already stood on.
    const Params p = make_version("A1H");
    const Vec2 start(-0.010985787804280073, -0.10007011373026983);
    const Orbit o = find_orbit(p, 22.1973, start);
    CHECK(o.message == "");
    REQUIRE(o.converged);
    CHECK(o.floquet.stable);
    CHECK(o.floquet.mu[0].real() == doctest::Approx(-0.99236).epsilon(1e-4));
    CHECK(scaled_norm(o.y - start) < 1e-6);
    // A start far off still ends at the same orbit, through steps that lower the residual.
    const Orbit far = find_orbit(p, 22.1973, start + Vec2(5e-4, -5e-3));
    REQUIRE(far.converged);
    CHECK(scaled_norm(far.y - o.y) < 1e-7);
}

TEST_CASE("analysis: a long period (A3C's stable period 24 at 18.1608 rad/s) is found from where the simulator settled") {
    // Over 24 forcing periods (8.3 s) the integrator's error lifts the map's residual noise to ~1.4e-8 at
    // rtol 1e-10, far above Newton's 1e-9: it stalled until the map was sharpened for it.
    const Params p = make_version("A3C");
    OrbitOptions opt;
    opt.period = 24;
    const Orbit o = find_orbit(p, 18.1608, Vec2(-0.0033572361275552146, -0.054075077098791016), opt);
    CHECK(o.message == "");
    REQUIRE(o.converged);
    CHECK(o.residual <= 1e-9);
    CHECK(o.floquet.stable);
    CHECK(o.floquet.mu[0].real() == doctest::Approx(-0.831).epsilon(2e-3));
    CHECK(o.impacts == 0);
    CHECK(o.y[0] == doctest::Approx(-0.00335650323).epsilon(1e-7));
}

TEST_CASE("analysis: the monodromy at each section of a long map is that of its first periods") {
    // The continuation's corrector period by period takes its first guesses along the orbit from these: each
    // must be the derivative of the map up to that section, through the compliant contacts on the way.
    const Params p = make_version("A1C");
    const Tolerances tol = analysis_tolerances(1e-10);
    Vec2 y0 = settle(p, 16.0, Vec2(left_well(p), 0.0), 30, tol);
    std::vector<Mat2> phis;
    MapResult r = detail::period_map(p, 16.0, y0, 4, true, tol, &phis);
    for (int i = 0; i < 50 && r.impacts == 0; ++i) {   // on along the attractor to four periods that press the bumper
        y0 = r.y;
        phis.clear();
        r = detail::period_map(p, 16.0, y0, 4, true, tol, &phis);
    }
    REQUIRE(phis.size() == 4);
    REQUIRE(r.impacts > 0);
    CHECK(max_rel_diff(phis.back(), r.M) < 1e-12);
    for (int i = 1; i <= 3; ++i) {
        CAPTURE(i);
        const MapResult ri = poincare_map(p, 16.0, y0, i, true, tol);
        CHECK(max_rel_diff(phis[static_cast<std::size_t>(i - 1)], ri.M) < 1e-6);
        CHECK(scaled_norm(r.sections[static_cast<std::size_t>(i - 1)] - ri.y) < 1e-9);
    }
    // Without the argument nothing changes: the same map.
    const MapResult plain = poincare_map(p, 16.0, y0, 4, true, tol);
    CHECK(plain.y == r.y);
    CHECK(plain.M == r.M);
}

TEST_CASE("analysis: the tangent computed after the run, on all cores, is the one computed during it, bit for bit") {
    // period_map defers each piece's propagators to the end and computes them side by side; applied in time
    // order they must give the very numbers of the tracker that applies them as the pieces arrive, for a
    // compliant contact (C), rigid impacts (G) and impacts that hold the cart (H), at every section.
    for (const char* name : {"A1C", "A1G", "A1H"}) {
        CAPTURE(name);
        const Params p = make_version(name);
        const Tolerances tol = analysis_tolerances(1e-10);
        const double omega = 16.0;
        const Vec2 y0 = settle(p, omega, Vec2(left_well(p), 0.0), 40, tol);
        std::vector<Mat2> deferred, immediate;
        const MapResult r = detail::period_map(p, omega, y0, 4, true, tol, &deferred);
        const MapResult r0 = detail::period_map(p, omega, y0, 4, true, tol, &immediate, false);
        CHECK(r.impacts > 0);
        CHECK(r.y == r0.y);
        CHECK(r.M == r0.M);
        REQUIRE(deferred.size() == immediate.size());
        for (std::size_t i = 0; i < deferred.size(); ++i) CHECK(deferred[i] == immediate[i]);
    }
}

TEST_CASE("analysis: the tangent's Magnus steps converge at orders 4 and 6") {
    // A Mathieu-like oscillator with a time-varying damping: Phi over [0, 2] in n equal steps against 40000
    // order-6 steps. Halving the step divides the error by 2^4 and 2^6.
    auto A = [](double t) {
        Mat2 a;
        a << 0.0, 1.0, -(1.0 + 0.5 * std::cos(3.0 * t)), -0.1 - 0.3 * std::sin(2.0 * t);
        return a;
    };
    auto run = [&](int n, int order) {
        Mat2 P = Mat2::Identity();
        const double h = 2.0 / n;
        for (int i = 0; i < n; ++i) {
            const double tm = (i + 0.5) * h;
            P = (order == 4 ? detail::magnus4_step(A(tm - detail::kGauss2 * h), A(tm + detail::kGauss2 * h), h)
                            : detail::magnus6_step(A(tm - detail::kGauss3 * h), A(tm), A(tm + detail::kGauss3 * h), h)) *
                P;
        }
        return P;
    };
    const Mat2 ref = run(40000, 6);
    for (int order : {4, 6}) {
        CAPTURE(order);
        const double e1 = (run(20, order) - ref).norm(), e2 = (run(40, order) - ref).norm();
        CHECK(std::log2(e1 / e2) == doctest::Approx(order).epsilon(0.05));
    }
}

TEST_CASE("analysis: the monodromy at the default rtol is the map's derivative, through dry-friction reversals") {
    // Central differences of the map at rtol 1e-13 (steps 1e-7 m and 1e-6 m/s, where they agree with 1e-8 and
    // 1e-5 to 1e-7): the tangent at rtol 1e-10 carries the friction's reversals and the bumper's contacts.
    struct Case {
        const char* model;
        double omega;
        int k;
    };
    for (const Case c : {Case{"A1C", 16.0, 1}, Case{"A1H", 13.6, 2}, Case{"A1G", 9.0, 1}}) {
        CAPTURE(c.model);
        const Params p = make_version(c.model);
        const Tolerances tol = analysis_tolerances(1e-10);
        OrbitOptions oo;
        oo.period = c.k;
        const Orbit o = find_orbit(p, c.omega, settle(p, c.omega, Vec2(-0.015, 0.0), 400, tol), oo);
        REQUIRE(o.converged);
        const MapResult r = poincare_map(p, c.omega, o.y, c.k, true, tol);
        Tolerances fine = tol;
        fine.rtol = 1e-13;
        Mat2 F;
        for (int j = 0; j < 2; ++j) {
            Vec2 d = Vec2::Zero();
            d[j] = j == 0 ? 1e-7 : 1e-6;
            F.col(j) = (poincare_map(p, c.omega, o.y + d, c.k, false, fine).y - poincare_map(p, c.omega, o.y - d, c.k, false, fine).y) /
                       (2 * d[j]);
        }
        CHECK(max_rel_diff(r.M, F) < 3e-3);
    }
}
