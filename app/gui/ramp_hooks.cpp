// The app's side of the live omega ramp (omega_ramp.hpp): the row under the omega slider, the command to the
// simulation, and its section points drawn over the bifurcation diagram. UI thread.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "app.hpp"
#include "widgets.hpp"

namespace impactlab::gui {

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
    sim_->send(SimCommand::ramp(target, rate));
    if (paused_) set_paused(false);
    char buf[128];
    std::snprintf(buf, sizeof buf, "ramping ω %.2f → %.2f rad/s at %.3g rad/s per s (%.0f s of simulation)", omega_,
                  target, rate, std::abs(target - omega_) / rate);
    toast(buf);
}

void App::draw_ramp_controls() {
    const float fs = ImGui::GetFontSize();
    if (ramp_.active()) {
        char label[64];
        std::snprintf(label, sizeof label, "Stop ramp (→ %.1f)", ramp_.target());
        if (ImGui::Button(label)) set_omega(omega_);   // holds omega where the ramp got to
        ImGui::SameLine();
        const double done = std::abs(omega_ - ramp_.omega_start()) /
                            std::max(1e-9, std::abs(ramp_.target() - ramp_.omega_start()));
        ImGui::ProgressBar(static_cast<float>(std::clamp(done, 0.0, 1.0)), ImVec2(-1, 0));
        return;
    }
    if (ImGui::Button("Ramp ω")) start_ramp(ramp_target_, ramp_rate_);
    tooltip("Moves ω slowly to the target while the rig runs (the paper's EF protocol, live): the section\n"
                 "points it passes are drawn over the bifurcation diagram, which grows as you watch.\n"
                 "Any other change of ω, a preset or Reset stops it.");
    same_line_or_wrap(fs * 4.2f);
    ImGui::SetNextItemWidth(fs * 4.2f);
    ImGui::DragFloat("##ramp_to", &ramp_target_, 0.05f, 0.0f, static_cast<float>(kMaxOmega), "to %.1f");
    ramp_target_ = std::clamp(ramp_target_, 0.0f, static_cast<float>(kMaxOmega));
    same_line_or_wrap(ImGui::CalcTextSize("0.050 rad/s²").x + 2.0f * ImGui::GetStyle().FramePadding.x);
    ImGui::SetNextItemWidth(-1);
    ImGui::DragFloat("##ramp_rate", &ramp_rate_, 0.001f, static_cast<float>(kMinRampRate),
                     static_cast<float>(kMaxRampRate), "%.3f rad/s²", ImGuiSliderFlags_Logarithmic);
    ramp_rate_ = std::clamp(ramp_rate_, static_cast<float>(kMinRampRate), static_cast<float>(kMaxRampRate));
}

void App::draw_ramp_points(Plot& plot) const {
    const auto& pts = ramp_.points();
    if (pts.empty()) return;
    // Green, apart from the density image's magma ramp and the live points' cyan.
    const ImU32 col = IM_COL32(110, 235, 120, 255);
    struct Dot { double x, y; };
    plot.scatter(pts.size(), [&](std::size_t i) { return Dot{pts[i].omega, pts[i].x}; }, col, 3.0f);
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s ramp: %zu points", ramp_.active() ? "live" : "last", pts.size());
    plot.text(plot.x_range().lo, plot.y_range().hi, buf, col, ImVec2(-0.05f, -1.4f));
}

}  // namespace impactlab::gui
