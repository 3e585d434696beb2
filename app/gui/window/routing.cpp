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
    const std::size_t n = traj_.size();
    if (bench_.window) return n > bench_.window ? n - bench_.window : 0;
    if (n == 0) return 0;
    const double t_from = traj_.back().t - trail_periods_ * kTwoPi / std::max(omega_, 0.5);
    return traj_.lower_bound(t_from, [](const SimMsg& m) { return m.t; });
}

ViewContext App::view_context() const {
    ViewContext c;
    c.traj = &traj_;
    c.sections = &sections_;
    c.map = &shown_map();
    c.last = last_;
    c.have_last = have_last_;
    c.epoch = epoch_;
    c.phi_prev = phi_prev_;
    c.params = &params_;
    c.params_rev = params_rev_;
    c.omega = omega_;
    c.speed = speed_;
    c.xI = xI_;
    c.xI_shown = xI_shown_;
    c.section_phase = section_phase_;
    c.paused = paused_;
    c.sim_paused = sim_->status().paused;
    c.replay = replay_.active();
    c.omega_moving = ramp_.active();
    c.ui_scale = ui_scale_;
    c.frame_dt = frame_dt_;
    c.now = now_s();
    c.trail_first = trail_first();
    c.trail_periods = trail_periods_;
    c.strip_window = strip_window_;
    c.bench_window = bench_.window;
    c.companion = &companion_;
    c.companion_mode = companion_mode_;
    c.companion_name = companion_mode_ == CompanionMode::Twin
                           ? std::string("twin")
                           : "ghost " + std::string(impact_models()[static_cast<std::size_t>(ghost_impact_)].id);
    c.magnify = magnification();
    c.frame_max_force = frame_max_force_;
    c.flash = flash_;
    c.impact_label = &impact_label_;
    return c;
}

void App::apply_view(const ViewAction& a) {
    if (a.hold) send(SimCommand::hold(*a.hold));   // each hold restarts the companion too
    if (a.set_state) set_state(a.set_state->first, a.set_state->second);
    if (a.start_orbit) restart_at_section(a.start_orbit->first, a.start_orbit->second);
    if (a.section_phase) set_section_phase(*a.section_phase);
}

void App::set_section_phase(double phi0) {
    if (phi0 == section_phase_) return;
    section_phase_ = phi0;
    // The orbits the clicker took belong to the old section: not to be mixed with the new one's points
    // (the map and the sections clear at the engine's new epoch).
    poincare_.clear_orbits();
    send(SimCommand::section_phase(phi0));
}

void App::start_orbit(double x, double v) {
    poincare_.start_orbit(x, v, epoch_);
    restart_at_section(x, v);
}

void App::restart_at_section(double x, double v) {
    // The orbit starts on the section: at the next phi = phi0 + 2 pi k (the forcing's phase moves on to
    // it), from (x, v) checked as a click in the phase portrait is (rail, bumper). The phase is written as
    // the core's Simulator::section_phi writes it, 2 pi n - psi, so the engine takes it for that section.
    const PickedState s = pick_state(x, v, xI_, params_.has_bumper());
    if (!s.note.empty()) toast(s.note);
    const double psi = section_phase_ > 0.0 ? kTwoPi - section_phase_ : 0.0;
    const double phi = kTwoPi * std::ceil((last_.phi + psi) / kTwoPi - 1e-9) - psi;
    restart_sim(s.x, s.v, last_.t, phi, omega_, false);
}

DataPanelContext App::data_context() const {
    DataPanelContext c;
    c.model = model_name();
    c.xI = xI_;
    c.ui_scale = ui_scale_;
    return c;
}

void App::set_state(double x, double v) {
    const PickedState s = pick_state(x, v, xI_, params_.has_bumper());
    if (!s.note.empty()) toast(s.note);
    send(SimCommand::set_state(s.x, s.v));
}

void App::set_companion(CompanionMode mode) {
    companion_mode_ = mode;
    companion_.clear();
    const std::string ghost = std::string(stiffness_sets()[static_cast<std::size_t>(stiffness_)].id) +
                              impact_models()[static_cast<std::size_t>(ghost_impact_)].id;
    send(SimCommand::companion(mode, ghost));
}

