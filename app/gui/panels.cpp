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

struct XY {
    double x, y;
};

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
    if (energy_floor_for_ != params_.name) {
        energy_floor_ = potential_floor(params_);
        energy_floor_for_ = params_.name;
    }
    const EnergyBalance eb = sim_->status().energy;
    draw_energy_bars(energy_bars(eb, params_.m, energy_floor_), eb.t0, eb.t);
}

void App::draw_rig() {
    const Palette& pal = palette();
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const int w = std::max(16, static_cast<int>(avail.x)), h = std::max(16, static_cast<int>(avail.y));
    RigState st;
    st.x = last_.x;
    st.v = last_.v;
    st.phi = last_.phi;
    st.phi_span = have_last_ ? last_.phi - phi_prev_ : 0.0;
    st.xI = xI_shown_;   // where the simulation has it: it travels to the slider's x_I, pushing the cart
    st.bumper_force = std::max(frame_max_force_, last_.force);
    st.bumper = params_.has_bumper();
    st.flash = flash_;
    st.magnet_force = -(spring_magnet(params_, last_.x).F - params_.k * last_.x);
    st.spring_force = -params_.k * last_.x;
    st.in_contact = in_contact(params_, last_.regime, last_.force);
    st.magnify = magnification();   // the drawing only (layout.hpp: RigMagnify)
    // Rendered at the framebuffer's resolution (sharp on high-DPI screens), shown at display size.
    const float fbs = std::max(1.0f, ImGui::GetIO().DisplayFramebufferScale.x);
    rig_.prepare(static_cast<int>(w * fbs), static_cast<int>(h * fbs), st, pal);
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    ImGui::Dummy(ImVec2(static_cast<float>(w), static_cast<float>(h)));   // the item the mouse hovers
    rig_.add_to(ImGui::GetWindowDrawList(), p0);
    rig_mouse(p0, fbs);   // drag the cart

    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImU32 text = pal.title_text, dim = pal.axis_text;
    const RigMagnify& mag = rig_.magnify();
    // Screen position of a point of the drawing (x already magnified: mag.draw_x, mag.bumper_face).
    auto at = [&](double x, double y) {
        const ImVec2 q = rig_.to_image(x, y);
        return ImVec2(p0.x + q.x / fbs, p0.y + q.y / fbs);
    };
    char buf[128];
    const float fs = ImGui::GetFontSize();
    // The labels go in order of importance, each at the first of its spots that lies inside the image and
    // clear of those placed before (LabelPlacer): none overprints another, none is cut at the edge, at any
    // UI scale, tile size, x_I or magnification; what finds no room is left out.
    LabelPlacer labels({p0.x, p0.y, static_cast<float>(w), static_cast<float>(h)});
    const ImU32 plate_bg = pal.dark ? IM_COL32(10, 12, 16, 150) : IM_COL32(255, 255, 255, 170);
    struct Spot {
        ImVec2 p, align;   // the point, and where on the text's box it sits (0..1 in x and y)
    };
    auto put = [&](const char* s, ImU32 col, std::initializer_list<Spot> spots, bool plate = true) {
        const ImVec2 ts = ImGui::CalcTextSize(s);
        for (const Spot& sp : spots) {
            const Rect r{std::round(sp.p.x - ts.x * sp.align.x) - 3, std::round(sp.p.y - ts.y * sp.align.y) - 1, ts.x + 6,
                         ts.y + 2};
            if (!labels.place(r)) continue;
            if (plate) dl->AddRectFilled(ImVec2(r.x, r.y), ImVec2(r.right(), r.bottom()), plate_bg, 3.0f);
            dl->AddText(ImVec2(r.x + 3, r.y + 1), col, s);
            return true;
        }
        return false;
    };
    // The ruler and the end walls are no place for a label either: their boxes are taken first.
    const auto reserve = [&](double x0, double y0, double x1, double y1) {
        const ImVec2 a = at(x0, y0), b = at(x1, y1);
        labels.reserve({std::min(a.x, b.x), std::min(a.y, b.y), std::abs(b.x - a.x), std::abs(b.y - a.y)});
    };
    {
        const double wall_x = mag.wall_x(), ruler = 0.025 * mag.gain;
        reserve(-ruler, rig::kRulerY - 0.001, ruler, rig::kRulerY + 0.0052);   // the ticks (numbers sit above)
        reserve(wall_x - 0.003, -0.065, wall_x + 0.013, 0.045);
        reserve(-wall_x - 0.013, -0.065, -wall_x + 0.003, 0.045);
    }
    const float edge = fs * 0.6f;
    // Regime badge (a compliant bumper has no regimes II/III: contact is free flight with F_I > 0).
    // The same words as the status bar, from the same sample (contact_label.hpp).
    const char* badge = contact_label(params_, last_.regime, last_.force);
    const ImU32 badge_col = in_contact(params_, last_.regime, last_.force) ? pal.bumper : pal.energy;
    const ImVec2 bp(p0.x + edge, p0.y + fs * 0.5f);
    put(badge, badge_col, {{bp, {0, 0}}});
    if (paused_) put(sim_->status().paused ? "PAUSED" : "STEPPING", pal.warn, {{ImVec2(p0.x + w - edge, bp.y), {1, 0}}}, false);
    // The magnification, where every eye goes first: beside the badge or under it.
    if (mag.gain > 1.001) {
        std::snprintf(buf, sizeof buf, "displacement ×%.3g (drawing only)", mag.gain);
        const float bw = ImGui::CalcTextSize(badge).x;
        if (!put(buf, pal.warn, {{ImVec2(bp.x + bw + fs, bp.y), {0, 0}}, {ImVec2(bp.x, bp.y + 1.6f * fs), {0, 0}}})) {
            std::snprintf(buf, sizeof buf, "displacement ×%.3g", mag.gain);
            put(buf, pal.warn, {{ImVec2(bp.x + bw + fs, bp.y), {0, 0}}, {ImVec2(bp.x, bp.y + 1.6f * fs), {0, 0}},
                                {ImVec2(p0.x + w - edge, p0.y + h - fs * 2.2f), {1, 1}}});
        }
    }
    const double face = mag.bumper_face(xI_shown_);
    const double bumper_top = rig::kBumperY + rig::kBumperHalfH + 0.0025, bumper_low = rig::kBumperY - rig::kBumperHalfH - 0.003;
    // The impact label speaks of the displayed instant: the force now while in contact, then the last
    // contact's v- or peak force, fading, for at most half a forcing period of simulated time.
    const bool touching = in_contact(params_, last_.regime, last_.force);
    const double label_alpha =
        impact_label_.alpha(touching, last_.t, now_s(), kTwoPi / std::max(omega_, 0.5), speed_);
    if (label_alpha > 0.02) {
        if (touching) std::snprintf(buf, sizeof buf, "F = %.1f N", std::max(0.0, last_.force));
        else if (impact_label_.was_impact()) std::snprintf(buf, sizeof buf, "impact  v- = %.3f m/s", impact_label_.v_minus());
        else std::snprintf(buf, sizeof buf, "contact  peak F = %.1f N", impact_label_.peak_force());
        const double heat = touching ? std::min(1.0, last_.force / 100) : 0.0;
        const ImU32 col = heat_color(static_cast<float>(0.5 + 0.5 * std::max(flash_, heat)), static_cast<float>(label_alpha));
        const ImVec2 q = at(face + 0.004, bumper_top);
        put(buf, col, {{q, {0, 1}}, {ImVec2(p0.x + w - 4, q.y), {1, 1}}, {at(face - 0.004, bumper_top), {1, 1}}});
    }
    // The cart's x beside the ruler (whose millimetres are magnified with the displacement).
    std::snprintf(buf, sizeof buf, "x = %+.2f mm", last_.x * 1e3);
    const double ruler_end = 0.025 * mag.gain;
    put(buf, text, {{at(ruler_end + 0.004, rig::kRulerY + 0.0025), {0, 0.5f}},
                    {at(-ruler_end - 0.004, rig::kRulerY + 0.0025), {1, 0.5f}},
                    {at(0.0, rig::kRulerY - 0.004), {0.5f, 0}}});
    // The bumper: under it, right of its face; at a large x_I against the image's right edge, or shorter.
    if (params_.has_bumper()) {
        std::snprintf(buf, sizeof buf, "bumper  x_I = %+.1f mm", xI_shown_ * 1e3);
        const ImVec2 q = at(face + 0.004, bumper_low), q_left = at(face - 0.004, bumper_low);
        if (!put(buf, dim, {{q, {0, 0}}, {ImVec2(p0.x + w - 4, q.y), {1, 0}}, {q_left, {1, 0}}})) {
            std::snprintf(buf, sizeof buf, "x_I = %+.1f mm", xI_shown_ * 1e3);
            put(buf, dim, {{q, {0, 0}}, {ImVec2(p0.x + w - 4, q.y), {1, 0}}, {q_left, {1, 0}}});
        }
    }
    // Legend: scale bar (the rig's size; the displacement is magnified on top of it) and the forcing.
    const ImVec2 lg(p0.x + edge, p0.y + h - fs * 0.8f);
    const float ten_mm = 0.010f * rig_.px_per_m() / fbs;
    const ImVec2 tl = ImGui::CalcTextSize("10 mm");
    if (labels.place({lg.x - 2, lg.y - fs * 0.6f, ten_mm + 8 + tl.x, fs * 1.2f})) {
        dl->AddLine(ImVec2(lg.x, lg.y), ImVec2(lg.x + ten_mm, lg.y), text, 2.0f);
        dl->AddLine(ImVec2(lg.x, lg.y - 4), ImVec2(lg.x, lg.y + 4), text, 1.5f);
        dl->AddLine(ImVec2(lg.x + ten_mm, lg.y - 4), ImVec2(lg.x + ten_mm, lg.y + 4), text, 1.5f);
        dl->AddText(ImVec2(lg.x + ten_mm + 6, lg.y - fs * 0.55f), dim, "10 mm");
    }
    const double om = last_.omega;
    std::snprintf(buf, sizeof buf, "unbalance  m0e ω² = %.2f N", params_.m0e * om * om);
    const ImVec2 ub(p0.x + w - edge, lg.y - fs * 0.55f);
    if (!put(buf, dim, {{ub, {1, 0}}})) {
        std::snprintf(buf, sizeof buf, "m0e ω² = %.2f N", params_.m0e * om * om);
        put(buf, dim, {{ub, {1, 0}}});
    }
    // Parts.
    std::snprintf(buf, sizeof buf, "magnets repel: %+.2f N", st.magnet_force);
    if (!put(buf, dim, {{at(-0.014, rig::kMagnetFixedY - 0.001), {1, 0.5f}}})) {
        std::snprintf(buf, sizeof buf, "magnets %+.2f N", st.magnet_force);
        put(buf, dim, {{at(-0.014, rig::kMagnetFixedY - 0.001), {1, 0.5f}}});
    }
    std::snprintf(buf, sizeof buf, "springs  k = %.0f N/m", params_.k);
    put(buf, dim, {{at(-mag.wall_x() + 0.012, rig::kSpringY + 0.0115), {0, 1}}});
    // Ruler numbers, at the magnified millimetres.
    for (int mm = -20; mm <= 20; mm += 20) {
        std::snprintf(buf, sizeof buf, "%d", mm);
        put(buf, dim, {{at(mm * 1e-3 * mag.gain, rig::kRulerY + 0.0058), {0.5f, 1}}}, false);
    }
    // The companion cart: a translucent outline where the twin or the ghost is.
    if (companion_mode_ != CompanionMode::Off && companion_.have()) {
        const double xc = rig_.magnify().draw_x(companion_.last().x);   // drawn as the cart is
        const ImVec2 a = at(xc - rig::kCartHalfW, rig::kCartHalfH), b = at(xc + rig::kCartHalfW, -rig::kCartHalfH);
        dl->AddRectFilled(a, b, companion_color(0.22f), 6.0f);
        dl->AddRect(a, b, companion_color(0.9f), 6.0f, 0, 2.0f);
        const std::string who = companion_mode_ == CompanionMode::Twin
                                    ? std::string("twin")
                                    : "ghost " + std::string(impact_models()[static_cast<std::size_t>(ghost_impact_)].id);
        dl->AddText(ImVec2(a.x + 4, b.y - ImGui::GetFontSize() - 2), companion_color(1.0f), who.c_str());
    }
}

