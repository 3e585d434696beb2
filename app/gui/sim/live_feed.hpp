// What the simulation published, as the UI keeps it: the drained histories, the settled Poincare map, the
// newest sample and what the frame derives from the samples (the contact flash, the impact label, the
// grazing monitor), and the restart whose first sample has not come back yet. Filled by the App's drain,
// read by every view's context. UI thread only.
#pragma once

#include <cstddef>
#include <cstdint>

#include "sim/history.hpp"
#include "sim/sim_messages.hpp"
#include "views/poincare_map.hpp"
#include "views/view_fit.hpp"

namespace impactlab::gui {

struct LiveFeed {
    History<SimMsg> traj{std::size_t{1} << 19};       // 9 min at 1x, 5 s at 100x
    History<SimMsg> sections{std::size_t{1} << 18};   // every section point of the epoch (CSV, x(t) dots)
    PoincareMap pc_map;                               // what the Poincare map shows: settled points only
    SectionFeeder pc_feed;
    SimMsg last{};
    bool have_last = false;
    std::uint32_t epoch = 0;
    std::uint64_t samples_seen = 0, impacts_seen = 0;
    double frame_max_force = 0;
    double flash = 0;
    ImpactLabel impact_label;   // the rig's "F = ..." label: during a contact and shortly after
    double phi_prev = 0;
    SimMsg grazing{};           // the cart's grazing monitor, last whole period (MsgKind::Grazing)
    bool have_grazing = false;
    double xI_shown = 0;        // [m] the bumper where the simulation has it (travelling to the asked xI)
    struct {
        bool pending = false, clear = false;
        double t = 0, since = 0;
        std::uint32_t epoch = 0;
    } restart;                  // a Restart sent, its sample not yet drained
};

}  // namespace impactlab::gui
