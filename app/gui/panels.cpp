// The windows of the visualiser, tiled over the main viewport: controls on the left; the rig and the
// bifurcation diagram on top; phase portrait, Poincare map and potential well in the middle; x(t) below.
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "app.hpp"
#include "gl_util.hpp"
#include "impactlab/forces.hpp"
#include "impactlab/sweep.hpp"
#include "theme.hpp"
#include "view_fit.hpp"

namespace impactlab::gui {

namespace {

constexpr ImGuiWindowFlags kTile = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus;

struct XY {
    double x, y;
};

bool begin_tile(const char* name, ImVec2 pos, ImVec2 size, ImGuiWindowFlags extra = 0) {
    ImGui::SetNextWindowPos(pos);
    ImGui::SetNextWindowSize(size);
    // No background fill: the tiles cover the window and App::frame clears it to WindowBg, which costs
    // nothing, while a million blended background pixels cost ~6 ms a frame under Mesa's llvmpipe.
    ImGui::PushStyleColor(ImGuiCol_WindowBg, IM_COL32(0, 0, 0, 0));
    const bool open = ImGui::Begin(name, nullptr, kTile | extra);
    ImGui::PopStyleColor();
    return open;
}

void section(const char* label) {
    ImGui::Spacing();
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_SliderGrab]);
    ImGui::TextUnformatted(label);
    ImGui::PopStyleColor();
    ImGui::Separator();
}

void tooltip(const char* text) {
    if (ImGui::IsItemHovered()) {
        ImGui::BeginTooltip();
        ImGui::PushTextWrapPos(ImGui::GetFontSize() * 24.0f);
        ImGui::TextUnformatted(text);
        ImGui::PopTextWrapPos();
        ImGui::EndTooltip();
    }
}

const char* regime_long(Regime r) {
    switch (r) {
        case Regime::Free: return "I  free flight";
        case Regime::Sticking: return "II  sticking (impact)";
        case Regime::Contact: return "III  permanent contact";
    }
    return "?";
}

// A small text with a dark/light plate behind it, for labels over the rig.
void plate_text(ImDrawList* dl, ImVec2 p, const char* text, ImU32 col, ImVec2 align = ImVec2(0, 0)) {
    const ImVec2 ts = ImGui::CalcTextSize(text);
    const ImVec2 a(std::round(p.x - ts.x * align.x), std::round(p.y - ts.y * align.y));
    const ImU32 bg = palette().dark ? IM_COL32(10, 12, 16, 150) : IM_COL32(255, 255, 255, 170);
    dl->AddRectFilled(ImVec2(a.x - 3, a.y - 1), ImVec2(a.x + ts.x + 3, a.y + ts.y + 1), bg, 3.0f);
    dl->AddText(a, col, text);
}

}  // namespace

