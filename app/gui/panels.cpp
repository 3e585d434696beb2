// The windows of the visualiser, tiled over the main viewport: controls on the left; the rig and the
// bifurcation diagram on top; phase portrait, Poincare map and potential well in the middle; x(t) below.
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

#include "app.hpp"
#include "contact_label.hpp"
#include "energy_bar.hpp"
#include "gl_util.hpp"
#include "impactlab/forces.hpp"
#include "impactlab/sweep.hpp"
#include "theme.hpp"
#include "view_fit.hpp"
#include "widgets.hpp"

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

DataPanelContext App::data_context() const {
    DataPanelContext c;
    c.model = model_name();
    c.xI = xI_;
    c.ui_scale = ui_scale_;
    return c;
}

void App::draw_menu() {
    if (!ImGui::BeginMainMenuBar()) return;
    if (ImGui::BeginMenu("File")) {
        if (ImGui::MenuItem("Screenshot (PNG)", "F12")) screenshot(screenshot_name());
        if (ImGui::MenuItem("Export trajectory + sections (CSV)", "Ctrl+E")) export_csv();
        if (ImGui::MenuItem("Export clip (PNG frames, video)...")) clip_window_ = true;
        ImGui::Separator();
        if (ImGui::MenuItem("Save session...", "Ctrl+S")) open_session_window(true);
        if (ImGui::MenuItem("Load session...", "Ctrl+O")) open_session_window(false);
        ImGui::Separator();
        if (ImGui::MenuItem("Measured data (load, fit, effects)...", nullptr, show_data_)) show_data_ = !show_data_;
        ImGui::Separator();
        if (ImGui::MenuItem("Quit", "Ctrl+Q")) glfwSetWindowShouldClose(win_, 1);
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Simulation")) {
        if (ImGui::MenuItem(paused_ ? "Play" : "Pause", "Space")) set_paused(!paused_);
        if (ImGui::MenuItem("Step one forcing period", "N")) step_period();
        if (ImGui::MenuItem("Reset (t = 0, from x0 at rest)", "R")) reset();
        ImGui::Separator();
        if (ImGui::MenuItem("Faster x2", "]")) set_speed(speed_ * 2);
        if (ImGui::MenuItem("Slower /2", "[")) set_speed(speed_ / 2);
        if (ImGui::MenuItem("Real time (1x)")) set_speed(1.0);
        ImGui::Separator();
        if (ImGui::MenuItem("Clear Poincare map", "C")) clear_poincare();
        ImGui::Separator();
        if (ImGui::MenuItem("Replay the last minutes", "Shift+R", replay_.active())) {
            if (replay_.active()) replay_request_ = ReplayRequest::Leave;
            else enter_replay();
        }
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("View")) {
        draw_view_menu_panels();   // tiles.cpp: presentation, panels, maximise, magnification
        ImGui::Separator();
        if (ImGui::MenuItem("Parameters (m, c, k, ..., the impact law's)...", "F4", show_params_)) show_params_ = !show_params_;
        if (ImGui::MenuItem("Details in the status bar (epoch, samples, dropped)", nullptr, details_)) details_ = !details_;
        if (ImGui::MenuItem("Dark theme", "T", dark_)) {
            dark_ = !dark_;
            apply_theme(dark_, ui_scale_);
            bif_dirty_ = true;
        }
        if (ImGui::BeginMenu("UI scale")) {
            for (float s : {0.75f, 1.0f, 1.25f, 1.5f, 2.0f, 2.5f, 3.0f}) {
                char label[16];
                std::snprintf(label, sizeof label, "%.0f%%", s * 100);
                if (ImGui::MenuItem(label, nullptr, std::abs(ui_scale_ - s) < 0.01f)) {
                    ui_scale_ = s;
                    fonts_dirty_ = true;
                }
            }
            ImGui::EndMenu();
        }
        ImGui::EndMenu();
    }
    analysis_.menu(analysis_context());
    if (ImGui::BeginMenu("Help")) {
        if (ImGui::MenuItem("What to try (five demonstrations)...", nullptr, show_guide_)) show_guide_ = !show_guide_;
        if (ImGui::MenuItem("Keyboard shortcuts", "F1")) show_help_ = true;
        ImGui::EndMenu();
    }
    // Right side: model, omega, fps.
    char right[96];
    std::snprintf(right, sizeof right, "%s   ω %.2f rad/s   %.0f fps", model_name().c_str(), omega_, fps_);
    const float w = ImGui::CalcTextSize(right).x;
    ImGui::SameLine(ImGui::GetWindowWidth() - w - 14.0f * ui_scale_);
    ImGui::TextDisabled("%s", right);
    ImGui::EndMainMenuBar();
}