void App::start_ramp(double target, double rate) {
    if (const std::string err = OmegaRamp::check(target, rate, kMaxOmega, kMinRampRate, kMaxRampRate); !err.empty()) {
        toast(err);
        return;
    }
    if (std::abs(target - omega_) < 1e-6) {
        toast("ramp: ω is already " + std::to_string(target).substr(0, 5) + " rad/s");
        return;
    }
    ramp_.begin(omega_, target, rate);
    send(SimCommand::ramp(target, rate));
    if (paused_) set_paused(false);
    char buf[128];
    std::snprintf(buf, sizeof buf, "ramping ω %.2f → %.2f rad/s at %.3g rad/s per s (%.0f s of simulation)", omega_,
                  target, rate, std::abs(target - omega_) / rate);
    toast(buf);
}

BifurcationContext App::bifurcation_context() {
    BifurcationContext c;
    c.params = &params_;
    c.model = model_name();
    c.omega = omega_;
    c.xI = xI_;
    // Settled section points only (replaying: those of the cursor's instant); the diagram's sections are at
    // phi = 2 pi n, so the map's at another phase would not lie on it.
    const bool strobe = section_phase_ == 0.0 || section_phase_ == kTwoPi;
    c.live = strobe ? &shown_map().points() : nullptr;
    c.protocol = &bif_protocol_;
    c.steps = &bif_steps_;
    c.ramp = &ramp_;
    c.overlay = [this](Plot& plot) { analysis_.overlay_diagram(plot); };
    c.overlay_legend = [this](bool compact) { analysis_.overlay_legend(compact); };
    if (const auto& ov = analysis_.overlay()) c.branches = &*ov;
    return c;
}

void App::start_bifurcation() {
    if (const std::string err = bif_panel_.start(bifurcation_context()); !err.empty()) toast(err);
}

void App::poll_bifurcation() {
    if (bif_dirty_) {   // the theme or the fonts changed
        bif_panel_.mark_dirty();
        bif_dirty_ = false;
    }
    if (const std::string msg = bif_panel_.poll(bifurcation_context()); !msg.empty()) toast(msg);
}

void App::draw_bifurcation() {
    const BifurcationAction act = bif_panel_.draw(bifurcation_context());
    if (act.omega) set_omega(*act.omega);
    if (!act.toast.empty()) toast(act.toast);
}

AnalysisContext App::analysis_context() const {
    AnalysisContext c;
    c.params = &params_;
    c.model = model_name();
    c.omega = omega_;
    c.xI = xI_;
    c.diagram_omega = bif_panel_.omega_axis();
    c.ui_scale = ui_scale_;
    c.plane_open = panel_visible_[static_cast<std::size_t>(PanelId::Plane)];
    c.basins_open = panel_visible_[static_cast<std::size_t>(PanelId::Basins)];
    // The live map (not a replayed one): continuation starts from what runs now.
    if (pc_map_.status() == PoincareMap::Status::Periodic && !pc_map_.points().empty()) {
        const MapPoint& m = pc_map_.points().back();
        c.orbit = AnalysisContext::Orbit{m.x, m.v, pc_map_.period()};
    }
    c.chaotic = pc_map_.status() == PoincareMap::Status::Chaotic;
    c.sim_time = have_last_ ? last_.t : 0.0;
    return c;
}

void App::apply_analysis(const AnalysisAction& a) {
    for (auto [p, toggle, open] : {std::tuple{PanelId::Plane, a.toggle_plane, a.open_plane},
                                   std::tuple{PanelId::Basins, a.toggle_basins, a.open_basins}}) {
        const bool now = panel_visible_[static_cast<std::size_t>(p)];
        if (toggle || (open && !now)) set_panel_visible(p, !now);
    }
    if (a.xI) set_xi(*a.xI);
    if (a.omega) set_omega(*a.omega);
    if (a.reset) {
        // The basins start every cell at t = 0, phi = 0: the Reset command does the same from (x0, v0).
        x0_ = a.reset->first;
        send(SimCommand::reset(a.reset->first, a.reset->second));
        if (paused_) set_paused(false);
    }
    if (!a.toast.empty()) toast(a.toast);
}

}  // namespace impactlab::gui
