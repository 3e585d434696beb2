// Lyapunov exponents: a linear oscillator's exact values, Benettin against two trajectories on a chaotic
// impacting orbit, and the sign along a CF sweep against the sweep's own period count.
#include <doctest/doctest.h>

#include <cmath>

#include "impactlab/analysis.hpp"
#include "impactlab/params.hpp"

using namespace impactlab;
using namespace impactlab::analysis;

TEST_CASE("analysis: Lyapunov exponents of a linear oscillator are -c/2m") {
    Params p = make_version("A1none");
    p.a = {0, 0, 0, 0};
    p.b = {0, 0, 0, 0};
    p.T = 0;
    State s;
    const LyapunovResult r = lyapunov(p, 9.0, s, 5, 60, analysis_tolerances(1e-10));
    CHECK(r.lambda_max == doctest::Approx(-p.c / (2 * p.m)).epsilon(1e-3));
    CHECK(r.lambda_max + r.lambda_min == doctest::Approx(-p.c / p.m).epsilon(1e-6));
}

TEST_CASE("analysis: Benettin's exponent agrees with two trajectories on chaotic impacting motion") {
    for (const char* name : {"A1G", "A1C"}) {
        CAPTURE(name);
        const Params p = make_version(name);
        State s;
        s.x = left_well(p);
        const State s0 = s;
        // The distance d0 must stay far above the integrator's noise (rtol times the scales) or that noise,
        // amplified, is measured instead: rtol 1e-11 against d0 = 1e-6.
        const Tolerances tol = analysis_tolerances(1e-11);
        const LyapunovResult r = lyapunov(p, 16.0, s, 30, 600, tol);
        const double two = lyapunov_two_trajectory(p, 16.0, s0, 30, 600, tol, 1e-6);
        CHECK(r.lambda_max > 0.1);
        CHECK(two == doctest::Approx(r.lambda_max).epsilon(0.15));
    }
}

TEST_CASE("analysis: the largest exponent's sign separates chaos from periodic motion along a CF sweep") {
    const Params p = make_version("A1C");
    CfSpec spec;
    spec.omega_min = 10.0;
    // 10 (period 1), 12.75 (period 2), 15.5 and 18.25 (chaos), 21 (period 2). Not 22: 0.15 rad/s from the
    // doubling at 22.147 the alternation decays by only 1.5 % a period, and whether the sweep's 20 transient
    // periods end on the period-2 label there follows the processor's paths (masked: 17 periods, -0.05 1/s).
    spec.omega_max = 21.0;
    spec.steps = 5;
    const auto pts = lyapunov_sweep(p, spec);
    REQUIRE(pts.size() == 5);
    int chaotic = 0;
    for (const auto& pt : pts) {
        CAPTURE(pt.omega);
        CAPTURE(pt.period);
        CAPTURE(pt.lambda_max);
        const bool chaos = pt.period > 16;
        chaotic += chaos;
        CHECK(chaos == (pt.lambda_max > 0.05));
        if (!chaos) CHECK(pt.lambda_max < -0.05);
    }
    CHECK(chaotic >= 2);
}