void App::draw_controls_run() {
    const auto& stiff = stiffness_sets();
    const auto& imps = impact_models();
    const float full = ImGui::GetContentRegionAvail().x;

    // Model: title and the two live combos.
    ImGui::TextUnformatted("Model");
    ImGui::SameLine();
    ImGui::TextColored(ImGui::GetStyle().Colors[ImGuiCol_SliderGrab], "%s", model_name().c_str());
    if (!layout_.controls_narrow) {   // a narrow column (large UI scale) keeps the words for the tooltip
        ImGui::SameLine();
        ImGui::TextDisabled("(live: keeps x, v, φ)");
    }
    ImGui::SetNextItemWidth(full * 0.40f);
    if (ImGui::BeginCombo("##stiffness", stiff[static_cast<std::size_t>(stiffness_)].id)) {
        for (std::size_t i = 0; i < stiff.size(); ++i) {
            if (ImGui::Selectable(stiff[i].id, static_cast<int>(i) == stiffness_)) set_model(static_cast<int>(i), impact_);
            tooltip(stiff[i].summary);
        }
        ImGui::EndCombo();
    }
    tooltip("Stiffness version (Table 1): springs, magnets, bearing resistance, unbalance.  K cycles.");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(-1);
    if (ImGui::BeginCombo("##impact", imps[static_cast<std::size_t>(impact_)].id)) {
        for (std::size_t i = 0; i < imps.size(); ++i) {
            char label[96];
            const char* kind = imps[i].kind == ImpactKind::Rigid       ? "rigid, event-driven"
                               : imps[i].kind == ImpactKind::Compliant ? "compliant Hunt-Crossley"
                                                                       : "no bumper";
            std::snprintf(label, sizeof label, "%-4s %s", imps[i].id, kind);
            if (ImGui::Selectable(label, static_cast<int>(i) == impact_)) set_model(stiffness_, static_cast<int>(i));
            tooltip(imps[i].summary);
        }
        ImGui::EndCombo();
    }
    tooltip("Impact model (Tables 2, 3): C, C1 compliant; G instantaneous; H finite duration; none: no bumper.  M cycles.");

    section("Forcing and bumper");
    float w = static_cast<float>(omega_);
    ImGui::SetNextItemWidth(-1);
    if (ImGui::SliderFloat("##omega", &w, 0.0f, 30.0f, "ω = %.2f rad/s")) set_omega(w);
    tooltip("Speed of the unbalance (Left/Right: -/+0.1, with Shift: 1). Drag it from 9 to 13 to watch the "
            "period-doubling cascade.");
    if (ImGui::Button("-1")) set_omega(omega_ - 1);
    same_line_or_wrap(button_width("-.1"));
    if (ImGui::Button("-.1")) set_omega(omega_ - 0.1);
    same_line_or_wrap(button_width("+.1"));
    if (ImGui::Button("+.1")) set_omega(omega_ + 0.1);
    same_line_or_wrap(button_width("+1"));
    if (ImGui::Button("+1")) set_omega(omega_ + 1);
    if (omega_ > 0) {
        char period[32];
        std::snprintf(period, sizeof period, layout_.controls_narrow ? "%.2f s" : "T = %.3f s", kTwoPi / omega_);
        same_line_or_wrap(ImGui::CalcTextSize(period).x);
        ImGui::TextDisabled("%s", period);
    }
    draw_ramp_controls();
    float xi_mm = static_cast<float>(xI_ * 1e3);
    ImGui::SetNextItemWidth(-1);
    if (ImGui::SliderFloat("##xI", &xi_mm, -20.0f, 20.0f, "bumper x_I = %.1f mm")) set_xi(xi_mm * 1e-3);
    tooltip("Position of the one-sided bumper (Up/Down: +/-0.5 mm). x = 0 is the hilltop between the wells. "
            "Moving it onto the cart pushes the cart back to the contact point.");

    section("Run");
    const float bw = (full - 2 * ImGui::GetStyle().ItemSpacing.x) / 3.0f;
    if (ImGui::Button(paused_ ? "Play" : "Pause", ImVec2(bw, 0))) set_paused(!paused_);
    tooltip("Space");
    ImGui::SameLine();
    if (ImGui::Button(layout_.controls_narrow ? "Step" : "Step period", ImVec2(bw, 0))) step_period();
    tooltip("N: run to the next Poincare section, then pause");
    ImGui::SameLine();
    if (ImGui::Button("Reset", ImVec2(bw, 0))) reset();
    tooltip("R: t = 0, φ = 0, the cart at rest at x0 (the left well)");
    float sp = static_cast<float>(speed_);
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
    ImGui::SliderFloat("##trail", &trail_periods_, 1.0f, 60.0f, "trail %.0f periods");
    tooltip("Length of the fading trail in the phase portrait, in forcing periods.");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(half);
    ImGui::SliderFloat("##window", &strip_window_, 0.5f, 60.0f, "x(t) %.1f s", ImGuiSliderFlags_Logarithmic);
    tooltip("Time span of the scrolling x(t) strip.");
    if (ImGui::Checkbox("dark", &dark_)) {
        apply_theme(dark_, ui_scale_);
        bif_dirty_ = true;
    }
    tooltip("T: dark or light theme (light reads better on a projector).");
    ImGui::SameLine();
    // The scale applies when the slider is released (rebuilding the font under the mouse would jump).
    static bool editing = false;
    static float scale_edit = 1.0f;
    if (!editing) scale_edit = ui_scale_;
    ImGui::SetNextItemWidth(-1);
    ImGui::SliderFloat("##scale", &scale_edit, 0.75f, 3.0f, "UI scale %.2f");
    editing = ImGui::IsItemActive();
    if (ImGui::IsItemDeactivatedAfterEdit()) {
        ui_scale_ = std::round(scale_edit * 4.0f) / 4.0f;
        fonts_dirty_ = true;
    }
    tooltip("Ctrl + / Ctrl -: size of text and controls, for projectors.");
    // The rig's displacement magnification (the drawing only) and presentation mode (tiles.cpp).
    float g = static_cast<float>(magnification());
    ImGui::SetNextItemWidth(half);
    if (ImGui::SliderFloat("##magnify", &g, 1.0f, 10.0f, "rig disp. ×%.1f")) set_magnification(g);
    tooltip("Magnifies the cart's displacement from x = 0 in the rig's drawing only (cart and bumper alike,\n"
            "so a contact still looks like one); the rig's title says so. Presentation mode has its own (×3).");
    ImGui::SameLine();
    if (ImGui::Button(layout_.controls_narrow ? "Present" : "Presentation", ImVec2(-1, 0))) set_presentation(true);
    tooltip("P: the rig and one plot, large, with a slim bar of controls (P or Esc to come back).");
    const float tw = (full - 2 * ImGui::GetStyle().ItemSpacing.x) / 3.0f;
    const bool narrow = layout_.controls_narrow;
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
        std::snprintf(b1, sizeof b1, "%.3f s", last_.t);
        cell("t", b1);
        std::snprintf(b1, sizeof b1, "%+.3f mm", last_.x * 1e3);
        cell("x", b1);
        ImGui::TableNextRow();
        std::snprintf(b1, sizeof b1, "%.3f rad", std::fmod(last_.phi, kTwoPi));
        cell("φ", b1);
        std::snprintf(b1, sizeof b1, "%+.4f m/s", last_.v);
        cell("v", b1);
        ImGui::TableNextRow();
        std::snprintf(b1, sizeof b1, "%+.2f mJ", last_.energy * 1e3);
        cell("E", b1);
        std::snprintf(b1, sizeof b1, "%llu", static_cast<unsigned long long>(impacts_seen_));
        cell("impacts", b1);
        ImGui::EndTable();
    }
    ImGui::TextDisabled("regime");
    ImGui::SameLine();
    ImGui::TextUnformatted(contact_label(params_, last_.regime, last_.force));
    draw_grazing();
    lyapunov_live_.update(params_, omega_, last_.x, last_.v, now_s());
    ImGui::TextDisabled("λ_max");
    ImGui::SameLine();
    ImGui::TextUnformatted(lyapunov_live_.text().c_str());
    tooltip("The largest Lyapunov exponent at this ω, recomputed on a worker every 3 s from the current state\n"
            "(20 periods to settle, 60 averaged): positive on a chaotic attractor, negative on a periodic one.");

    section("Forces on the cart [N]");
    // The terms of Eq. (1) at this instant (core's force_terms), signed as they push the cart.
    const ForceTerms f = force_terms(params_, last_.t, last_.x, last_.v, last_.phi, last_.omega, 0.0);
    const double magnets = -(f.spring_magnet - params_.k * last_.x), springs = -params_.k * last_.x;
    const double bumper = std::max(last_.force, f.impact) > 0 ? -std::max(last_.force, f.impact) : 0.0;
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
    if (energy_floor_rev_ != params_rev_) {
        energy_floor_ = potential_floor(params_);
        energy_floor_rev_ = params_rev_;
    }
    const EnergyBalance eb = sim_->status().energy;
    draw_energy_bars(energy_bars(eb, params_.m, energy_floor_), eb.t0, eb.t);
}

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
    c.paused = paused_;
    c.sim_paused = sim_->status().paused;
    c.replay = replay_.active();
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
    if (a.hold) sim_->send(SimCommand::hold(*a.hold));   // each hold restarts the companion too
    if (a.set_state) set_state(a.set_state->first, a.set_state->second);
    if (a.start_orbit) restart_at_section(a.start_orbit->first, a.start_orbit->second);
}

