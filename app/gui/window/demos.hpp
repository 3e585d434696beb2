// "What to try": the panel of five demonstrations, whether it is open, and what the last one asked for.
// UI thread only.
#pragma once

#include "views/guide_panel.hpp"

namespace impactlab::gui {

struct Demos {
    // Demonstration 1: A1H's first doubling (10.8613 rad/s) crossed slowly, 0.6 rad/s over 600 s of
    // simulation, 30 s of wall time at 20x, the split reached about 13 s in.
    static constexpr double kDemo1From = 10.6, kDemo1To = 11.2, kDemo1Rate = 1e-3;
    GuidePanel panel;
    bool show = false;
    int last = 0;        // the last demonstration run (1-5), 0 none
    double speed = 0;    // the speed the last demonstration asked for (0: none)
};

}  // namespace impactlab::gui
