// The app's side of the analysis views (analysis_panels): what it hands them each frame, and a click's
// requests turned into the app's own commands to the simulation thread. UI thread.
#include "app.hpp"

namespace impactlab::gui {

AnalysisContext App::analysis_context() const {
    AnalysisContext c;
    c.params = &params_;
    c.model = model_name();
    c.omega = omega_;
    c.xI = xI_;
    c.diagram_omega = bif_panel_.omega_axis();
    c.ui_scale = ui_scale_;
    return c;
}

void App::apply_analysis(const AnalysisAction& a) {
    if (a.xI) set_xi(*a.xI);
    if (a.omega) set_omega(*a.omega);
    if (a.reset) {
        // The basins start every cell at t = 0, phi = 0: the Reset command does the same from (x0, v0).
        x0_ = a.reset->first;
        sim_->send(SimCommand::reset(a.reset->first, a.reset->second));
        if (paused_) set_paused(false);
    }
    if (!a.toast.empty()) toast(a.toast);
}

}  // namespace impactlab::gui
