// Replay of the recent past (app_replay.cpp): the cursor over the history (sim/replay.hpp), what was asked
// while the histories were rewound (done once they are live again), the live values put aside meanwhile,
// and the Poincare map as it stood at the cursor. UI thread only.
#pragma once

#include "sim/replay.hpp"
#include "sim/sim_messages.hpp"
#include "views/poincare_map.hpp"

namespace impactlab::gui {

enum class ReplayRequest { None, Leave, Continue, Clip };   // asked while the histories are rewound

struct ReplayController {
    Replay player;
    ReplayRequest request = ReplayRequest::None;
    struct {
        SimMsg last{};
        double phi_prev = 0, max_force = 0;
        bool rewound = false;   // the histories and the newest sample show the cursor's instant
    } live;
    PoincareMap map;            // replaying: the live map as it stood at the cursor

    // The map the panels show: the live one, or while replaying the one at the cursor.
    const PoincareMap& shown_map(const PoincareMap& live_map) const { return player.active() ? map : live_map; }
};

}  // namespace impactlab::gui
