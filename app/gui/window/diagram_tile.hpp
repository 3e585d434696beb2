// The bifurcation diagram's tile: the panel (its range, live points and the Lyapunov strip) and the settings
// sessions save, which the panel edits. UI thread only.
#pragma once

#include "views/bifurcation_panel.hpp"

namespace impactlab::gui {

struct DiagramTile {
    BifurcationPanel panel;
    int protocol = 0, steps = 300;
    bool dirty = true;   // the look changed: the diagram is drawn afresh
};

}  // namespace impactlab::gui
