// The controls column (App::draw_controls in tiles.cpp stacks or tabs its three groups): the model, the
// forcing and the bumper, the run, the presets, the omega ramp, the companion cart, the display settings,
// the state, the grazing monitor and the energy budget. Each widget calls the App's actions. UI thread.
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "window/app.hpp"
#include "views/contact_label.hpp"
#include "views/energy_bar.hpp"
#include "render/gl_util.hpp"
#include "impactlab/forces.hpp"
#include "impactlab/sweep.hpp"
#include "render/theme.hpp"
#include "views/view_fit.hpp"
#include "render/widgets.hpp"

namespace impactlab::gui {

namespace {

void section(const char* label) {
    ImGui::Spacing();
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_SliderGrab]);
    ImGui::TextUnformatted(label);
    ImGui::PopStyleColor();
    ImGui::Separator();
}

}  // namespace

void App::draw_controls_run() {
    const auto& stiff = stiffness_sets();
    const auto& imps = impact_models();
    const float full = ImGui::GetContentRegionAvail().x;

    // Model: title and the two live combos.
    ImGui::TextUnformatted("Model");
    ImGui::SameLine();
    ImGui::TextColored(ImGui::GetStyle().Colors[ImGuiCol_SliderGrab], "%s", model_name().c_str());
    if (!layout_.frame.controls_narrow) {   // a narrow column (large UI scale) keeps the words for the tooltip
        ImGui::SameLine();
        ImGui::TextDisabled("(live: keeps x, v, φ)");
    }
    ImGui::SetNextItemWidth(full * 0.40f);
    if (ImGui::BeginCombo("##stiffness", stiff[static_cast<std::size_t>(run_.stiffness)].id)) {
        for (std::size_t i = 0; i < stiff.size(); ++i) {
            if (ImGui::Selectable(stiff[i].id, static_cast<int>(i) == run_.stiffness)) set_model(static_cast<int>(i), run_.impact);
            tooltip(stiff[i].summary);
        }
        ImGui::EndCombo();
    }
    tooltip("Stiffness version (Table 1): springs, magnets, bearing resistance, unbalance.  K cycles.");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(-1);
    if (ImGui::BeginCombo("##impact", imps[static_cast<std::size_t>(run_.impact)].id)) {
        for (std::size_t i = 0; i < imps.size(); ++i) {
            char label[96];
            const char* kind = imps[i].kind == ImpactKind::Rigid       ? "rigid, event-driven"
                               : imps[i].kind == ImpactKind::Compliant ? "compliant Hunt-Crossley"
                                                                       : "no bumper";
            std::snprintf(label, sizeof label, "%-4s %s", imps[i].id, kind);
            if (ImGui::Selectable(label, static_cast<int>(i) == run_.impact)) set_model(run_.stiffness, static_cast<int>(i));
            tooltip(imps[i].summary);
        }
        ImGui::EndCombo();
    }
    tooltip("Impact model (Tables 2, 3): C, C1 compliant; G instantaneous; H finite duration; none: no bumper.  M cycles.");

    section("Forcing and bumper");
    float w = static_cast<float>(run_.omega);
    ImGui::SetNextItemWidth(-1);
    if (ImGui::SliderFloat("##omega", &w, 0.0f, 30.0f, "ω = %.2f rad/s")) set_omega(w);
    tooltip("Speed of the unbalance (Left/Right: -/+0.1, with Shift: 1). Drag it from 9 to 13 to watch the "
            "period-doubling cascade.");
    if (ImGui::Button("-1")) set_omega(run_.omega - 1);
    same_line_or_wrap(button_width("-.1"));
    if (ImGui::Button("-.1")) set_omega(run_.omega - 0.1);
    same_line_or_wrap(button_width("+.1"));
    if (ImGui::Button("+.1")) set_omega(run_.omega + 0.1);
    same_line_or_wrap(button_width("+1"));
    if (ImGui::Button("+1")) set_omega(run_.omega + 1);
    if (run_.omega > 0) {
        char period[32];
        std::snprintf(period, sizeof period, layout_.frame.controls_narrow ? "%.2f s" : "T = %.3f s", kTwoPi / run_.omega);
        same_line_or_wrap(ImGui::CalcTextSize(period).x);
        ImGui::TextDisabled("%s", period);
    }
    draw_ramp_controls();
    float xi_mm = static_cast<float>(run_.xI * 1e3);
    ImGui::SetNextItemWidth(-1);
    if (ImGui::SliderFloat("##xI", &xi_mm, -20.0f, 20.0f, "bumper x_I = %.1f mm")) set_xi(xi_mm * 1e-3);
    tooltip("Position of the one-sided bumper (Up/Down: +/-0.5 mm). x = 0 is the hilltop between the wells. "
            "Moving it onto the cart pushes the cart back to the contact point.");

    section("Run");
    const float bw = (full - 2 * ImGui::GetStyle().ItemSpacing.x) / 3.0f;
    if (ImGui::Button(run_.paused ? "Play" : "Pause", ImVec2(bw, 0))) set_paused(!run_.paused);
    tooltip("Space");
    ImGui::SameLine();
    if (ImGui::Button(layout_.frame.controls_narrow ? "Step" : "Step period", ImVec2(bw, 0))) step_period();
    tooltip("N: run to the next Poincare section, then pause");
    ImGui::SameLine();
    if (ImGui::Button("Reset", ImVec2(bw, 0))) reset();
    tooltip("R: t = 0, φ = 0, the cart at rest at x0 (the left well)");
    float sp = static_cast<float>(run_.speed);
    ImGui::SetNextItemWidth(-1);
    if (ImGui::SliderFloat("##speed", &sp, 0.01f, 100.0f, "speed %.2fx real time", ImGuiSliderFlags_Logarithmic))
        set_speed(sp);
    tooltip("Simulated seconds per real second ( [ and ] halve and double ).");

    section("Presets (keys 1-4)");
    const auto list = presets_for(model_name());
    const float pw = (full - ImGui::GetStyle().ItemSpacing.x) / 2.0f;
    for (std::size_t i = 0; i < list.size(); ++i) {
        char label[64];
        std::snprintf(label, sizeof label, "%zu  %s", i + 1, list[i].label);
        if (ImGui::Button(label, ImVec2(pw, 0))) apply_preset(list[i]);
        char tip[320];
        char per[32];
        if (list[i].period > 0) std::snprintf(per, sizeof per, "period %d", list[i].period);
        else std::snprintf(per, sizeof per, "chaotic");
        std::snprintf(tip, sizeof tip, "%s\nω = %.2f rad/s, from rest at x = %.1f mm, x_I = 0: %s after ~400 periods",
                      list[i].note, list[i].omega, list[i].x0 * 1e3, per);
        tooltip(tip);
        if (i % 2 == 0 && i + 1 < list.size()) ImGui::SameLine();
    }

    draw_companion_controls();
}

