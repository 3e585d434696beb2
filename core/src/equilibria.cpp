#include "impactlab/equilibria.hpp"

#include <algorithm>
#include <limits>

#include "impactlab/forces.hpp"

namespace impactlab {

double potential_floor(const Params& p) {
    constexpr double kRail = 0.1;   // [m] either side of the hilltop
    double floor = std::min(spring_magnet_potential(p, -kRail), spring_magnet_potential(p, kRail));
    // Cells of 0.1 mm: far narrower than any well of the rig.
    for (const Equilibrium& e : equilibria([&](double x) { return spring_magnet(p, x).F; }, -kRail, kRail, 2000))
        if (e.stable) floor = std::min(floor, spring_magnet_potential(p, e.x));
    return floor;
}

double turning_point(const Piece& piece) {
    if (!piece.step || !(piece.at(piece.t0)[1] > 0) || !(piece.at(piece.t1)[1] < 0))
        return std::numeric_limits<double>::quiet_NaN();
    return bisect([&](double t) { return piece.at(t)[1] > 0; }, piece.t0, piece.t1);
}

}  // namespace impactlab
