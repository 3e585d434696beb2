#include "energy_bar.hpp"

#include <algorithm>
#include <cmath>


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

}  // namespace impactlab::gui