void App::draw_controls_view() {
    const float full = ImGui::GetContentRegionAvail().x;
    section("Display");
    const float half = (full - ImGui::GetStyle().ItemSpacing.x) / 2.0f;
    ImGui::SetNextItemWidth(half);
    ImGui::SliderFloat("##trail", &view_.trail_periods, 1.0f, 60.0f, "trail %.0f periods");
    tooltip("Length of the fading trail in the phase portrait, in forcing periods.");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(half);
    ImGui::SliderFloat("##window", &view_.strip_window, 0.5f, 60.0f, "x(t) %.1f s", ImGuiSliderFlags_Logarithmic);
    tooltip("Time span of the scrolling x(t) strip.");
    if (ImGui::Checkbox("dark", &view_.dark)) {
        apply_theme(view_.dark, view_.ui_scale);
        bif_.dirty = true;
    }
    tooltip("T: dark or light theme (light reads better on a projector).");
    ImGui::SameLine();
    // The scale applies when the slider is released (rebuilding the font under the mouse would jump).
    static bool editing = false;
    static float scale_edit = 1.0f;
    if (!editing) scale_edit = view_.ui_scale;
    ImGui::SetNextItemWidth(-1);
    ImGui::SliderFloat("##scale", &scale_edit, 0.75f, 3.0f, "UI scale %.2f");
    editing = ImGui::IsItemActive();
    if (ImGui::IsItemDeactivatedAfterEdit()) {
        view_.ui_scale = std::round(scale_edit * 4.0f) / 4.0f;
        view_.fonts_dirty = true;
    }
    tooltip("Ctrl + / Ctrl -: size of text and controls, for projectors.");
    // The rig's displacement magnification (the drawing only) and presentation mode (tiles.cpp).
    float g = static_cast<float>(magnification());
    ImGui::SetNextItemWidth(half);
    if (ImGui::SliderFloat("##magnify", &g, 1.0f, 10.0f, "rig disp. ×%.1f")) set_magnification(g);
    tooltip("Magnifies the cart's displacement from x = 0 in the rig's drawing only (cart and bumper alike,\n"
            "so a contact still looks like one); the rig's title says so. Presentation mode has its own (×3).");
    ImGui::SameLine();
    if (ImGui::Button(layout_.frame.controls_narrow ? "Present" : "Presentation", ImVec2(-1, 0))) set_presentation(true);
    tooltip("P: the rig and one plot, large, with a slim bar of controls (P or Esc to come back).");
    const float tw = (full - 2 * ImGui::GetStyle().ItemSpacing.x) / 3.0f;
    const bool narrow = layout_.frame.controls_narrow;
    if (ImGui::Button(narrow ? "Clear" : "Clear map", ImVec2(tw, 0))) clear_poincare();
    tooltip("C: clear the Poincare map");
    ImGui::SameLine();
    if (ImGui::Button(narrow ? "PNG" : "Screenshot", ImVec2(tw, 0))) screenshot(screenshot_name());
    tooltip("F12: the whole window as PNG, in the current folder");
    ImGui::SameLine();
    if (ImGui::Button(narrow ? "CSV" : "Export CSV", ImVec2(tw, 0))) export_csv();
    tooltip("Ctrl+E: the trajectory in memory and the Poincare points as CSV files");
}

