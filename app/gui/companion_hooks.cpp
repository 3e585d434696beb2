// The mouse sets the state, the companion cart and the grazing monitor (issues 9, 11): the App's side of
// them. The physics is the sim thread's (SimEngine: SetState, Hold; SimThread: the companion in lockstep);
// what is checked before a command is sent is state_pick.cpp's; this file sends, lays out and draws.
// UI thread.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app.hpp"
#include "plot2d.hpp"
#include "theme.hpp"
#include "widgets.hpp"

namespace impactlab::gui {

// Magenta: apart from the cart's trace, the section dots and the bumper, in both themes.
ImU32 App::companion_color(float alpha) {
    const ImVec4 c = palette().dark ? ImVec4(0.94f, 0.45f, 0.88f, alpha) : ImVec4(0.66f, 0.13f, 0.58f, alpha);
    return ImGui::ColorConvertFloat4ToU32(c);
}

void App::set_state(double x, double v) {
    const PickedState s = pick_state(x, v, xI_, params_.has_bumper());
    if (!s.note.empty()) toast(s.note);
    sim_->send(SimCommand::set_state(s.x, s.v));
}

void App::set_companion(CompanionMode mode) {
    companion_mode_ = mode;
    companion_.clear();
    const std::string ghost = std::string(stiffness_sets()[static_cast<std::size_t>(stiffness_)].id) +
                              impact_models()[static_cast<std::size_t>(ghost_impact_)].id;
    sim_->send(SimCommand::companion(mode, ghost));
}

void App::plot_click(ClickDelay& delay, bool hovered, bool clicked, double x, double v) {
    if (hovered && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) delay.double_clicked();
    if (clicked) delay.click(x, v, now_s());
    // A double-click gives the plot's view back: the state is set only once none can follow.
    if (const auto p = delay.due(now_s(), ImGui::GetIO().MouseDoubleClickTime)) set_state(p->first, p->second);
}

void App::draw_companion_controls() {
    ImGui::Spacing();
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_SliderGrab]);
    ImGui::TextUnformatted("Companion cart");
    ImGui::PopStyleColor();
    ImGui::Separator();
    const char* modes[] = {"off", "twin 1 µm apart", "ghost under model"};
    int mode = static_cast<int>(companion_mode_);
    const bool ghost = companion_mode_ == CompanionMode::Ghost;
    ImGui::SetNextItemWidth(ghost ? ImGui::GetContentRegionAvail().x * 0.62f : -1.0f);
    if (ImGui::Combo("##companion", &mode, modes, 3)) set_companion(static_cast<CompanionMode>(mode));
    tooltip("A second cart beside the first, on the same forcing and bumper, drawn translucent in the rig, the "
              "phase portrait, the potential and x(t).\ntwin: the same model from x + 1 µm: in chaos the "
              "two part by orders of magnitude (sensitivity to initial conditions), on a periodic orbit they "
              "do not.\nghost: the same state under another impact law (switch C to G and see where they "
              "part).\nA reset, a preset or a click that sets the state starts both again.");
    if (ghost) {
        ImGui::SameLine();
        ImGui::SetNextItemWidth(-1.0f);
        const auto& imps = impact_models();
        if (ImGui::BeginCombo("##ghost", imps[static_cast<std::size_t>(ghost_impact_)].id)) {
            for (std::size_t i = 0; i < imps.size(); ++i) {
                if (ImGui::Selectable(imps[i].id, static_cast<int>(i) == ghost_impact_)) {
                    ghost_impact_ = static_cast<int>(i);
                    set_companion(CompanionMode::Ghost);
                }
                tooltip(imps[i].summary);
            }
            ImGui::EndCombo();
        }
        tooltip("The ghost's impact law; its stiffness is the cart's.");
    }
    if (companion_mode_ != CompanionMode::Off && companion_.have()) {
        const double d = companion_.separation_now(), d0 = companion_.separation_start();
        ImGui::TextDisabled("|Δx|");
        tooltip("The distance between the two carts now, and how many decades it grew since they started.");
        ImGui::SameLine();
        if (companion_mode_ == CompanionMode::Twin && d0 > 0 && d > 0)
            ImGui::Text("%.2e m  (%+.1f decades)", d, std::log10(d / d0));
        else ImGui::Text("%.2e m", d);
    }
}

