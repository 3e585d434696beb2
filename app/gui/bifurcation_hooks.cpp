// The app's side of the bifurcation panel (bifurcation_panel): what it hands the panel each frame, and what
// the panel asks for turned into the app's own commands and toasts. UI thread.
#include "app.hpp"

namespace impactlab::gui {

BifurcationContext App::bifurcation_context() {
    BifurcationContext c;
    c.params = &params_;
    c.model = model_name();
    c.omega = omega_;
    c.xI = xI_;
    c.live = &shown_map().points();   // settled section points only (replaying: those of the cursor's instant)
    c.protocol = &bif_protocol_;
    c.steps = &bif_steps_;
    c.overlay = [this](Plot& plot) {
        analysis_.overlay_diagram(plot);
        draw_ramp_points(plot);
    };
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

}  // namespace impactlab::gui