void App::draw_controls_state() {
    section("State");
    if (ImGui::BeginTable("state", 4, ImGuiTableFlags_SizingStretchProp)) {
        auto cell = [](const char* k, const char* text) {
            ImGui::TableNextColumn();
            ImGui::TextDisabled("%s", k);
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(text);
        };
        char b1[48];
        ImGui::TableNextRow();
        std::snprintf(b1, sizeof b1, "%.3f s", feed_.last.t);
        cell("t", b1);
        std::snprintf(b1, sizeof b1, "%+.3f mm", feed_.last.x * 1e3);
        cell("x", b1);
        ImGui::TableNextRow();
        std::snprintf(b1, sizeof b1, "%.3f rad", std::fmod(feed_.last.phi, kTwoPi));
        cell("φ", b1);
        std::snprintf(b1, sizeof b1, "%+.4f m/s", feed_.last.v);
        cell("v", b1);
        ImGui::TableNextRow();
        std::snprintf(b1, sizeof b1, "%+.2f mJ", feed_.last.energy * 1e3);
        cell("E", b1);
        std::snprintf(b1, sizeof b1, "%llu", static_cast<unsigned long long>(feed_.impacts_seen));
        cell("impacts", b1);
        ImGui::EndTable();
    }
    ImGui::TextDisabled("regime");
    ImGui::SameLine();
    ImGui::TextUnformatted(contact_label(run_.params, feed_.last.regime, feed_.last.force));
    draw_grazing();
    lyapunov_live_.update(run_.params, run_.omega, feed_.last.x, feed_.last.v, now_s());
    ImGui::TextDisabled("λ_max");
    ImGui::SameLine();
    ImGui::TextUnformatted(lyapunov_live_.text().c_str());
    tooltip("The largest Lyapunov exponent at this ω, recomputed on a worker every 3 s from the current state\n"
            "(20 periods to settle, 60 averaged): positive on a chaotic attractor, negative on a periodic one.");

    section("Forces on the cart [N]");
    // The terms of Eq. (1) at this instant (core's force_terms), signed as they push the cart.
    const ForceTerms f = force_terms(run_.params, feed_.last.t, feed_.last.x, feed_.last.v, feed_.last.phi, feed_.last.omega, 0.0);
    const double magnets = -(f.spring_magnet - run_.params.k * feed_.last.x), springs = -run_.params.k * feed_.last.x;
    const double bumper = std::max(feed_.last.force, f.impact) > 0 ? -std::max(feed_.last.force, f.impact) : 0.0;
    struct Bar { const char* name; double value; };
    const Bar bars[] = {{"unbalance", f.unbalance}, {"springs", springs}, {"magnets", magnets},
                        {"resistance", -f.resistance}, {"bumper", bumper}};
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const Palette& pal = palette();
    const float label_w = ImGui::CalcTextSize("resistance ").x;
    const float bar_w = ImGui::GetContentRegionAvail().x - label_w - ImGui::CalcTextSize("-00.0").x - 8;
    const double full_scale = 20.0;   // [N] at the end of a bar (longer bars are clipped)
    const float line_x = ImGui::GetCursorPosX();
    for (const Bar& b : bars) {
        ImGui::TextDisabled("%s", b.name);
        ImGui::SameLine(line_x + label_w);
        const ImVec2 p = ImGui::GetCursorScreenPos();
        const float h = ImGui::GetTextLineHeight();
        const float mid = p.x + 0.5f * bar_w;
        const float len = static_cast<float>(std::clamp(b.value / full_scale, -1.0, 1.0)) * 0.5f * bar_w;
        dl->AddRectFilled(ImVec2(p.x, p.y + 2), ImVec2(p.x + bar_w, p.y + h - 2), pal.plot_bg, 2.0f);
        dl->AddRectFilled(ImVec2(std::min(mid, mid + len), p.y + 3), ImVec2(std::max(mid, mid + len), p.y + h - 3),
                          b.value >= 0 ? pal.trace : pal.trace2, 2.0f);
        dl->AddLine(ImVec2(mid, p.y + 1), ImVec2(mid, p.y + h - 1), pal.plot_frame);
        ImGui::Dummy(ImVec2(bar_w, h));
        ImGui::SameLine();
        ImGui::Text("%+.1f", std::abs(b.value) < 0.05 ? 0.0 : b.value);   // no "-0.0"
    }

    section("Energy balance");
    tooltip("Since the last change of model, x_I or state: the energy at the start plus the work of the\n"
            "unbalance (in) against kinetic, potential (above the well's floor) and what the resistance and\n"
            "the bumper dissipated (out). Each term is integrated on its own, so the two bars agree only if\n"
            "the simulation conserves energy as it should.");
    if (run_.energy_floor_rev != run_.params_rev) {
        run_.energy_floor = potential_floor(run_.params);
        run_.energy_floor_rev = run_.params_rev;
    }
    const EnergyBalance eb = sim_->status().energy;
    draw_energy_bars(energy_bars(eb, run_.params.m, run_.energy_floor), eb.t0, eb.t);
}