void App::start_orbit(double x, double v) {
    poincare_.start_orbit(x, v, epoch_);
    restart_at_section(x, v);
}

void App::restart_at_section(double x, double v) {
    // The orbit starts on the section: at the next phi = 2 pi n (the forcing's phase moves on to it), from
    // (x, v) checked as a click in the phase portrait is (rail, bumper).
    const PickedState s = pick_state(x, v, xI_, params_.has_bumper());
    if (!s.note.empty()) toast(s.note);
    const double phi0 = kTwoPi * std::ceil(last_.phi / kTwoPi - 1e-9);
    restart_sim(s.x, s.v, last_.t, phi0, omega_, false);
}

void App::draw_status() {
    if (replay_.active()) {   // the bar becomes the replay's timeline (app_replay.cpp)
        draw_replay_bar();
        return;
    }
    const SimStatus st = sim_->status();
    const Palette& pal = palette();
    ImGui::Text("t = %.2f s", last_.t);
    ImGui::SameLine(0, 18);
    ImGui::TextDisabled("|");
    ImGui::SameLine(0, 18);
    if (warming_) ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(pal.warn), "warming up at 100x to t = %.0f s", opt_.warmup);
    else if (st.paused) ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(pal.warn), "paused");
    else if (st.lagging)
        ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(pal.warn), "speed %.2fx asked, %.2fx achieved (model too slow)",
                           speed_, st.achieved_speed);
    else ImGui::Text("speed %.2fx (achieved %.2fx)", speed_, st.achieved_speed);
    const char* help = "F1: shortcuts";
    const char* replay = "Replay";
    // The fields after the speed only where they fit before the buttons on the right (a large UI scale or a
    // narrow window drops the least useful first: the regime stays, then the samples, then the epoch).
    const float right_w = ImGui::CalcTextSize(help).x + ImGui::CalcTextSize(replay).x + 2 * ImGui::GetStyle().FramePadding.x +
                          48.0f * ui_scale_;
    char epoch[32], samples[64];
    std::snprintf(epoch, sizeof epoch, "epoch %u", epoch_);
    std::snprintf(samples, sizeof samples, "samples %.2fM, dropped %llu", static_cast<double>(samples_seen_) / 1e6,
                  static_cast<unsigned long long>(st.dropped));
    const char* regime = contact_label(params_, last_.regime, last_.force);
    const float sep = ImGui::CalcTextSize("|").x + 36.0f;
    float room = ImGui::GetWindowWidth() - right_w - (ImGui::GetItemRectMax().x - ImGui::GetWindowPos().x);
    // The epoch and the ring's counts are the simulation's bookkeeping: shown with View > Details only.
    const char* fields[3] = {details_ ? epoch : "", details_ ? samples : "", regime};
    for (const char* field : fields)
        if (*field) room -= sep + ImGui::CalcTextSize(field).x;
    bool drop[3] = {};
    for (int i = 0; i < 3 && room < 0; ++i) {
        if (!*fields[i]) continue;
        drop[i] = true;
        room += sep + ImGui::CalcTextSize(fields[i]).x;
    }
    for (int i = 0; i < 3; ++i) {
        if (drop[i] || !*fields[i]) continue;
        const char* field = fields[i];
        ImGui::SameLine(0, 18);
        ImGui::TextDisabled("|");
        ImGui::SameLine(0, 18);
        ImGui::TextUnformatted(field);
    }
    ImGui::SameLine(ImGui::GetWindowWidth() - ImGui::CalcTextSize(help).x - ImGui::CalcTextSize(replay).x -
                    ImGui::GetStyle().FramePadding.x * 2 - 30.0f * ui_scale_);
    if (ImGui::SmallButton(replay)) enter_replay();
    tooltip("Shift+R: scrub back through the last minutes (the simulation pauses)");
    ImGui::SameLine(ImGui::GetWindowWidth() - ImGui::CalcTextSize(help).x - 12.0f * ui_scale_);
    ImGui::TextDisabled("%s", help);
}

