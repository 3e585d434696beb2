// The live omega ramp (sim/omega_ramp.hpp) and the inputs of its row under the omega slider. UI thread only.
#pragma once

#include "sim/omega_ramp.hpp"

namespace impactlab::gui {

struct RampControl {
    OmegaRamp live;                           // the live omega ramp and the section points it passed
    float target = 25.0f, rate = 0.05f;       // its inputs [rad/s], [rad/s per s]
};

}  // namespace impactlab::gui
