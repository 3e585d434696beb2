// What the user asked the simulation for: the model, the forcing, the bumper, the speed and the parameters.
// The simulation thread follows within a few milliseconds; the panels read these for V(x) and the forces
// shown. UI thread only.
#pragma once

#include "impactlab/params.hpp"

namespace impactlab::gui {

struct RunRequest {
    int stiffness = 0, impact = 3;   // indices into stiffness_sets() / impact_models()
    double omega = 9.0, xI = 0.0, speed = 1.0, x0 = -0.011;
    bool paused = false;
    Params params;                   // the UI's copy, for V(x) and the display of forces
    int params_rev = 0;              // bumped at every change of params (the potential, the energy floor)
    double energy_floor = 0;         // [J] the well's floor V_min of params (the energy bar's zero)
    int energy_floor_rev = -1;       // the params_rev it was computed for
};

}  // namespace impactlab::gui