void App::draw_ramp_controls() {
    const float fs = ImGui::GetFontSize();
    if (ramp_.live.active()) {
        char label[64];
        std::snprintf(label, sizeof label, "Stop ramp (→ %.1f)", ramp_.live.target());
        if (ImGui::Button(label)) set_omega(run_.omega);   // holds omega where the ramp got to
        ImGui::SameLine();
        const double done = std::abs(run_.omega - ramp_.live.omega_start()) /
                            std::max(1e-9, std::abs(ramp_.live.target() - ramp_.live.omega_start()));
        ImGui::ProgressBar(static_cast<float>(std::clamp(done, 0.0, 1.0)), ImVec2(-1, 0));
        return;
    }
    if (ImGui::Button("Ramp ω")) start_ramp(ramp_.target, ramp_.rate);
    tooltip("Moves ω slowly to the target while the rig runs (the paper's EF protocol, live): the section\n"
                 "points it passes are drawn over the bifurcation diagram, which grows as you watch.\n"
                 "Any other change of ω, a preset or Reset stops it.");
    same_line_or_wrap(fs * 4.2f);
    ImGui::SetNextItemWidth(fs * 4.2f);
    ImGui::DragFloat("##ramp_to", &ramp_.target, 0.05f, 0.0f, static_cast<float>(kMaxOmega), "to %.1f");
    ramp_.target = std::clamp(ramp_.target, 0.0f, static_cast<float>(kMaxOmega));
    same_line_or_wrap(ImGui::CalcTextSize("0.050 rad/s²").x + 2.0f * ImGui::GetStyle().FramePadding.x);
    ImGui::SetNextItemWidth(-1);
    ImGui::DragFloat("##ramp_rate", &ramp_.rate, 0.001f, static_cast<float>(kMinRampRate),
                     static_cast<float>(kMaxRampRate), "%.3f rad/s²", ImGuiSliderFlags_Logarithmic);
    ramp_.rate = std::clamp(ramp_.rate, static_cast<float>(kMinRampRate), static_cast<float>(kMaxRampRate));
}