void App::draw_grazing() {
    ImGui::TextDisabled("bumper gap");
    ImGui::SameLine();
    if (!have_grazing_) {
        ImGui::TextUnformatted(params_.has_bumper() ? "(after a whole forcing period)" : "no bumper");
    } else {
        // xI - max x over the last forcing period: > 0 clear, 0 touching, < 0 pressed into a compliant bumper.
        const double gap = xI_shown_ - grazing_.x;
        if (!params_.has_bumper()) ImGui::TextUnformatted("no bumper");
        else if (std::abs(gap) < 1e-4) ImGui::Text("x_I − max x = %+.2f µm", gap * 1e6);   // near grazing
        else ImGui::Text("x_I − max x = %+.3f mm", gap * 1e3);
    }
    tooltip("The grazing monitor: how close the orbit came to the bumper over the last forcing period. "
              "A grazing bifurcation is coming when the gap shrinks to 0 (from a clear orbit) or the impact "
              "velocity to 0 (from an impacting one).");
    ImGui::TextDisabled("impact");
    ImGui::SameLine();
    if (!have_grazing_ || !params_.has_bumper()) {
        ImGui::TextUnformatted("-");
    } else if (grazing_.energy < 0.5) {
        ImGui::TextUnformatted("none in the last period");
    } else if (params_.rigid()) {
        ImGui::Text("v− = %.4f m/s  (%d in the period)", grazing_.v, static_cast<int>(grazing_.energy));
    } else {
        ImGui::Text("entry %.4f m/s, depth %.1f µm", grazing_.v, grazing_.force * 1e6);
    }
    tooltip("Rigid bumper (G, H): the velocity v− of the last impact in the period. Compliant (C, C1): the "
              "entry velocity of the last contact and the deepest penetration x − x_I.");
}

void App::draw_separation(ImVec2 size) {
    const Palette& pal = palette();
    const History<Separation>& sep = companion_.separation();
    const double t_now = sep.empty() ? last_.t : sep.back().t;
    // From the restart (the growth from 1 um is the point), the last two minutes at most.
    const double t_from = sep.empty() ? t_now - strip_window_ : std::max(sep[0].t, t_now - 120.0);
    Plot plot;
    Axes ax;
    ax.x_label = "t [s]";
    ax.y_label = "log10 |Δx| [m]";
    if (!plot.begin("##separation", size, {t_from, std::max(t_now, t_from + 0.1)}, {-9.0, -1.0}, ax)) return;
    const std::size_t first = sep.lower_bound(t_from, [](const Separation& s) { return s.t; });
    plot.series(sep.size() - first, [&](std::size_t i) {
        const Separation& s = sep[first + i];
        struct { double x, y; } p{s.t, std::log10(std::max(s.dx, 1e-9))};
        return p;
    }, companion_color(1.0f), 1.5f);
    plot.hline(-6.0, pal.grid, 1.0f, true);
    const char* what = companion_mode_ == CompanionMode::Twin ? "twin: |Δx| from 1 µm" : "ghost: |Δx|";
    plot.draw()->AddText(ImVec2(plot.area_min().x + 6, plot.area_min().y + 4), pal.axis_text, what);
    plot.end();
}

void App::rig_mouse(ImVec2 image_min, float fbs) {
    // The rig image's mapping, from two points of RigView::to_image (framebuffer pixels): m -> screen.
    const ImVec2 o = rig_.to_image(0.0, 0.0), e = rig_.to_image(0.01, 0.01);
    const double ppm_x = (e.x - o.x) / 0.01, ppm_y = (o.y - e.y) / 0.01;
    if (!(ppm_x > 0) || !(ppm_y > 0)) return;
    const ImVec2 mouse = ImGui::GetIO().MousePos;
    const double mx = ((mouse.x - image_min.x) * fbs - o.x) / ppm_x;
    const double my = -((mouse.y - image_min.y) * fbs - o.y) / ppm_y;
    const bool hovered = ImGui::IsItemHovered();
    // mx is in the drawing, whose displacements may be magnified (tiles.cpp, RigMagnify): the cart is drawn
    // at draw_x(x), and a drawn distance is gain times the true one.
    const RigMagnify& mag = rig_.magnify();
    const bool on_cart =
        hovered && std::abs(mx - mag.draw_x(last_.x)) <= rig::kCartHalfW && std::abs(my) <= rig::kCartHalfH;
    if (!dragging_cart_ && on_cart) {
        ImGui::SetMouseCursor(ImGuiMouseCursor_Hand);
        if (!ImGui::IsMouseDown(ImGuiMouseButton_Left))
            ImGui::SetTooltip("drag the cart: the simulation holds it at the mouse;\nlet go to start from there at rest");
        if (ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
            dragging_cart_ = true;
            drag_grab_ = last_.x - mx / mag.gain;
            drag_x_ = std::nan("");   // the first frame sends the hold
        }
    }
    if (!dragging_cart_) return;
    ImGui::SetMouseCursor(ImGuiMouseCursor_ResizeEW);
    const PickedState s = pick_state(mx / mag.gain + drag_grab_, 0.0, xI_, params_.has_bumper());
    if (ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
        if (!(std::abs(s.x - drag_x_) <= 1e-6)) {   // moved (each hold restarts the companion too)
            drag_x_ = s.x;
            sim_->send(SimCommand::hold(drag_x_));
        }
        ImGui::SetTooltip("x = %+.2f mm%s", drag_x_ * 1e3, s.note.empty() ? "" : "  (at the bumper)");
    } else {   // let go: from there at rest (a toast says so if the bumper or the rail stopped the hand)
        dragging_cart_ = false;
        set_state(mx / mag.gain + drag_grab_, 0.0);
    }
}

}  // namespace impactlab::gui
