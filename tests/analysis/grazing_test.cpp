// Continuation through a rigid grazing: the impact-to-impact equations, a free branch of A1G that crosses its
// grazing onto the impacting branch (orbits on both sides confirmed by the Simulator, the grazing against the
// bumperless orbit's largest x, the multipliers' scaling), the impacting period-2 branch that joins two
// grazings, and the isola of A1G's impacting period-1 window.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "impactlab/analysis.hpp"
#include "impactlab/params.hpp"
#include "impactlab/simulator.hpp"

using namespace impactlab;
using namespace impactlab::analysis;

namespace {

const BifPoint* near_point(const ContinuationResult& r, BifKind kind, double q, double tol) {
    for (const auto& b : r.points)
        if (b.kind == kind && std::abs(b.param - q) < tol) return &b;
    return nullptr;
}

// Near the section point of A1G's stable impacting period-1 orbit at 16 rad/s (-0.0231881754, -0.0292330136).
// Settling onto it from the left well is no start: the run crosses a chaotic transient there, and where
// it ends after 200 periods (this orbit, or Newton's landing on an unstable one) follows the last bits of
// libm's CPU-specific paths.
const Vec2 kStableWindow16(-0.02319, -0.02923);

// One forcing period of the rig from (x, v) at phi = 0, through the core Simulator itself.
struct Return { Vec2 y; std::uint64_t impacts; };
Return one_period(const Params& p, double omega, const Vec2& y0) {
    const Drive d(omega, 0.0, 0.0);
    State s;
    s.x = y0[0];
    s.v = y0[1];
    Simulator::make_consistent(p, d, s);
    Simulator sim(analysis_tolerances(1e-11));
    sim.advance(p, d, s, d.time_of_phase(kTwoPi));
    return {Vec2(s.x, s.v), s.impacts};
}

// The largest x of the bumperless orbit at omega, minus xI (the grazing's test on the free side).
double gap(const Params& p, double omega, const Vec2& guess) {
    Params f = p;
    f.impact = find_impact("none");
    OrbitOptions oo;
    oo.sim = analysis_tolerances(1e-11);
    const Orbit o = find_orbit(f, omega, guess, oo);
    REQUIRE(o.converged);
    double x_max = 0;
    peak_phase(f, omega, o.y, 1, oo.sim, &x_max);
    return x_max - p.xI;
}

}  // namespace

TEST_CASE("impact_shot: its Jacobian is the equations' finite-difference slope, and its orbit is the map's") {
    const Params p = make_version("A1G");
    // The stable impacting period-1 orbit of the window at 16 rad/s, found on the stroboscopic map from a
    // start near it (kStableWindow16).
    OrbitOptions oo;
    const Orbit o = find_orbit(p, 16.0, kStableWindow16, oo);
    REQUIRE(o.converged);
    REQUIRE(o.impacts == 1);
    CHECK(o.floquet.stable);
    double theta = 0, vm = 0;
    REQUIRE(first_impact(p, 16.0, o.y, 1, oo.sim, theta, vm));
    const ImpactOrbit io = find_impact_orbit(p, 16.0, theta, vm, 1);
    REQUIRE(io.converged);
    CHECK(std::abs(io.v_minus - vm) < 1e-7);
    CHECK(scaled_norm(io.section - o.y) < 1e-7);
    // Central differences of the residual against the tangent-built Jacobian.
    const Tolerances tol = analysis_tolerances(1e-12);
    const ImpactShot s = impact_shot(p, 16.0, io.theta, io.v_minus, 1, true, tol);
    const double h[2] = {1e-5, 1e-5};
    for (int j = 0; j < 2; ++j) {
        double th_p = io.theta, th_m = io.theta, v_p = io.v_minus, v_m = io.v_minus;
        if (j == 0) { th_p += h[0]; th_m -= h[0]; }
        else { v_p += h[1] * kVScale; v_m -= h[1] * kVScale; }
        const Vec2 col = (impact_shot(p, 16.0, th_p, v_p, 1, false, tol).residual -
                          impact_shot(p, 16.0, th_m, v_m, 1, false, tol).residual) / (2 * h[j]);
        CAPTURE(j);
        CHECK((col - s.J.col(j)).norm() < 1e-4 * std::max(1.0, s.J.col(j).norm()));
    }
}

