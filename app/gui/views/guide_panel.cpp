#include "guide_panel.hpp"

#include <imgui.h>

#include "render/theme.hpp"

namespace impactlab::gui {

namespace {
constexpr GuideDemo kDemos[kDemoCount] = {
    {"Period doubling", "A1H at ω = 10.6 rad/s, ω ramped slowly to 11.2 at 20x (30 s; the guide folds away).",
     "Watch the Poincaré map: its one point splits in two as ω passes 10.86 rad/s, about 13 s in, and x(t) "
     "repeats every second forcing period."},
    {"The road to chaos", "A1H from ω = 9 rad/s ramped to 16 at 50x, the bifurcation diagram computing beside it.",
     "Watch the green points the ramp leaves over the diagram: one branch, then two near 10.9 rad/s, then a "
     "cloud (chaos) from about 12.8."},
    {"Switching the impact model", "A1C in chaos with a ghost cart under model G (a rigid bumper) from the same state.",
     "Watch the magenta ghost: it follows the cart for a while, then parts; in chaos the bumper's law decides "
     "where the cart goes."},
    {"The energy budget", "A1H in chaos; the Energy balance under State in the controls.",
     "What the unbalance puts in equals kinetic and potential energy plus what friction and the bumper took "
     "out, to about one part in ten million, impacts and all."},
    {"Basins of attraction", "A1G at ω = 13 rad/s, its basins computed (F3).",
     "Two attractors live side by side here: each starting state (x0, v0) is coloured by the one it ends on, "
     "and the borders between them are fine-grained."},
};
}  // namespace

const GuideDemo& guide_demo(int k) { return kDemos[(k < 1 || k > kDemoCount) ? 0 : k - 1]; }

GuideAction GuidePanel::draw(bool* open, int last_demo) {
    GuideAction act;
    const float fs = ImGui::GetFontSize();
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + 0.5f * vp->Size.x, vp->Pos.y + 0.5f * vp->Size.y), ImGuiCond_FirstUseEver,
                            ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowSize(ImVec2(fs * 34.0f, 0), ImGuiCond_FirstUseEver);
    // Folded, only its title bar, narrow (over the controls' corner, not a plot); unfolded, its own width.
    if (collapsed_) ImGui::SetNextWindowSize(ImVec2(fs * 9.0f, 0), ImGuiCond_Always);
    else if (was_collapsed_) ImGui::SetNextWindowSize(ImVec2(fs * 34.0f, 0), ImGuiCond_Always);
    was_collapsed_ = collapsed_;
    if (aside_pending_) {
        ImGui::SetNextWindowSize(ImVec2(fs * 9.0f, 0), ImGuiCond_Always);
        aside_pending_ = false;
        ImGui::SetNextWindowCollapsed(true, ImGuiCond_Always);
        ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + 0.25f * fs, vp->Pos.y + vp->Size.y - 2.0f * fs), ImGuiCond_Always,
                                ImVec2(0.0f, 1.0f));
    }
    const bool shown = ImGui::Begin("What to try###guide", open, ImGuiWindowFlags_NoSavedSettings);
    collapsed_ = ImGui::IsWindowCollapsed();
    const ImVec2 wp = ImGui::GetWindowPos(), ws = ImGui::GetWindowSize();
    rect_[0] = wp.x;
    rect_[1] = wp.y;
    rect_[2] = wp.x + ws.x;
    rect_[3] = wp.y + ws.y;
    if (!shown) {
        ImGui::End();
        return act;
    }
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextUnformatted("A cart on a rail between springs and magnets, shaken by a spinning unbalance, hits a "
                           "bumper. Each button below sets the rig up and says what to look for.");
    ImGui::PopTextWrapPos();
    for (int k = 1; k <= kDemoCount; ++k) {
        const GuideDemo& d = guide_demo(k);
        ImGui::Separator();
        ImGui::PushID(k);
        if (ImGui::Button(k == last_demo ? "Again" : "Show me", ImVec2(fs * 5.0f, 0))) act.demo = k;
        ImGui::PopID();
        ImGui::SameLine();
        ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_SliderGrab]);
        ImGui::Text("%d. %s", k, d.title);
        ImGui::PopStyleColor();
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextDisabled("%s", d.does);
        ImGui::TextUnformatted(d.look_for);
        ImGui::PopTextWrapPos();
    }
    ImGui::Separator();
    ImGui::TextDisabled("Help > What to try opens this again; F1 lists the keys.");
    ImGui::End();
    return act;
}

}  // namespace impactlab::gui
