// The companion cart: the twin or the ghost, the track of its records (source 1), its mode and the ghost's
// impact law. UI thread only.
#pragma once

#include "sim/companion_track.hpp"

namespace impactlab::gui {

struct Companion {
    CompanionTrack track;
    CompanionMode mode = CompanionMode::Off;
    int ghost_impact = 2;   // the ghost's impact law, an index into impact_models()
};

}  // namespace impactlab::gui