// Runs one panel, timing it in benchmark mode (App::panel_s_).
template <class F>
void App::timed(int slot, F&& draw) {
    if (!bench_mode_) {
        draw();
        return;
    }
    const auto t0 = std::chrono::steady_clock::now();
    draw();
    panel_s_[static_cast<std::size_t>(slot)] += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void App::layout_and_draw() {
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    draw_menu();
    const float menu_h = ImGui::GetFrameHeight();
    const float status_h = std::round(ImGui::GetFrameHeight() + 6.0f * ui_scale_);
    const float left_w = std::round(std::clamp(292.0f * ui_scale_, 240.0f, vp->Size.x * 0.42f));
    const float x0 = vp->Pos.x + left_w, y0 = vp->Pos.y + menu_h;
    const float W = vp->Size.x - left_w, H = vp->Size.y - menu_h - status_h;
    const float row1 = std::round(H * 0.41f), row2 = std::round(H * 0.34f), row3 = H - row1 - row2;
    const float rig_w = std::round(W * 0.58f);
    const float third = std::round(W / 3.0f);

    set_plot_backdrops_by_clear(true);   // the tiles draw no background: frame() clears under their plots
    if (begin_tile("Controls", ImVec2(vp->Pos.x, y0), ImVec2(left_w, H))) timed(0, [&] { draw_controls(); });
    ImGui::End();

    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(4.0f * ui_scale_, 4.0f * ui_scale_));
    if (begin_tile("Rig (top view, to scale)", ImVec2(x0, y0), ImVec2(rig_w, row1),
                   ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse))
        timed(1, [&] { draw_rig(); });
    ImGui::End();
    if (begin_tile("Bifurcation diagram", ImVec2(x0 + rig_w, y0), ImVec2(W - rig_w, row1),
                   ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse))
        timed(2, [&] { draw_bifurcation(); });
    ImGui::End();
    const float y1 = y0 + row1;
    if (begin_tile("Phase portrait (x, v)", ImVec2(x0, y1), ImVec2(third, row2), ImGuiWindowFlags_NoScrollbar))
        timed(3, [&] { draw_phase(); });
    ImGui::End();
    if (begin_tile("Poincaré map (φ = 2πn)###poincare", ImVec2(x0 + third, y1), ImVec2(third, row2), ImGuiWindowFlags_NoScrollbar))
        timed(4, [&] { draw_poincare(); });
    ImGui::End();
    if (begin_tile("Potential well V(x)", ImVec2(x0 + 2 * third, y1), ImVec2(W - 2 * third, row2),
                   ImGuiWindowFlags_NoScrollbar))
        timed(5, [&] { draw_potential(); });
    ImGui::End();
    if (begin_tile("Displacement x(t)        dots: Poincaré sections (φ = 2πn)    dashed: bumper x_I###strip",
                   ImVec2(x0, y1 + row2), ImVec2(W, row3), ImGuiWindowFlags_NoScrollbar))
        timed(6, [&] { draw_strip(); });
    ImGui::End();
    ImGui::PopStyleVar();
    set_plot_backdrops_by_clear(false);   // floating windows (data panel) draw their own

    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(8.0f * ui_scale_, 3.0f * ui_scale_));
    if (begin_tile("##status", ImVec2(vp->Pos.x, vp->Pos.y + vp->Size.y - status_h), ImVec2(vp->Size.x, status_h),
                   ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoScrollbar))
        draw_status();
    ImGui::End();
    ImGui::PopStyleVar();

    data_panel_.poll(data_context());
    if (show_data_) data_panel_.draw(&show_data_, data_context());
    apply_analysis(analysis_.draw(analysis_context()));
    if (show_help_) draw_help();
    draw_toast();
}

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
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("View")) {
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

void App::draw_controls() {
    const auto& stiff = stiffness_sets();
    const auto& imps = impact_models();
    const float full = ImGui::GetContentRegionAvail().x;

    // Model: title and the two live combos.
    ImGui::TextUnformatted("Model");
    ImGui::SameLine();
    ImGui::TextColored(ImGui::GetStyle().Colors[ImGuiCol_SliderGrab], "%s", model_name().c_str());
    ImGui::SameLine();
    ImGui::TextDisabled("(live: keeps x, v, φ)");
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
    ImGui::SameLine();
    if (ImGui::Button("-.1")) set_omega(omega_ - 0.1);
    ImGui::SameLine();
    if (ImGui::Button("+.1")) set_omega(omega_ + 0.1);
    ImGui::SameLine();
    if (ImGui::Button("+1")) set_omega(omega_ + 1);
    ImGui::SameLine();
    if (omega_ > 0) ImGui::TextDisabled("T = %.3f s", kTwoPi / omega_);
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
    if (ImGui::Button("Step period", ImVec2(bw, 0))) step_period();
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
    const float tw = (full - 2 * ImGui::GetStyle().ItemSpacing.x) / 3.0f;
    if (ImGui::Button("Clear map", ImVec2(tw, 0))) clear_poincare();
    tooltip("C: clear the Poincare map");
    ImGui::SameLine();
    if (ImGui::Button("Screenshot", ImVec2(tw, 0))) screenshot(screenshot_name());
    tooltip("F12: the whole window as PNG, in the current folder");
    ImGui::SameLine();
    if (ImGui::Button("Export CSV", ImVec2(tw, 0))) export_csv();
    tooltip("Ctrl+E: the trajectory in memory and the Poincare points as CSV files");

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
    ImGui::TextUnformatted(regime_long(last_.regime));
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
    st.xI = xI_;
    st.bumper_force = std::max(frame_max_force_, last_.force);
    st.flash = flash_;
    st.magnet_force = -(spring_magnet(params_, last_.x).F - params_.k * last_.x);
    st.spring_force = -params_.k * last_.x;
    st.in_contact = last_.regime != Regime::Free || last_.force > 0;
    // Rendered at the framebuffer's resolution (sharp on high-DPI screens), shown at display size.
    const float fbs = std::max(1.0f, ImGui::GetIO().DisplayFramebufferScale.x);
    const GLuint tex = rig_.render(static_cast<int>(w * fbs), static_cast<int>(h * fbs), st, pal);
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(tex)), ImVec2(static_cast<float>(w), static_cast<float>(h)),
                 ImVec2(0, 1), ImVec2(1, 0));

    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImU32 text = pal.title_text, dim = pal.axis_text;
    auto at = [&](double x, double y) {
        const ImVec2 q = rig_.to_image(x, y);
        return ImVec2(p0.x + q.x / fbs, p0.y + q.y / fbs);
    };
    char buf[128];
    // Ruler numbers.
    for (int mm = -20; mm <= 20; mm += 20) {
        std::snprintf(buf, sizeof buf, "%d", mm);
        const ImVec2 q = at(mm * 1e-3, rig::kRulerY + 0.0058);
        const ImVec2 ts = ImGui::CalcTextSize(buf);
        dl->AddText(ImVec2(q.x - ts.x * 0.5f, q.y - ts.y), dim, buf);
    }
    std::snprintf(buf, sizeof buf, "x = %+.2f mm", last_.x * 1e3);
    plate_text(dl, at(0.029, rig::kRulerY + 0.0025), buf, text, ImVec2(0, 0.5f));
    // Parts.
    std::snprintf(buf, sizeof buf, "springs  k = %.0f N/m", params_.k);
    plate_text(dl, at(-rig::kWallX + 0.012, rig::kSpringY + 0.0115), buf, dim, ImVec2(0, 1));
    std::snprintf(buf, sizeof buf, "magnets repel: %+.2f N", st.magnet_force);
    plate_text(dl, at(-0.014, rig::kMagnetFixedY - 0.001), buf, dim, ImVec2(1, 0.5f));
    const double face = xI_ + rig::kCartHalfW;
    std::snprintf(buf, sizeof buf, "bumper  x_I = %+.1f mm", xI_ * 1e3);
    plate_text(dl, at(face + 0.004, rig::kBumperY - rig::kBumperHalfH - 0.003), buf, dim, ImVec2(0, 0));
    // The impact label speaks of the displayed instant: the force now while in contact, then the last
    // contact's v- or peak force, fading, for at most half a forcing period of simulated time.
    const bool touching = last_.force > 0 || last_.regime != Regime::Free;
    const double label_alpha =
        impact_label_.alpha(touching, last_.t, now_s(), kTwoPi / std::max(omega_, 0.5), speed_);
    if (label_alpha > 0.02) {
        if (touching) std::snprintf(buf, sizeof buf, "F = %.1f N", std::max(0.0, last_.force));
        else if (impact_label_.was_impact()) std::snprintf(buf, sizeof buf, "impact  v- = %.3f m/s", impact_label_.v_minus());
        else std::snprintf(buf, sizeof buf, "contact  peak F = %.1f N", impact_label_.peak_force());
        const double heat = touching ? std::min(1.0, last_.force / 100) : 0.0;
        plate_text(dl, at(face + 0.004, rig::kBumperY + rig::kBumperHalfH + 0.0025), buf,
                   heat_color(static_cast<float>(0.5 + 0.5 * std::max(flash_, heat)), static_cast<float>(label_alpha)),
                   ImVec2(0, 1));
    }
    // Legend: scale bar and the forcing.
    const float fs = ImGui::GetFontSize();
    const ImVec2 lg(p0.x + fs * 0.6f, p0.y + h - fs * 0.8f);
    const float ten_mm = 0.010f * rig_.px_per_m() / fbs;
    dl->AddLine(ImVec2(lg.x, lg.y), ImVec2(lg.x + ten_mm, lg.y), text, 2.0f);
    dl->AddLine(ImVec2(lg.x, lg.y - 4), ImVec2(lg.x, lg.y + 4), text, 1.5f);
    dl->AddLine(ImVec2(lg.x + ten_mm, lg.y - 4), ImVec2(lg.x + ten_mm, lg.y + 4), text, 1.5f);
    dl->AddText(ImVec2(lg.x + ten_mm + 6, lg.y - fs * 0.55f), dim, "10 mm");
    const double om = last_.omega;
    std::snprintf(buf, sizeof buf, "unbalance  m0e ω² = %.2f N", params_.m0e * om * om);
    const ImVec2 us = ImGui::CalcTextSize(buf);
    plate_text(dl, ImVec2(p0.x + w - us.x - fs * 0.6f, lg.y - fs * 0.55f), buf, dim);
    // Regime badge (a compliant bumper has no regimes II/III: contact is free flight with F_I > 0).
    const bool pressed = !params_.rigid() && last_.force > 0;
    const char* badge = pressed ? "I  on the compliant bumper" : regime_long(last_.regime);
    const ImU32 badge_col = last_.regime == Regime::Free && !pressed ? pal.energy : pal.bumper;
    const ImVec2 bs = ImGui::CalcTextSize(badge);
    const ImVec2 bp(p0.x + fs * 0.6f, p0.y + fs * 0.5f);
    dl->AddRectFilled(ImVec2(bp.x - 4, bp.y - 2), ImVec2(bp.x + bs.x + 4, bp.y + bs.y + 2),
                      pal.dark ? IM_COL32(0, 0, 0, 140) : IM_COL32(255, 255, 255, 190), 4.0f);
    dl->AddText(bp, badge_col, badge);
    if (paused_) {
        const char* p = sim_->status().paused ? "PAUSED" : "STEPPING";
        const ImVec2 ps = ImGui::CalcTextSize(p);
        dl->AddText(ImVec2(p0.x + w - ps.x - fs * 0.6f, bp.y), pal.warn, p);
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
    plot.shade_right_of(xI_, pal.bumper);
    plot.vline(xI_, pal.bumper, 1.5f, true);
    plot.hline(0.0, pal.grid, 1.0f);
    plot.trail(n - first, traj_.seq_of(first), traj_.generation(),
               [&](std::size_t i) { const SimMsg& m = traj_[first + i]; return XY{m.x, m.v}; }, pal.trace, 1.6f);
    // The latest section points on the orbit, and the cart now.
    const std::size_t ns = sections_.size(), s0 = ns > 64 ? ns - 64 : 0;
    plot.scatter(ns - s0, [&](std::size_t i) { const SimMsg& m = sections_[s0 + i]; return XY{m.x, m.v}; }, pal.section, 4.0f);
    const ImVec2 c = plot.to_px(last_.x, last_.v);
    plot.draw()->AddCircleFilled(c, 4.5f * ui_scale_, pal.trail_head);
    plot.draw()->AddCircle(c, 7.0f * ui_scale_, pal.trace, 0, 1.5f);
    char buf[64];
    std::snprintf(buf, sizeof buf, "trail %.0f periods", static_cast<double>(trail_periods_));
    plot.draw()->AddText(ImVec2(plot.area_min().x + 6, plot.area_min().y + 4), pal.axis_text, buf);
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
    const History<MapPoint>& pts = pc_map_.points();
    const std::size_t n = pts.size();
    const PoincareMap::Status status = pc_map_.status();
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
    char label[128];
    const unsigned long long seen = pc_map_.seen();
    if (seen == 0) std::snprintf(label, sizeof label, "no section yet (one per forcing period)");
    else if (status == PoincareMap::Status::Settling)
        std::snprintf(label, sizeof label, "settling...  %llu period%s, the transient is not drawn", seen, seen == 1 ? "" : "s");
    else if (periodic) std::snprintf(label, sizeof label, "period %d", pc_map_.period());
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
    const bool two_lines = legend && ImGui::CalcTextSize(label).x + legend_w + 24 > area_w;
    const double edge = ring + 3.0 + 0.06 * std::min(area_w, area_h);
    const double label_band = (two_lines ? 2.1 : 1.0) * fs + 10.0;
    if (n == 0) {
        // Settling: an empty map in the phase portrait's view.
        pc_x_ = phase_x_;
        pc_v_ = phase_v_;
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
    plot.shade_right_of(xI_, pal.bumper);
    plot.vline(xI_, pal.bumper, 1.5f, true);

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
    if (periodic && n >= static_cast<std::size_t>(pc_map_.period())) {
        // The order of the visits, 1..k along the last cycle: points closer than a dot share one label
        // ("1,4"), so a doubled orbit's close pairs read as pairs, not as single points.
        const std::size_t k = static_cast<std::size_t>(pc_map_.period());
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
    plot.shade_right_of(xI_, pal.bumper);
    plot.vline(xI_, pal.bumper, 1.5f, true);
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
    plot.text(xI_, yr.hi, " bumper", pal.bumper, ImVec2(0, -0.2f));
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
    if (!plot.begin("##strip", ImGui::GetContentRegionAvail(), {t_from, t_now}, strip_y_.cur, ax)) return;
    plot.hline(xI_, pal.bumper, 1.5f, true);
    plot.hline(0.0, pal.grid, 1.0f);
    plot.series(n - first, [&](std::size_t i) { const SimMsg& m = traj_[first + i]; return XY{m.t, m.x}; }, pal.trace, 1.5f);
    const std::size_t s0 = sections_.lower_bound(t_from, [](const SimMsg& m) { return m.t; });
    plot.scatter(sections_.size() - s0, [&](std::size_t i) { const SimMsg& m = sections_[s0 + i]; return XY{m.t, m.x}; },
                 pal.section, 4.0f);
    plot.end();
}

void App::update_density_texture(int w, int h) {
    if (!diagram_ || w <= 0 || h <= 0) return;
    if (!bif_dirty_ && w == bif_tex_w_ && h == bif_tex_h_) return;
    bif_dirty_ = false;
    bif_tex_w_ = w;
    bif_tex_h_ = h;
    std::vector<float> count(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0.0f);
    // Each omega column of a CF sweep is splatted over its share of the width, so the diagram has no gaps.
    std::size_t distinct = 1;
    for (std::size_t i = 1; i < diagram_->points.size(); ++i)
        if (diagram_->points[i].omega != diagram_->points[i - 1].omega) ++distinct;
    const bool cf = diagram_->protocol != "ef";
    // (A column's share: the diagram's omega extent bif_x_ over its columns, in the pixels of the view shown.)
    const double col_px = w / std::max<double>(1, distinct) * (bif_x_.span() / bif_view_x_.span());
    const int splat = cf ? std::clamp(static_cast<int>(col_px), 1, 12) : 1;
    for (const auto& p : diagram_->points) {
        const double fx = (p.omega - bif_view_x_.lo) / bif_view_x_.span(), fy = (bif_view_y_.hi - p.x) / bif_view_y_.span();
        const int ix = static_cast<int>(fx * w), iy = static_cast<int>(fy * h);
        if (iy < 0 || iy >= h) continue;
        for (int k = 0; k < splat; ++k) {
            const int x = ix + k - splat / 2;
            if (x < 0 || x >= w) continue;
            count[static_cast<std::size_t>(iy) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)] += 1.0f;
        }
    }
    float mx = 0;
    for (float c : count) mx = std::max(mx, c);
    const float norm = 1.0f / std::log1p(std::max(mx, 1.0f));
    std::vector<unsigned char> rgba(count.size() * 4, 0);
    for (std::size_t i = 0; i < count.size(); ++i) {
        if (count[i] <= 0) continue;
        density_color(palette().dark, std::log1p(count[i]) * norm, &rgba[i * 4]);
    }
    bif_tex_ = upload_rgba_texture(static_cast<GLuint>(bif_tex_), w, h, rgba.data());
}

void App::draw_bifurcation() {
    const Palette& pal = palette();
    // Header row: protocol, steps, compute/cancel, progress.
    const char* protos[] = {"CF up", "CF down", "EF ramp"};
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 6.2f);
    ImGui::Combo("##proto", &bif_protocol_, protos, 3);
    tooltip("CF: constant ω steps, 20 transient + 70 recorded periods each, every step starting where the last "
            "ended. EF: the experiment's slow ramp of ω over 2800 s.");
    ImGui::SameLine();
    ImGui::BeginDisabled(bif_protocol_ == 2);
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 6.0f);
    ImGui::SliderInt("##steps", &bif_steps_, 25, 600, "%d steps");
    ImGui::EndDisabled();
    ImGui::SameLine();
    if (bif_.running()) {
        if (ImGui::Button("Cancel")) bif_.cancel();
        ImGui::SameLine();
        char over[32];
        std::snprintf(over, sizeof over, "%.0f%%", 100.0 * bif_.progress());
        ImGui::ProgressBar(static_cast<float>(bif_.progress()), ImVec2(-1, 0), over);
    } else {
        char label[48];
        std::snprintf(label, sizeof label, "Compute for %s", model_name().c_str());
        if (ImGui::Button(label)) start_bifurcation();
        tooltip("B: runs on a worker thread; the animation goes on.");
    }

    Plot plot;
    Axes ax;
    ax.x_label = "ω [rad/s]";
    ax.y_label = "x at sections [mm]";
    ax.y_scale = 1e3;
    if (opt_.bif_zoom_hi > opt_.bif_zoom_lo && diagram_ && !bif_zoom_applied_) {
        // --bif-zoom: the omega range asked for, the auto-fit's x at sections.
        bif_zoom_applied_ = true;
        Plot::set_user_view("##bif", {opt_.bif_zoom_lo, opt_.bif_zoom_hi}, bif_y_);
    }
    if (!plot.begin("##bif", ImGui::GetContentRegionAvail(), bif_x_, bif_y_, ax)) return;
    const ImVec2 a = plot.area_min(), b = plot.area_max();
    // The density image is drawn for the view shown (zoomed and panned by the mouse, or the auto-fit).
    if (const Range vx = plot.x_range(), vy = plot.y_range();
        vx.lo != bif_view_x_.lo || vx.hi != bif_view_x_.hi || vy.lo != bif_view_y_.lo || vy.hi != bif_view_y_.hi) {
        bif_view_x_ = vx;
        bif_view_y_ = vy;
        bif_dirty_ = true;
    }
    if (diagram_) {
        update_density_texture(static_cast<int>(b.x - a.x), static_cast<int>(b.y - a.y));
        if (bif_tex_) plot.draw()->AddImage(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(bif_tex_)), a, b);
        char info[96];
        std::snprintf(info, sizeof info, "%s  %s%s  %zu points", diagram_->model.c_str(), diagram_->protocol.c_str(),
                      diagram_->cancelled ? " (cancelled)" : "", diagram_->points.size());
        plate_text(plot.draw(), ImVec2(a.x + 6, b.y - ImGui::GetTextLineHeight() - 6), info, pal.axis_text);
    } else {
        const char* hint = bif_.running() ? "computing on a worker thread..." : "press B (or Compute) for a diagram";
        const ImVec2 ts = ImGui::CalcTextSize(hint);
        plot.draw()->AddText(ImVec2(0.5f * (a.x + b.x - ts.x), 0.5f * (a.y + b.y - ts.y)), pal.axis_text, hint);
    }
    plot.hline(xI_, pal.bumper, 1.0f, true);
    // The current omega, and the one under the mouse (a click sets it).
    plot.vline(omega_, pal.cursor, 2.0f);
    char buf[48];
    std::snprintf(buf, sizeof buf, " %.2f", omega_);
    plot.text(omega_, bif_y_.hi, buf, pal.title_text, ImVec2(0, -0.1f));
    if (plot.hovered()) {
        const double w = std::clamp(plot.x_at(ImGui::GetIO().MousePos.x), 0.0, kMaxOmega);
        plot.vline(w, pal.trace, 1.0f, true);
        ImGui::SetTooltip("ω = %.2f rad/s  (click to set)", w);
        if (plot.clicked()) set_omega(w);
    }
    analysis_.overlay_diagram(plot);   // continued branches and bifurcation points (named on hover)
    plot.end();
}

void App::draw_status() {
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
    ImGui::SameLine(0, 18);
    ImGui::TextDisabled("|");
    ImGui::SameLine(0, 18);
    ImGui::Text("epoch %u", epoch_);
    ImGui::SameLine(0, 18);
    ImGui::TextDisabled("|");
    ImGui::SameLine(0, 18);
    ImGui::Text("samples %.2fM, dropped %llu", static_cast<double>(samples_seen_) / 1e6,
                static_cast<unsigned long long>(st.dropped));
    ImGui::SameLine(0, 18);
    ImGui::TextDisabled("|");
    ImGui::SameLine(0, 18);
    ImGui::Text("%s", regime_long(last_.regime));
    const char* help = "F1: shortcuts";
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
            {"click diagram", "set ω there"},
            {"C", "clear the Poincare map"},
            {"T", "dark / light theme"},
            {"Ctrl + / Ctrl -", "UI scale"},
            {"F12, Ctrl+S", "screenshot (PNG)"},
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