void App::draw_help() {
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x * 0.5f, vp->Pos.y + vp->Size.y * 0.5f), ImGuiCond_Appearing,
                            ImVec2(0.5f, 0.5f));
    if (ImGui::Begin("Keyboard shortcuts", &show_help_,
                     ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoCollapse)) {
        static const char* keys[][2] = {
            {"Space", "play / pause"},
            {"N  or  .", "step one forcing period (to the next Poincare section)"},
            {"R", "reset: t = 0, cart at rest in the left well"},
            {"Left / Right", "ω -/+ 0.1 rad/s (Shift: 1 rad/s)"},
            {"Up / Down", "bumper x_I +/- 0.5 mm (Shift: 2 mm)"},
            {"[  /  ]", "speed / 2, x 2 (0.01x .. 100x)"},
            {"M", "next impact model (C, C1, G, H), live"},
            {"K", "next stiffness (A1, A3), live"},
            {"1 .. 4", "presets: period 1, period 2, chaos, periodic window"},
            {"B", "compute (or cancel) the bifurcation diagram"},
            {"O", "continue the periodic orbits over the diagram's ω range (or cancel)"},
            {"F2, F3", "parameter plane (ω, x_I), basins of attraction at ω"},
            {"F4", "parameters of the running model (m, c, k, T, m0e, eps, the impact law's)"},
            {"click diagram", "set ω there"},
            {"click phase / well", "start the cart from that (x, v) / that x at rest"},
            {"drag the cart", "hold it at the mouse; let go: from there at rest"},
            {"right-drag diagram", "compute the ω range of the box (column by column)"},
            {"C", "clear the Poincare map"},
            {"T", "dark / light theme"},
            {"P", "presentation mode: the rig and one plot, large (V: the next plot)"},
            {"Z", "maximise the panel under the mouse, or restore"},
            {"Esc", "restore a maximised panel, leave presentation mode"},
            {"Ctrl + / Ctrl -", "UI scale"},
            {"F12", "screenshot (PNG)"},
            {"Ctrl+S, Ctrl+O", "save, load a session (JSON)"},
            {"Shift+R", "replay: scrub back (Space play, Left/Right a period, , . a sample,"},
            {"", "  Enter continue from there, Esc back to live)"},
            {"Ctrl+E", "export trajectory and sections (CSV)"},
            {"F1, H", "this window"},
            {"Ctrl+Q", "quit"},
        };
        if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV)) {
            for (const auto& k : keys) {
                ImGui::TableNextRow();
                ImGui::TableSetColumnIndex(0);
                ImGui::TextColored(ImGui::GetStyle().Colors[ImGuiCol_SliderGrab], "%s", k[0]);
                ImGui::TableSetColumnIndex(1);
                ImGui::TextUnformatted(k[1]);
            }
            ImGui::EndTable();
        }
        ImGui::Spacing();
        ImGui::TextDisabled("impactlab %s  -  Dear ImGui %s", IMPACTLAB_VERSION, IMGUI_VERSION);
    }
    ImGui::End();
}

void App::draw_toast() {
    if (toast_.empty() || now_s() > toast_until_ || opt_.frames > 0) return;
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    const float pad = 14.0f * ui_scale_;
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x - pad, vp->Pos.y + vp->Size.y - pad - ImGui::GetFrameHeight() * 1.5f),
                            ImGuiCond_Always, ImVec2(1, 1));
    ImGui::SetNextWindowBgAlpha(0.92f);
    if (ImGui::Begin("##toast", nullptr,
                     ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoInputs |
                         ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav))
        ImGui::TextUnformatted(toast_.c_str());
    ImGui::End();
}

}  // namespace impactlab::gui
