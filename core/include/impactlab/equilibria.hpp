// Sign changes, found one way for every caller: the equilibria (wells and hilltops) of a static force law,
// the floor of the springs' and magnets' potential, and the cart's turning points on the integrator's
// dense output. The fit's well report, the orbit search's start, the GUI's energy bar and grazing
// monitor and the tangent tracker all use these.
#pragma once

#include <vector>

#include "impactlab/params.hpp"
#include "impactlab/simulator.hpp"

namespace impactlab {

// The boundary in [a, b] where on_a_side(x), true at a and false at b, turns false: `halvings`
// bisections, then the midpoint of the last bracket. Which side an exact zero of a function lies on is
// the predicate's to say. Once a and b are neighbouring doubles the bracket no longer moves, so more
// halvings than that change nothing.
template <class OnASide>
double bisect(OnASide&& on_a_side, double a, double b, int halvings = 60) {
    for (int i = 0; i < halvings; ++i) {
        const double m = 0.5 * (a + b);
        (on_a_side(m) ? a : b) = m;
    }
    return 0.5 * (a + b);
}

struct Equilibrium {
    double x = 0;
    bool stable = false;   // a well (R rises through zero); else a hilltop
};

// The zeros of a static restoring force R(x) (m x'' = -R(x) + ...) on [lo, hi], ascending: each of `cells`
// equal cells whose ends differ in sign (zero counts as positive) is bisected, 60 halvings.
template <class Force>
std::vector<Equilibrium> equilibria(Force&& R, double lo, double hi, int cells) {
    std::vector<Equilibrium> out;
    const double h = (hi - lo) / cells;
    double xa = lo, Ra = R(lo);
    for (int i = 1; i <= cells; ++i) {
        const double xb = lo + h * i, Rb = R(xb);
        if ((Ra < 0) != (Rb < 0)) {
            const bool neg = Ra < 0;
            out.push_back({bisect([&](double x) { return (R(x) < 0) == neg; }, xa, xb), Rb > Ra});
        }
        xa = xb;
        Ra = Rb;
    }
    return out;
}

// The lowest V(x) of the springs' and magnets' potential (spring_magnet_potential) on the rail
// [-0.1, 0.1] m [J]: the deepest well's floor, or an end of the rail where that is lower.
double potential_floor(const Params& p);

// The instant inside a free-flight piece where the cart turns back (v from + at t0 to - at t1), by
// bisection on the dense output (60 halvings); NaN when v does not go from + to - across the piece.
double turning_point(const Piece& piece);

}  // namespace impactlab
