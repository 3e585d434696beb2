// Routing: the contexts the App hands its views each frame, and what a view asks for (a click, a drag, a
// box, a job's result) turned into the App's commands to the simulation thread and its toasts. No view talks
// to the simulation thread; this file is the only way in. UI thread.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>

#include "window/app.hpp"
#include "render/plot2d.hpp"
#include "render/theme.hpp"
#include "render/widgets.hpp"

namespace impactlab::gui {

std::size_t App::trail_first() const {
    const std::size_t n = feed_.traj.size();
    if (bench_.window) return n > bench_.window ? n - bench_.window : 0;
    if (n == 0) return 0;
    const double t_from = feed_.traj.back().t - view_.trail_periods * kTwoPi / std::max(run_.omega, 0.5);
    return feed_.traj.lower_bound(t_from, [](const SimMsg& m) { return m.t; });
}

ViewContext App::view_context() const {
    ViewContext c;
    c.traj = &feed_.traj;
    c.sections = &feed_.sections;
    c.map = &shown_map();
    c.last = feed_.last;
    c.have_last = feed_.have_last;
    c.epoch = feed_.epoch;
    c.phi_prev = feed_.phi_prev;
    c.params = &run_.params;
    c.params_rev = run_.params_rev;
    c.omega = run_.omega;
    c.speed = run_.speed;
    c.xI = run_.xI;
    c.xI_shown = feed_.xI_shown;
    c.section_phase = view_.section_phase;
    c.paused = run_.paused;
    c.sim_paused = sim_->status().paused;
    c.replay = replay_.player.active();
    c.omega_moving = ramp_.live.active();
    c.ui_scale = view_.ui_scale;
    c.frame_dt = frames_.dt;
    c.now = now_s();
    c.trail_first = trail_first();
    c.trail_periods = view_.trail_periods;
    c.strip_window = view_.strip_window;
    c.bench_window = bench_.window;
    c.companion = &companion_.track;
    c.companion_mode = companion_.mode;
    c.companion_name = companion_.mode == CompanionMode::Twin
                           ? std::string("twin")
                           : "ghost " + std::string(impact_models()[static_cast<std::size_t>(companion_.ghost_impact)].id);
    c.magnify = magnification();
    c.frame_max_force = feed_.frame_max_force;
    c.flash = feed_.flash;
    c.impact_label = &feed_.impact_label;
    return c;
}

void App::apply_view(const ViewAction& a) {
    if (a.hold) send(SimCommand::hold(*a.hold));   // each hold restarts the companion too
    if (a.set_state) set_state(a.set_state->first, a.set_state->second);
    if (a.start_orbit) restart_at_section(a.start_orbit->first, a.start_orbit->second);
    if (a.section_phase) set_section_phase(*a.section_phase);
}

void App::set_section_phase(double phi0) {
    if (phi0 == view_.section_phase) return;
    view_.section_phase = phi0;
    // The orbits the clicker took belong to the old section: not to be mixed with the new one's points
    // (the map and the sections clear at the engine's new epoch).
    poincare_.clear_orbits();
    send(SimCommand::section_phase(phi0));
}

void App::start_orbit(double x, double v) {
    poincare_.start_orbit(x, v, feed_.epoch);
    restart_at_section(x, v);
}

void App::restart_at_section(double x, double v) {
    // The orbit starts on the section: at the next phi = phi0 + 2 pi k (the forcing's phase moves on to
    // it), from (x, v) checked as a click in the phase portrait is (rail, bumper). The phase is written as
    // the core's Simulator::section_phi writes it, 2 pi n - psi, so the engine takes it for that section.
    const PickedState s = pick_state(x, v, run_.xI, run_.params.has_bumper());
    if (!s.note.empty()) toast(s.note);
    const double psi = view_.section_phase > 0.0 ? kTwoPi - view_.section_phase : 0.0;
    const double phi = kTwoPi * std::ceil((feed_.last.phi + psi) / kTwoPi - 1e-9) - psi;
    restart_sim(s.x, s.v, feed_.last.t, phi, run_.omega, false);
}

DataPanelContext App::data_context() const {
    DataPanelContext c;
    c.model = model_name();
    c.xI = run_.xI;
    c.ui_scale = view_.ui_scale;
    return c;
}

void App::set_state(double x, double v) {
    const PickedState s = pick_state(x, v, run_.xI, run_.params.has_bumper());
    if (!s.note.empty()) toast(s.note);
    send(SimCommand::set_state(s.x, s.v));
}

void App::set_companion(CompanionMode mode) {
    companion_.mode = mode;
    companion_.track.clear();
    const std::string ghost = std::string(stiffness_sets()[static_cast<std::size_t>(run_.stiffness)].id) +
                              impact_models()[static_cast<std::size_t>(companion_.ghost_impact)].id;
    send(SimCommand::companion(mode, ghost));
}

void App::start_ramp(double target, double rate) {
    if (const std::string err = OmegaRamp::check(target, rate, kMaxOmega, kMinRampRate, kMaxRampRate); !err.empty()) {
        toast(err);
        return;
    }
    if (std::abs(target - run_.omega) < 1e-6) {
        toast("ramp: ω is already " + std::to_string(target).substr(0, 5) + " rad/s");
        return;
    }
    ramp_.live.begin(run_.omega, target, rate);
    send(SimCommand::ramp(target, rate));
    if (run_.paused) set_paused(false);
    char buf[128];
    std::snprintf(buf, sizeof buf, "ramping ω %.2f → %.2f rad/s at %.3g rad/s per s (%.0f s of simulation)", run_.omega,
                  target, rate, std::abs(target - run_.omega) / rate);
    toast(buf);
}

BifurcationContext App::bifurcation_context() {
    BifurcationContext c;
    c.params = &run_.params;
    c.model = model_name();
    c.omega = run_.omega;
    c.xI = run_.xI;
    // Settled section points only (replaying: those of the cursor's instant); the diagram's sections are at
    // phi = 2 pi n, so the map's at another phase would not lie on it.
    const bool strobe = view_.section_phase == 0.0 || view_.section_phase == kTwoPi;
    c.live = strobe ? &shown_map().points() : nullptr;
    c.protocol = &bif_.protocol;
    c.steps = &bif_.steps;
    c.ramp = &ramp_.live;
    c.overlay = [this](Plot& plot) { analysis_.overlay_diagram(plot); };
    c.overlay_legend = [this](bool compact) { analysis_.overlay_legend(compact); };
    if (const auto& ov = analysis_.overlay()) c.branches = &*ov;
    return c;
}

void App::start_bifurcation() {
    if (const std::string err = bif_.panel.start(bifurcation_context()); !err.empty()) toast(err);
}

void App::poll_bifurcation() {
    if (bif_.dirty) {   // the theme or the fonts changed
        bif_.panel.mark_dirty();
        bif_.dirty = false;
    }
    if (const std::string msg = bif_.panel.poll(bifurcation_context()); !msg.empty()) toast(msg);
}

void App::draw_bifurcation() {
    const BifurcationAction act = bif_.panel.draw(bifurcation_context());
    if (act.omega) set_omega(*act.omega);
    if (!act.toast.empty()) toast(act.toast);
}

AnalysisContext App::analysis_context() const {
    AnalysisContext c;
    c.params = &run_.params;
    c.model = model_name();
    c.omega = run_.omega;
    c.xI = run_.xI;
    c.diagram_omega = bif_.panel.omega_axis();
    c.ui_scale = view_.ui_scale;
    c.plane_open = layout_.panel_visible[static_cast<std::size_t>(PanelId::Plane)];
    c.basins_open = layout_.panel_visible[static_cast<std::size_t>(PanelId::Basins)];
    // The live map (not a replayed one): continuation starts from what runs now.
    if (feed_.pc_map.status() == PoincareMap::Status::Periodic && !feed_.pc_map.points().empty()) {
        const MapPoint& m = feed_.pc_map.points().back();
        c.orbit = AnalysisContext::Orbit{m.x, m.v, feed_.pc_map.period()};
    }
    c.chaotic = feed_.pc_map.status() == PoincareMap::Status::Chaotic;
    c.sim_time = feed_.have_last ? feed_.last.t : 0.0;
    return c;
}

void App::apply_analysis(const AnalysisAction& a) {
    for (auto [p, toggle, open] : {std::tuple{PanelId::Plane, a.toggle_plane, a.open_plane},
                                   std::tuple{PanelId::Basins, a.toggle_basins, a.open_basins}}) {
        const bool now = layout_.panel_visible[static_cast<std::size_t>(p)];
        if (toggle || (open && !now)) set_panel_visible(p, !now);
    }
    if (a.xI) set_xi(*a.xI);
    if (a.omega) set_omega(*a.omega);
    if (a.reset) {
        // The basins start every cell at t = 0, phi = 0: the Reset command does the same from (x0, v0).
        run_.x0 = a.reset->first;
        send(SimCommand::reset(a.reset->first, a.reset->second));
        if (run_.paused) set_paused(false);
    }
    if (!a.toast.empty()) toast(a.toast);
}

}  // namespace impactlab::gui
