#include "energy_bar.hpp"

#include <algorithm>
#include <cmath>

#include "impactlab/forces.hpp"

namespace impactlab::gui {

EnergyBars energy_bars(const EnergyBalance& b, double m, double V_min) {
    EnergyBars r;
    const double kinetic = 0.5 * m * b.v * b.v;
    // E less kinetic is V(x) plus a compliant bumper's elastic energy; measured from the well's floor.
    const double potential = std::max(0.0, b.E - kinetic - V_min);
    r.in = {std::max(0.0, b.E0 - V_min), std::max(0.0, b.work_unbalance), std::max(0.0, b.work_effects)};
    r.out = {kinetic, potential, std::max(0.0, b.dissipated_resistance), std::max(0.0, b.dissipated_bumper),
             std::max(0.0, -b.work_effects)};
    double in = 0, out = 0;
    for (double s : r.in) in += s;
    for (double s : r.out) out += s;
    r.full = std::max(in, out);
    r.residual = b.residual();
    return r;
}

double potential_floor(const Params& p) {
    double best_x = 0, best = spring_magnet_potential(p, 0.0);
    for (int i = -1000; i <= 1000; ++i) {   // +-0.1 m, the rail
        const double x = 1e-4 * i, v = spring_magnet_potential(p, x);
        if (v < best) best = v, best_x = x;
    }
    // Golden-section refinement inside the best cell: the floor to far below a microjoule.
    double a = best_x - 1e-4, c = best_x + 1e-4;
    for (int it = 0; it < 40; ++it) {
        const double m1 = c - 0.618 * (c - a), m2 = a + 0.618 * (c - a);
        if (spring_magnet_potential(p, m1) < spring_magnet_potential(p, m2)) c = m2;
        else a = m1;
    }
    return std::min(best, spring_magnet_potential(p, 0.5 * (a + c)));
}

}  // namespace impactlab::gui
