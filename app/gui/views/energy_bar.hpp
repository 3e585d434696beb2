// The energy bar, a teaching overlay: where the energy put in went, as two stacked bars of the
// same length when the balance closes. In: the energy at the start of the balance and the work of the
// unbalance. Out: kinetic, potential (above the bottom of the well) and what the resistance and the bumper
// dissipated. The numbers come from the core's EnergyLedger on the sim thread; this only lays them out.
#pragma once

#include <array>

#include "impactlab/energy.hpp"
#include "impactlab/equilibria.hpp"
#include "impactlab/params.hpp"

namespace impactlab::gui {

struct EnergyBars {
    // Segment lengths [J], each >= 0. in: start, unbalance, effects' work (if they feed energy in);
    // out: kinetic, potential, resistance, bumper, effects (if they dissipate).
    std::array<double, 3> in{};
    std::array<double, 5> out{};
    double full = 0;        // [J] the longer bar's total: the bars' common scale
    double residual = 0;    // [J] in - out, the balance's error as the ledger reports it
};

// GL-free. V_min [J]: the bottom of the potential well, so that the potential share is >= 0 (V(x) itself is
// negative in the wells of the double-well stiffness).
EnergyBars energy_bars(const EnergyBalance& b, double m, double V_min);

// V_min is core's potential_floor(p) (impactlab/equilibria.hpp): the deepest well's floor on the rail.

// energy_bar_view.cpp. UI thread, inside an ImGui window: the two bars, a legend in mJ and the closing error.
void draw_energy_bars(const EnergyBars& bars, double t0, double t);

}  // namespace impactlab::gui
