// A doubling located by the library, checked against Newton on the period map at a sharp tolerance: the
// multiplier nearest -1 of the period-k orbit found from y at omega, plus 1 (its sign says which side of the
// doubling omega lies on). At rtol 1e-12 the multiplier is smooth to about 1e-6; at the default 1e-10 an
// impacting orbit's jitters by 3e-3.
#pragma once

#include <doctest/doctest.h>

#include <cmath>

#include <Eigen/LU>

#include "impactlab/analysis.hpp"
#include "impactlab/params.hpp"

namespace impactlab::test {

// The period-k orbit Newton finds from y at omega on the map at rtol (required to converge). An orbit that
// expands 3e5-fold (A1C's period 8 pressing the bumper) brings the map's noise, amplified, above Newton's
// residual tolerance at any rtol: there the reference is sharpened tenfold, and failing that its position
// is what counts, Newton's next step (M - I)^-1 (P(y) - y) from where it ended, required below 1e-9 (scaled).
inline analysis::Orbit newton_orbit(const Params& p, double omega, const Vec2& y, int k, double rtol = 1e-12) {
    analysis::OrbitOptions oo;
    oo.period = k;
    oo.sim.rtol = rtol;
    analysis::Orbit o = analysis::find_orbit(p, omega, y, oo);
    if (!o.converged) {
        oo.sim.rtol = std::max(rtol * 0.1, 1e-13);
        o = analysis::find_orbit(p, omega, y, oo);
    }
    if (!o.converged) {
        const analysis::MapResult r = analysis::poincare_map(p, omega, o.y, k, true, oo.sim);
        const Vec2 step = (r.M - Mat2::Identity()).fullPivLu().solve(r.y - o.y);
        CAPTURE(o.residual);
        REQUIRE(analysis::scaled_norm(step) < 1e-9);
    }
    return o;
}

inline double doubling_side(const Params& p, double omega, const Vec2& y, int k, double rtol = 1e-12) {
    const analysis::Orbit o = newton_orbit(p, omega, y, k, rtol);
    const auto& mu = o.floquet.mu;
    return (std::abs(mu[0] + 1.0) < std::abs(mu[1] + 1.0) ? mu[0] : mu[1]).real() + 1.0;
}

}  // namespace impactlab::test
