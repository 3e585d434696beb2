// What the live plot views (rig, phase portrait, Poincare map, potential, x(t)) read each frame and what a
// click in one asks for. The App fills a ViewContext from the shared sample history and its own settings,
// a view draws inside its tile, and the App routes the returned ViewAction to the simulation; no view
// talks to the simulation thread. UI thread only.
#pragma once

#include <imgui.h>

#include <cstddef>
#include <optional>
#include <string>
#include <utility>

#include "sim/companion_track.hpp"
#include "sim/history.hpp"
#include "impactlab/params.hpp"
#include "views/poincare_map.hpp"
#include "sim/sim_messages.hpp"
#include "sim/state_pick.hpp"
#include "views/view_fit.hpp"

namespace impactlab::gui {

struct ViewContext {
    const History<SimMsg>* traj = nullptr;       // every sample the window keeps (replaying: up to the cursor)
    const History<SimMsg>* sections = nullptr;   // every section point of the epoch
    const PoincareMap* map = nullptr;            // the map shown (replaying: as it stood at the cursor)
    SimMsg last{};                               // the newest sample (replaying: the cursor's)
    bool have_last = false;
    std::uint32_t epoch = 0;                     // of the newest record (bumped by every change)
    double phi_prev = 0;                         // phi one frame ago (the unbalance disc's motion blur)
    const Params* params = nullptr;              // the UI's copy of the model
    int params_rev = 0;                          // changes whenever *params does (a switch, an edit)
    double omega = 0, speed = 1;                 // asked for [rad/s], the speed factor
    double xI = 0;                               // [m] the slider's bumper position
    double xI_shown = 0;                         // [m] where the simulation has it (travelling to xI)
    double section_phase = 0;                    // [rad] the Poincare section's phase phi0 asked for
    bool paused = false, sim_paused = false;     // asked for; what the simulation says
    bool replay = false;                         // the panels show a replayed instant
    bool omega_moving = false;                   // a live ramp moves omega (the map's period is no one omega's)
    float ui_scale = 1;
    double frame_dt = 1.0 / 60, now = 0;         // [s] of wall time
    std::size_t trail_first = 0;                 // the first sample of the phase portrait's trail
    float trail_periods = 8, strip_window = 6;   // the trail [forcing periods] and the x(t) window [s]
    std::size_t bench_window = 0;                // --bench-plot: the plots show this many newest samples
    const CompanionTrack* companion = nullptr;   // the twin or the ghost
    CompanionMode companion_mode = CompanionMode::Off;
    std::string companion_name;                  // "twin" or "ghost G"
    double magnify = 1;                          // the rig's displacement magnification (drawing only)
    double frame_max_force = 0, flash = 0;       // the bumper's glow this frame
    const ImpactLabel* impact_label = nullptr;        // the rig's "F = ..." label, fed by the App's drain
    bool companion_shown() const { return companion_mode != CompanionMode::Off && companion && companion->have(); }
};

// What the mouse asked for in a view: the App checks it (rail, bumper) and sends it.
struct ViewAction {
    std::optional<std::pair<double, double>> set_state;   // start from (x, v) [m, m/s]
    std::optional<double> hold;                           // hold the cart at x [m] (dragged in the rig)
    std::optional<std::pair<double, double>> start_orbit; // the Poincare clicker: a new orbit from (x, v) at a section
    std::optional<double> section_phase;                  // the Poincare section's phase phi0 [rad], 0 .. 2 pi
};

// The companion's colour in every plot (magenta: apart from the cart's trace, the sections and the bumper).
ImU32 companion_color(float alpha);

// A plain click in a plot that sets the state, delayed by the double-click time so that a double-click
// still resets the plot's view: the (x, v) once it is due.
std::optional<std::pair<double, double>> delayed_click(ClickDelay& delay, bool hovered, bool clicked, double x, double v,
                                                       double now);

}  // namespace impactlab::gui