std::size_t App::trail_first() const {
    const std::size_t n = traj_.size();
    if (bench_window_) return n > bench_window_ ? n - bench_window_ : 0;
    if (n == 0) return 0;
    const double t_from = traj_.back().t - trail_periods_ * kTwoPi / std::max(omega_, 0.5);
    return traj_.lower_bound(t_from, [](const SimMsg& m) { return m.t; });
}

void App::draw_phase() {
    const Palette& pal = palette();
    const std::size_t n = traj_.size();
    const std::size_t first = trail_first();
    // Auto-fit to the trail (and keep the bumper in view when it is near).
    const auto xe = phase_x_extent_.update(traj_, first, [](const SimMsg& m) { return m.x; });
    const auto ve = phase_v_extent_.update(traj_, first, [](const SimMsg& m) { return m.v; });
    double xl = xe.lo, xh = xe.hi, vl = ve.lo, vh = ve.hi;
    if (first >= n) {
        xl = xh = last_.x;
        vl = vh = 0;
    }
    if (xI_ > xh && xI_ - xh < 0.004) xh = xI_;
    const double dt = frame_dt_;
    phase_x_.track({xl, xh}, 0.08, 0.004, dt);
    phase_v_.track({vl, vh}, 0.08, 0.04, dt);
    Plot plot;
    Axes ax;
    ax.x_label = "x [mm]";
    ax.y_label = "v [m/s]";
    ax.x_scale = 1e3;
    if (!plot.begin("##phase", ImGui::GetContentRegionAvail(), phase_x_.cur, phase_v_.cur, ax)) return;
    if (params_.has_bumper()) {   // impact law "none": no bumper to draw
        plot.shade_right_of(xI_shown_, pal.bumper);
        plot.vline(xI_shown_, pal.bumper, 1.5f, true);
    }
    plot.hline(0.0, pal.grid, 1.0f);
    const History<SimMsg>& ct = companion_.traj();   // the companion over the same stretch of time, under the cart
    const bool comp = companion_mode_ != CompanionMode::Off && companion_.have();
    const std::size_t cf = comp && first < n ? ct.lower_bound(traj_[first].t, [](const SimMsg& m) { return m.t; }) : ct.size();
    if (comp)
        plot.path(ct.size() - cf, [&](std::size_t i) { const SimMsg& m = ct[cf + i]; return XY{m.x, m.v}; },
                  companion_color(0.6f), 1.3f);
    plot.trail(n - first, traj_.seq_of(first), traj_.generation(),
               [&](std::size_t i) { const SimMsg& m = traj_[first + i]; return XY{m.x, m.v}; }, pal.trace, 1.6f);
    // The latest section points on the orbit, and the cart now.
    const std::size_t ns = sections_.size(), s0 = ns > 64 ? ns - 64 : 0;
    plot.scatter(ns - s0, [&](std::size_t i) { const SimMsg& m = sections_[s0 + i]; return XY{m.x, m.v}; }, pal.section, 4.0f);
    const ImVec2 c = plot.to_px(last_.x, last_.v);
    plot.draw()->AddCircleFilled(c, 4.5f * ui_scale_, pal.trail_head);
    plot.draw()->AddCircle(c, 7.0f * ui_scale_, pal.trace, 0, 1.5f);
    if (comp) plot.draw()->AddCircle(plot.to_px(companion_.last().x, companion_.last().v), 6.0f * ui_scale_, companion_color(1.0f), 0, 2.0f);
    char buf[64];
    std::snprintf(buf, sizeof buf, "trail %.0f periods", static_cast<double>(trail_periods_));
    plot.draw()->AddText(ImVec2(plot.area_min().x + 6, plot.area_min().y + 4), pal.axis_text, buf);
    // A plain click starts the cart from (x, v) there (drag, wheel and double-click keep zooming).
    const ImVec2 mp = ImGui::GetIO().MousePos;
    const double mx = plot.x_at(mp.x), mv = plot.y_at(mp.y);
    if (plot.hovered() && !plot.dragging())
        ImGui::SetTooltip("x = %+.2f mm, v = %+.3f m/s\nclick to start from here", mx * 1e3, mv);
    plot_click(phase_click_, plot.hovered(), plot.clicked(), mx, mv);
    plot.end();
}