TEST_CASE("A1G with the bumper at -4 mm: the free period-1 branch crosses its grazing onto the impacting branch") {
    Params p = make_version("A1G");
    p.xI = -0.004;
    ContinuationSpec spec;
    spec.lo = 8.0;
    spec.hi = 14.0;
    spec.start = 9.0;
    spec.max_period = 1;
    const ContinuationResult r = continue_orbits(p, spec);
    const BifPoint* g = near_point(r, BifKind::Grazing, 9.6005, 1e-3);
    REQUIRE(g != nullptr);
    // The grazing: the bumperless orbit's largest x passes xI there, to 1e-6 rad/s.
    CHECK(gap(p, g->param - 1e-6, g->y) < 0);
    CHECK(gap(p, g->param + 1e-6, g->y) > 0);
    CHECK(g->param == doctest::Approx(9.60049627).epsilon(2e-8));
    // The impacting orbits lie on the free orbits' side (below the grazing): a nonsmooth fold, and the
    // impacting branch turns in a smooth fold at 9.5489 to go on up to the end of the range.
    CHECK(g->scenario == "nonsmooth fold");
    const BifPoint* f = near_point(r, BifKind::Fold, 9.548943, 1e-5);
    REQUIRE(f != nullptr);
    // Nordmark's square-root map: impact speed ~ d, largest multiplier ~ 1/d along the impacting branch.
    CHECK(g->speed_exponent == doctest::Approx(1.0).epsilon(0.1));
    CHECK(g->mu_exponent == doctest::Approx(-1.0).epsilon(0.15));
    // Both sides are the rig's periodic orbits: free ones below the grazing, impacting ones past it, each
    // returning to itself after one period of the Simulator with as many impacts as the branch says.
    int free_checked = 0, impacting_checked = 0;
    double q_max = 0;
    for (const Branch& b : r.branches)
        for (const BranchPoint& q : b.points) {
            q_max = std::max(q_max, q.param);
            if (std::abs(q.param - g->param) > 0.2) continue;
            const Return ret = one_period(p, q.param, q.y);
            CAPTURE(q.param);
            CHECK(static_cast<int>(ret.impacts) == q.impacts);
            CHECK(scaled_norm(ret.y - q.y) < 1e-5);
            (q.impacts == 0 ? free_checked : impacting_checked)++;
        }
    CHECK(free_checked >= 3);
    CHECK(impacting_checked >= 3);
    CHECK(q_max > 13.99);   // on the impacting side up to the end of the range
}

TEST_CASE("A1G's impacting period-2 branch joins the grazings at 12.7992694 and 15.9679638, with its fold") {
    ContinuationSpec spec;
    spec.lo = 9.0;
    spec.hi = 25.0;
    spec.start = 9.0;
    spec.max_period = 2;
    const ContinuationResult r = continue_orbits(make_version("A1G"), spec);
    const BifPoint* g1 = near_point(r, BifKind::Grazing, 12.7992694, 1e-6);
    const BifPoint* g2 = near_point(r, BifKind::Grazing, 15.9679638, 1e-6);
    REQUIRE(g1 != nullptr);
    REQUIRE(g2 != nullptr);
    CHECK(g1->scenario == "nonsmooth fold");
    CHECK(g2->scenario == "nonsmooth fold");
    // The impacting branch from one grazing ends where its impacts end, at the other grazing, found from the
    // impacting side at the value located from the free side (which one is reached first depends on the
    // order the branches are followed in).
    bool joined = false;
    for (const Branch& b : r.branches)
        if (b.end.find("grazing at omega = 15.96796") != std::string::npos ||
            b.end.find("grazing at omega = 12.79926") != std::string::npos)
            joined = true;
    CHECK(joined);
    CHECK(near_point(r, BifKind::Fold, 19.2743009, 1e-6) != nullptr);
}

TEST_CASE("A1G's impacting period-1 window is an isola: a closed branch with folds at 11.9603683 and 18.3212424") {
    ContinuationSpec spec;
    spec.lo = 5.0;
    spec.hi = 25.0;
    spec.start = 16.0;
    spec.guess = kStableWindow16;
    spec.max_period = 1;
    const ContinuationResult r = continue_orbits(make_version("A1G"), spec);
    REQUIRE(r.branches.size() == 1);
    CHECK(r.branches[0].end.find("closed loop") != std::string::npos);
    CHECK(near_point(r, BifKind::Fold, 11.9603683, 1e-6) != nullptr);
    CHECK(near_point(r, BifKind::Fold, 18.3212424, 1e-6) != nullptr);
    for (const BranchPoint& q : r.branches[0].points) {
        CHECK(q.impacts == 1);   // never free: it never grazes
        CHECK(q.param > 11.96);
        CHECK(q.param < 18.33);
    }
}