void App::draw_companion_controls() {
    ImGui::Spacing();
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_SliderGrab]);
    ImGui::TextUnformatted("Companion cart");
    ImGui::PopStyleColor();
    ImGui::Separator();
    const char* modes[] = {"off", "twin 1 µm apart", "ghost under model"};
    int mode = static_cast<int>(companion_.mode);
    const bool ghost = companion_.mode == CompanionMode::Ghost;
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
        if (ImGui::BeginCombo("##ghost", imps[static_cast<std::size_t>(companion_.ghost_impact)].id)) {
            for (std::size_t i = 0; i < imps.size(); ++i) {
                if (ImGui::Selectable(imps[i].id, static_cast<int>(i) == companion_.ghost_impact)) {
                    companion_.ghost_impact = static_cast<int>(i);
                    set_companion(CompanionMode::Ghost);
                }
                tooltip(imps[i].summary);
            }
            ImGui::EndCombo();
        }
        tooltip("The ghost's impact law; its stiffness is the cart's.");
    }
    if (companion_.mode != CompanionMode::Off && companion_.track.have()) {
        const double d = companion_.track.separation_now(), d0 = companion_.track.separation_start();
        ImGui::TextDisabled("|Δx|");
        tooltip("The distance between the two carts now, and how many decades it grew since they started.");
        ImGui::SameLine();
        if (companion_.mode == CompanionMode::Twin && d0 > 0 && d > 0)
            ImGui::Text("%.2e m  (%+.1f decades)", d, std::log10(d / d0));
        else ImGui::Text("%.2e m", d);
    }
}

void App::draw_grazing() {
    ImGui::TextDisabled("bumper gap");
    ImGui::SameLine();
    if (!feed_.have_grazing) {
        ImGui::TextUnformatted(run_.params.has_bumper() ? "(after a whole forcing period)" : "no bumper");
    } else {
        // xI - max x over the last forcing period: > 0 clear, 0 touching, < 0 pressed into a compliant bumper.
        const double gap = feed_.xI_shown - feed_.grazing.x;
        if (!run_.params.has_bumper()) ImGui::TextUnformatted("no bumper");
        else if (std::abs(gap) < 1e-4) ImGui::Text("x_I − max x = %+.2f µm", gap * 1e6);   // near grazing
        else ImGui::Text("x_I − max x = %+.3f mm", gap * 1e3);
    }
    tooltip("The grazing monitor: how close the orbit came to the bumper over the last forcing period. "
              "A grazing bifurcation is coming when the gap shrinks to 0 (from a clear orbit) or the impact "
              "velocity to 0 (from an impacting one).");
    ImGui::TextDisabled("impact");
    ImGui::SameLine();
    if (!feed_.have_grazing || !run_.params.has_bumper()) {
        ImGui::TextUnformatted("-");
    } else if (feed_.grazing.energy < 0.5) {
        ImGui::TextUnformatted("none in the last period");
    } else if (run_.params.rigid()) {
        ImGui::Text("v− = %.4f m/s  (%d in the period)", feed_.grazing.v, static_cast<int>(feed_.grazing.energy));
    } else {
        ImGui::Text("entry %.4f m/s, depth %.1f µm", feed_.grazing.v, feed_.grazing.force * 1e6);
    }
    tooltip("Rigid bumper (G, H): the velocity v− of the last impact in the period. Compliant (C, C1): the "
              "entry velocity of the last contact and the deepest penetration x − x_I.");
}

}  // namespace impactlab::gui