namespace {
// Poincare points by impacts in the forcing period before them: 0, 1, 2, 3 or more.
ImU32 impacts_color(int impacts, float alpha) {
    const bool dark = palette().dark;
    static constexpr ImU32 kDark[4] = {IM_COL32(255, 196, 70, 255), IM_COL32(255, 96, 96, 255),
                                       IM_COL32(196, 126, 255, 255), IM_COL32(90, 200, 255, 255)};
    static constexpr ImU32 kLight[4] = {IM_COL32(205, 120, 0, 255), IM_COL32(200, 30, 40, 255),
                                        IM_COL32(120, 50, 200, 255), IM_COL32(20, 110, 200, 255)};
    const int k = impacts < 0 ? 0 : impacts > 3 ? 3 : impacts;
    ImVec4 c = ImGui::ColorConvertU32ToFloat4((dark ? kDark : kLight)[k]);
    c.w = alpha;
    return ImGui::ColorConvertFloat4ToU32(c);
}
}  // namespace

void App::draw_poincare() {
    const Palette& pal = palette();
    const PoincareMap& map = shown_map();   // replaying: as it stood at the cursor
    const History<MapPoint>& pts = map.points();
    const std::size_t n = pts.size();
    const PoincareMap::Status status = map.status();
    const bool periodic = status == PoincareMap::Status::Periodic;
    // A periodic orbit is a few points: large. A chaotic one is thousands: small enough to show structure.
    const float dot = periodic ? std::max(7.0f, 8.0f * ui_scale_) : std::max(3.0f, 3.5f * ui_scale_);
    const float ring = std::max(dot * 0.5f + 3.0f, 6.0f * ui_scale_);

    // Four age bands (oldest first, fading) times four impact counts (0, 1, 2, 3+): one scatter call each.
    for (auto& b : pc_buckets_) b.clear();
    bool impacts_seen[4] = {};
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t age_band = periodic ? 3 : std::min<std::size_t>(3, 4 * i / n);
        const int cat = std::min(pts[i].impacts, 3);
        impacts_seen[cat] = true;
        pc_buckets_[age_band * 4 + static_cast<std::size_t>(cat)].push_back(static_cast<std::uint32_t>(i));
    }
    const bool legend = impacts_seen[1] || impacts_seen[2] || impacts_seen[3];

    // The label: what the map knows. The period is the settle detector's, never a guess from the transient.
    char label[160];
    const unsigned long long seen = map.seen();
    if (seen == 0) std::snprintf(label, sizeof label, "no section yet (one per forcing period)");
    else if (map.provisional())
        std::snprintf(label, sizeof label, "no period yet (provisional)  %zu of %llu points", n, seen);
    else if (status == PoincareMap::Status::Settling)
        std::snprintf(label, sizeof label, "settling...  %llu period%s, the transient is not drawn", seen, seen == 1 ? "" : "s");
    else if (periodic) std::snprintf(label, sizeof label, "period %d", map.period());
    else std::snprintf(label, sizeof label, "chaos: no period <= 16   %zu points", n);
    static const char* kNames[4] = {"0", "1", "2", "3+"};
    const char* legend_title = "impacts/period";
    const float fs = ImGui::GetFontSize();
    const float r_legend = 0.3f * fs;
    float legend_w = ImGui::CalcTextSize(legend_title).x;
    for (int cat = 0; cat < 4; ++cat)
        if (impacts_seen[cat]) legend_w += 0.6f * fs + 2 * r_legend + 3 + ImGui::CalcTextSize(kNames[cat]).x;

    // The fit, in the data area Plot::begin will lay out (its margins): the newest point's ring stays off
    // the frame, and a band at the top for the label and the legend (a second line when they do not fit
    // side by side) stays free of points.
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const double area_w = avail.x - fs * 4.4f, area_h = avail.y - fs * 2.8f;
    // Replaying, the map is that of the replayed instant, and says so.
    char when[48] = "";
    if (replay_.active()) std::snprintf(when, sizeof when, "  (replay, t = %.2f s)", last_.t);
    const auto too_wide = [&] { return ImGui::CalcTextSize(label).x + ImGui::CalcTextSize(when).x + 12 > area_w; };
    if (too_wide()) {   // a small tile or a large UI scale: the short words
        if (seen == 0) std::snprintf(label, sizeof label, "no section yet");
        else if (map.provisional()) std::snprintf(label, sizeof label, "no period yet  %zu", n);
        else if (status == PoincareMap::Status::Settling) std::snprintf(label, sizeof label, "settling... %llu", seen);
        else if (!periodic) std::snprintf(label, sizeof label, "chaos  %zu points", n);
        if (replay_.active() && too_wide()) std::snprintf(when, sizeof when, "  (replay)");
    }
    {
        const std::size_t len = std::strlen(label);
        std::snprintf(label + len, sizeof label - len, "%s", when);
    }
    const bool two_lines = legend && ImGui::CalcTextSize(label).x + legend_w + 24 > area_w;
    const double edge = ring + 3.0 + 0.06 * std::min(area_w, area_h);
    const double label_band = (two_lines ? 2.1 : 1.0) * fs + 10.0;
    if (n == 0 && phase_x_.init) {
        // Settling: an empty map in the phase portrait's view.
        pc_x_ = phase_x_;
        pc_v_ = phase_v_;
        pc_fit_generation_ = ~std::uint64_t{0};
    } else if (n == 0) {
        // The phase portrait is not drawn (presentation mode): the trail's own extent, not an unset 0..1 m.
        double xl = last_.x, xh = last_.x, vl = last_.v, vh = last_.v;
        for (std::size_t i = trail_first(); i < traj_.size(); ++i) {
            xl = std::min(xl, traj_[i].x);
            xh = std::max(xh, traj_[i].x);
            vl = std::min(vl, traj_[i].v);
            vh = std::max(vh, traj_[i].v);
        }
        pc_x_.snap({xl, xh}, 0.08, 0.004);
        pc_v_.snap({vl, vh}, 0.08, 0.04);
        pc_fit_generation_ = ~std::uint64_t{0};
    } else {
        const auto xe = pc_x_extent_.update(pts, 0, [](const MapPoint& m) { return m.x; });
        const auto ve = pc_v_extent_.update(pts, 0, [](const MapPoint& m) { return m.v; });
        const AxisFit fx = fit_axis(xe.lo, xe.hi, 0.002, area_w, edge, edge);
        const AxisFit fv = fit_axis(ve.lo, ve.hi, 0.02, area_h, edge, edge + label_band);
        if (pts.generation() != pc_fit_generation_) {
            // A new decision (period found, chaos said): the view jumps to it rather than gliding there.
            pc_x_.snap({fx.lo, fx.hi}, 0.0, 1e-12);
            pc_v_.snap({fv.lo, fv.hi}, 0.0, 1e-12);
            pc_fit_generation_ = pts.generation();
        } else {
            pc_x_.track({fx.lo, fx.hi}, 0.0, 1e-12, frame_dt_);
            pc_v_.track({fv.lo, fv.hi}, 0.0, 1e-12, frame_dt_);
        }
    }
    Plot plot;
    Axes ax;
    ax.x_label = "x [mm]";
    ax.y_label = "v [m/s]";
    ax.x_scale = 1e3;
    if (!plot.begin("##poincare", avail, pc_x_.cur, pc_v_.cur, ax)) return;
    if (params_.has_bumper()) {   // impact law "none": no bumper to draw
        plot.shade_right_of(xI_, pal.bumper);
        plot.vline(xI_, pal.bumper, 1.5f, true);
    }

    // Newest band first over one shared pixel bitmap: a pixel a newer point covers is not drawn again
    // for an older one (100k points cost one pass, not sixteen).
    static constexpr float kAlpha[4] = {0.22f, 0.42f, 0.68f, 1.0f};
    plot.share_dots(true);
    for (std::size_t b = 4; b-- > 0;) {
        for (int cat = 0; cat < 4; ++cat) {
            const auto& idx = pc_buckets_[b * 4 + static_cast<std::size_t>(cat)];
            plot.scatter(idx.size(), [&](std::size_t j) { const MapPoint& m = pts[idx[j]]; return XY{m.x, m.v}; },
                         impacts_color(cat, kAlpha[b]), dot);
        }
    }
    plot.share_dots(false);
    if (n) {
        const ImVec2 c = plot.to_px(pts.back().x, pts.back().v);
        plot.draw()->AddCircle(c, ring, pal.section_new, 0, 2.0f);
    }
    if (periodic && n >= static_cast<std::size_t>(map.period())) {
        // The order of the visits, 1..k along the last cycle: points closer than a dot share one label
        // ("1,4"), so a doubled orbit's close pairs read as pairs, not as single points.
        const std::size_t k = static_cast<std::size_t>(map.period());
        std::vector<ImVec2> at(k);
        std::vector<bool> done(k, false);
        for (std::size_t j = 0; j < k; ++j) at[j] = plot.to_px(pts[n - k + j].x, pts[n - k + j].v);
        for (std::size_t j = 0; j < k; ++j) {
            if (done[j]) continue;
            char text[64];
            int len = std::snprintf(text, sizeof text, "%zu", j + 1);
            for (std::size_t q = j + 1; q < k; ++q) {
                const float dx = at[q].x - at[j].x, dy = at[q].y - at[j].y;
                if (!done[q] && dx * dx + dy * dy < 1.44f * dot * dot) {
                    done[q] = true;
                    if (len > 0 && len < 56) len += std::snprintf(text + len, sizeof text - static_cast<std::size_t>(len), ",%zu", q + 1);
                }
            }
            const float tw = ImGui::CalcTextSize(text).x;
            const bool left = at[j].x + ring + 4 + tw > plot.area_max().x;
            plot.draw()->AddText(ImVec2(left ? at[j].x - ring - 4 - tw : at[j].x + ring + 2, at[j].y - fs - 1),
                                 pal.axis_text, text);
        }
    }

    const ImVec2 lp(plot.area_min().x + 6, plot.area_min().y + 4);
    plate_text(plot.draw(), lp, label, pal.title_text);
    if (legend) {   // right-aligned, beside the label or on the line below it
        float x = plot.area_max().x - 6;
        const float y = two_lines ? lp.y + fs + 4 : lp.y;
        for (int cat = 3; cat >= 0; --cat) {
            if (!impacts_seen[cat]) continue;
            x -= ImGui::CalcTextSize(kNames[cat]).x;
            plot.draw()->AddText(ImVec2(x, y), pal.axis_text, kNames[cat]);
            x -= r_legend + 3;
            plot.draw()->AddCircleFilled(ImVec2(x, y + 0.5f * fs), r_legend, impacts_color(cat, 1.0f), 12);
            x -= r_legend + 0.6f * fs;
        }
        x -= ImGui::CalcTextSize(legend_title).x;
        plot.draw()->AddText(ImVec2(x, y), pal.axis_text, legend_title);
    }
    plot.end();
}

