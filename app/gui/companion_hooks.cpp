// The mouse sets the state, the companion cart and the grazing monitor: the App's side of
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

}  // namespace impactlab::gui