void App::draw_potential() {
    const Palette& pal = palette();
    const std::string key = params_.stiffness_id;
    if (potential_for_ != key) {
        potential_for_ = key;
        potential_x_.clear();
        potential_v_.clear();
        for (int i = 0; i <= 400; ++i) {
            const double x = -0.026 + 0.052 * i / 400.0;
            potential_x_.push_back(x);
            potential_v_.push_back(spring_magnet_potential(params_, x));
        }
    }
    const double vmin = *std::min_element(potential_v_.begin(), potential_v_.end());
    const Range xr{-0.026, 0.026};
    // The y range follows the largest energy of the phase portrait's trail (grows at once, shrinks
    // slowly), with room for the "E = ..." label above the line.
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const auto ee = energy_extent_.update(traj_, trail_first(), [](const SimMsg& m) { return m.energy; });
    const double e_max = ee.empty ? last_.energy : std::max(ee.hi, last_.energy);
    trail_e_max_ = e_max;
    const float fs = ImGui::GetFontSize();
    const AxisFit fy = potential_y_range(vmin, e_max, avail.y - fs * 2.8f, fs * 1.6f);
    potential_y_.track({fy.lo, fy.hi}, 0.0, 1e-12, frame_dt_);
    const Range yr = potential_y_.cur;
    Plot plot;
    Axes ax;
    ax.x_label = "x [mm]";
    ax.y_label = "V(x), E [mJ]";
    ax.x_scale = 1e3;
    ax.y_scale = 1e3;
    if (!plot.begin("##potential", avail, xr, yr, ax)) return;
    if (params_.has_bumper()) {   // impact law "none": no bumper to draw
        plot.shade_right_of(xI_shown_, pal.bumper);
        plot.vline(xI_shown_, pal.bumper, 1.5f, true);
    }
    plot.path(potential_x_.size(), [&](std::size_t i) { return XY{potential_x_[i], potential_v_[i]}; }, pal.trace2, 2.0f);
    // Total mechanical energy as a level: where it cuts V(x) are the turning points.
    plot.hline(last_.energy, pal.energy, 1.2f, true);
    char buf[48];
    std::snprintf(buf, sizeof buf, "E = %.2f mJ", last_.energy * 1e3);
    plot.text(xr.lo + 0.001, last_.energy, buf, pal.energy, ImVec2(0, 1.05f));
    const double vx = spring_magnet_potential(params_, last_.x);
    const ImVec2 c = plot.to_px(last_.x, vx);
    plot.draw()->AddCircleFilled(c, 6.0f * ui_scale_, pal.trace);
    plot.draw()->AddCircle(c, 6.0f * ui_scale_, pal.trail_head, 0, 1.5f);
    if (companion_mode_ != CompanionMode::Off && companion_.have()) {
        const double xc = companion_.last().x;
        plot.draw()->AddCircle(plot.to_px(xc, spring_magnet_potential(params_, xc)), 8.0f * ui_scale_, companion_color(1.0f), 0, 2.0f);
    }
    if (params_.has_bumper()) plot.text(xI_shown_, yr.hi, " bumper", pal.bumper, ImVec2(0, -0.2f));
    // A plain click puts the cart at x there, at rest.
    const double mx = plot.x_at(ImGui::GetIO().MousePos.x);
    if (plot.hovered() && !plot.dragging())
        ImGui::SetTooltip("x = %+.2f mm, V = %.2f mJ\nclick to start from here at rest", mx * 1e3,
                          spring_magnet_potential(params_, mx) * 1e3);
    plot_click(potential_click_, plot.hovered(), plot.clicked(), mx, 0.0);
    plot.end();
}

void App::draw_strip() {
    const Palette& pal = palette();
    const std::size_t n = traj_.size();
    const double t_now = n ? traj_.back().t : 0.0;
    const double window = bench_window_ && n ? std::max(1e-3, t_now - traj_[n > bench_window_ ? n - bench_window_ : 0].t)
                                             : strip_window_;
    // Scrolls once the history covers the window; before that the axis starts at the first sample.
    const double t_from = n ? std::min(std::max(t_now - window, traj_[0].t), t_now - 0.5) : t_now - window;
    const std::size_t first = traj_.lower_bound(t_from, [](const SimMsg& m) { return m.t; });
    const auto xe = strip_x_extent_.update(traj_, first, [](const SimMsg& m) { return m.x; });
    double lo = xe.lo, hi = xe.hi;
    if (first >= n) lo = hi = last_.x;
    strip_y_.track({lo, hi}, 0.08, 0.004, frame_dt_);
    Plot plot;
    Axes ax;
    ax.x_label = "t [s]";
    ax.y_label = "x [mm]";
    ax.y_scale = 1e3;
    // With a companion cart, its separation |dx| on a log scale takes the right part of the tile.
    const bool comp = companion_mode_ != CompanionMode::Off;
    ImVec2 size = ImGui::GetContentRegionAvail();
    const float sep_w = comp ? std::round(size.x * 0.3f) : 0.0f;
    size.x -= comp ? sep_w + ImGui::GetStyle().ItemSpacing.x : 0.0f;
    if (!plot.begin("##strip", size, {t_from, t_now}, strip_y_.cur, ax)) return;
    if (params_.has_bumper()) plot.hline(xI_shown_, pal.bumper, 1.5f, true);
    plot.hline(0.0, pal.grid, 1.0f);
    if (comp) {
        const History<SimMsg>& ct = companion_.traj();
        const std::size_t c0 = ct.lower_bound(t_from, [](const SimMsg& m) { return m.t; });
        plot.series(ct.size() - c0, [&](std::size_t i) { const SimMsg& m = ct[c0 + i]; return XY{m.t, m.x}; },
                    companion_color(0.75f), 1.5f);
    }
    plot.series(n - first, [&](std::size_t i) { const SimMsg& m = traj_[first + i]; return XY{m.t, m.x}; }, pal.trace, 1.5f);
    const std::size_t s0 = sections_.lower_bound(t_from, [](const SimMsg& m) { return m.t; });
    plot.scatter(sections_.size() - s0, [&](std::size_t i) { const SimMsg& m = sections_[s0 + i]; return XY{m.t, m.x}; },
                 pal.section, 4.0f);
    plot.end();
    if (comp) {
        ImGui::SameLine();
        draw_separation(ImVec2(sep_w, size.y));
    }
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
    const char* fields[3] = {epoch, samples, regime};
    for (const char* field : fields) room -= sep + ImGui::CalcTextSize(field).x;
    bool drop[3] = {};
    for (int i = 0; i < 3 && room < 0; ++i) {
        drop[i] = true;
        room += sep + ImGui::CalcTextSize(fields[i]).x;
    }
    for (int i = 0; i < 3; ++i) {
        if (drop[i]) continue;
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
