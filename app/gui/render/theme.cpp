#include "theme.hpp"

#include <algorithm>
#include <cmath>

namespace impactlab::gui {

namespace {

Palette g_palette;

ImU32 rgba(int r, int g, int b, int a = 255) { return IM_COL32(r, g, b, a); }
void set3(float* dst, float r, float g, float b) {
    dst[0] = r;
    dst[1] = g;
    dst[2] = b;
}

void dark_style(ImGuiStyle& s) {
    ImGui::StyleColorsDark(&s);
    ImVec4* c = s.Colors;
    const ImVec4 bg(0.085f, 0.095f, 0.115f, 1.0f);
    const ImVec4 panel(0.110f, 0.122f, 0.145f, 1.0f);
    const ImVec4 accent(0.30f, 0.62f, 0.95f, 1.0f);
    c[ImGuiCol_WindowBg] = panel;
    c[ImGuiCol_ChildBg] = panel;
    c[ImGuiCol_PopupBg] = ImVec4(0.12f, 0.13f, 0.16f, 0.98f);
    c[ImGuiCol_MenuBarBg] = bg;
    c[ImGuiCol_TitleBg] = bg;
    c[ImGuiCol_TitleBgActive] = ImVec4(0.13f, 0.16f, 0.21f, 1.0f);
    c[ImGuiCol_Border] = ImVec4(0.22f, 0.25f, 0.30f, 1.0f);
    c[ImGuiCol_FrameBg] = ImVec4(0.17f, 0.19f, 0.23f, 1.0f);
    c[ImGuiCol_FrameBgHovered] = ImVec4(0.21f, 0.25f, 0.31f, 1.0f);
    c[ImGuiCol_FrameBgActive] = ImVec4(0.24f, 0.30f, 0.38f, 1.0f);
    c[ImGuiCol_SliderGrab] = accent;
    c[ImGuiCol_SliderGrabActive] = ImVec4(0.45f, 0.72f, 1.0f, 1.0f);
    c[ImGuiCol_Button] = ImVec4(0.19f, 0.23f, 0.29f, 1.0f);
    c[ImGuiCol_ButtonHovered] = ImVec4(0.25f, 0.36f, 0.50f, 1.0f);
    c[ImGuiCol_ButtonActive] = ImVec4(0.27f, 0.45f, 0.68f, 1.0f);
    c[ImGuiCol_Header] = ImVec4(0.19f, 0.25f, 0.33f, 1.0f);
    c[ImGuiCol_HeaderHovered] = ImVec4(0.24f, 0.33f, 0.45f, 1.0f);
    c[ImGuiCol_HeaderActive] = ImVec4(0.27f, 0.40f, 0.58f, 1.0f);
    c[ImGuiCol_CheckMark] = accent;
    c[ImGuiCol_PlotHistogram] = accent;
    c[ImGuiCol_Separator] = ImVec4(0.22f, 0.25f, 0.30f, 1.0f);
    c[ImGuiCol_Text] = ImVec4(0.88f, 0.90f, 0.93f, 1.0f);
    c[ImGuiCol_TextDisabled] = ImVec4(0.52f, 0.56f, 0.62f, 1.0f);
}

void light_style(ImGuiStyle& s) {
    ImGui::StyleColorsLight(&s);
    ImVec4* c = s.Colors;
    const ImVec4 accent(0.12f, 0.42f, 0.80f, 1.0f);
    c[ImGuiCol_WindowBg] = ImVec4(0.965f, 0.968f, 0.975f, 1.0f);
    c[ImGuiCol_ChildBg] = c[ImGuiCol_WindowBg];
    c[ImGuiCol_MenuBarBg] = ImVec4(0.90f, 0.91f, 0.93f, 1.0f);
    c[ImGuiCol_TitleBg] = ImVec4(0.88f, 0.89f, 0.92f, 1.0f);
    c[ImGuiCol_TitleBgActive] = ImVec4(0.80f, 0.85f, 0.92f, 1.0f);
    c[ImGuiCol_Border] = ImVec4(0.74f, 0.76f, 0.80f, 1.0f);
    c[ImGuiCol_FrameBg] = ImVec4(0.88f, 0.89f, 0.91f, 1.0f);
    c[ImGuiCol_SliderGrab] = accent;
    c[ImGuiCol_CheckMark] = accent;
    c[ImGuiCol_Button] = ImVec4(0.84f, 0.87f, 0.91f, 1.0f);
    c[ImGuiCol_ButtonHovered] = ImVec4(0.72f, 0.82f, 0.95f, 1.0f);
    c[ImGuiCol_ButtonActive] = ImVec4(0.58f, 0.74f, 0.95f, 1.0f);
    c[ImGuiCol_PlotHistogram] = accent;
    c[ImGuiCol_Text] = ImVec4(0.10f, 0.11f, 0.13f, 1.0f);
}

}  // namespace

const Palette& palette() { return g_palette; }

const Palette& apply_theme(bool dark, float ui_scale) {
    ImGuiStyle s;
    if (dark) dark_style(s);
    else light_style(s);
    s.WindowRounding = 4.0f;
    s.ChildRounding = 3.0f;
    s.FrameRounding = 3.0f;
    s.GrabRounding = 3.0f;
    // A slider's value is its text ("ω = 12.00 rad/s"): a thin, translucent grab lets it be read through.
    s.GrabMinSize = 5.0f;
    s.Colors[ImGuiCol_SliderGrab].w = 0.55f;
    s.PopupRounding = 3.0f;
    s.WindowPadding = ImVec2(8, 7);
    s.FramePadding = ImVec2(6, 3);
    s.ItemSpacing = ImVec2(7, 5);
    s.WindowBorderSize = 1.0f;
    s.WindowTitleAlign = ImVec2(0.0f, 0.5f);
    s.ScaleAllSizes(ui_scale);
    ImGui::GetStyle() = s;

    Palette& p = g_palette;
    p.dark = dark;
    if (dark) {
        p.plot_bg = rgba(16, 19, 25);
        p.plot_frame = rgba(70, 78, 92);
        p.grid = rgba(60, 68, 82, 150);
        p.grid_minor = rgba(48, 54, 66, 90);
        p.axis_text = rgba(160, 170, 185);
        p.title_text = rgba(225, 230, 238);
        p.trace = rgba(90, 175, 255);
        p.trace2 = rgba(255, 170, 60);
        p.trail_head = rgba(255, 255, 255);
        p.section = rgba(255, 196, 70, 210);
        p.section_new = rgba(255, 90, 70);
        p.bumper = rgba(255, 95, 80);
        p.energy = rgba(120, 220, 150);
        p.cursor = rgba(255, 255, 255, 150);
        p.warn = rgba(255, 190, 60);
        set3(p.bg_top, 0.105f, 0.120f, 0.150f);
        set3(p.bg_bottom, 0.060f, 0.068f, 0.085f);
        set3(p.rig_grid, 0.32f, 0.36f, 0.44f);
        set3(p.field, 0.45f, 0.70f, 1.00f);
        set3(p.text, 0.80f, 0.84f, 0.90f);
    } else {
        p.plot_bg = rgba(255, 255, 255);
        p.plot_frame = rgba(150, 156, 166);
        p.grid = rgba(205, 210, 218, 255);
        p.grid_minor = rgba(230, 233, 238, 255);
        p.axis_text = rgba(70, 76, 86);
        p.title_text = rgba(25, 28, 34);
        p.trace = rgba(20, 100, 200);
        p.trace2 = rgba(220, 110, 20);
        p.trail_head = rgba(0, 0, 0);
        p.section = rgba(200, 60, 30, 200);
        p.section_new = rgba(20, 20, 20);
        p.bumper = rgba(210, 40, 30);
        p.energy = rgba(20, 140, 60);
        p.cursor = rgba(0, 0, 0, 140);
        p.warn = rgba(190, 110, 0);
        set3(p.bg_top, 0.975f, 0.980f, 0.990f);
        set3(p.bg_bottom, 0.905f, 0.915f, 0.935f);
        set3(p.rig_grid, 0.60f, 0.64f, 0.72f);
        set3(p.field, 0.15f, 0.40f, 0.85f);
        set3(p.text, 0.15f, 0.17f, 0.20f);
    }
    // Rig materials (same in both themes: they are "physical" colours).
    set3(p.rail, 0.62f, 0.65f, 0.70f);
    set3(p.cart, 0.20f, 0.42f, 0.72f);
    set3(p.cart_edge, 0.08f, 0.16f, 0.30f);
    set3(p.spring, 0.78f, 0.80f, 0.84f);
    set3(p.spring_back, 0.45f, 0.47f, 0.52f);
    set3(p.magnet_n, 0.85f, 0.22f, 0.20f);
    set3(p.magnet_s, 0.20f, 0.40f, 0.85f);
    set3(p.wall, 0.36f, 0.38f, 0.43f);
    set3(p.bumper_body, 0.30f, 0.31f, 0.34f);
    set3(p.disc, 0.70f, 0.72f, 0.76f);
    set3(p.mass, 0.95f, 0.62f, 0.15f);
    set3(p.hot, 1.0f, 0.35f, 0.15f);
    return p;
}

ImU32 heat_color(float t, float alpha) {
    // black-body like: dark red -> orange -> yellow -> white
    t = std::clamp(t, 0.0f, 1.0f);
    const float r = std::clamp(0.35f + 1.6f * t, 0.0f, 1.0f);
    const float g = std::clamp(-0.15f + 1.5f * t, 0.0f, 1.0f);
    const float b = std::clamp(-1.0f + 2.0f * t, 0.0f, 1.0f);
    return ImGui::ColorConvertFloat4ToU32(ImVec4(r, g, b, alpha));
}

void density_color(bool dark, float t, unsigned char out[4]) {
    t = std::clamp(t, 0.0f, 1.0f);
    float r, g, b, a;
    if (dark) {
        // "inferno" (polynomial fit by M. Zucker, CC0), from its visible part (0.30) to pale yellow.
        const float u = 0.30f + 0.70f * t;
        auto poly = [u](float c0, float c1, float c2, float c3, float c4, float c5, float c6) {
            return c0 + u * (c1 + u * (c2 + u * (c3 + u * (c4 + u * (c5 + u * c6)))));
        };
        r = poly(0.0002189f, 0.1065134f, 11.6024931f, -41.7039961f, 77.1629357f, -71.3194282f, 25.1311262f);
        g = poly(0.0016510f, 0.5639564f, -3.9728540f, 17.4363989f, -33.4023589f, 32.6260643f, -12.2426690f);
        b = poly(-0.0194809f, 3.9327124f, -15.9423941f, 44.3541452f, -81.8073093f, 73.2095199f, -23.0703250f);
        a = 1.0f;
    } else {
        // ink on paper: blue, darker and more opaque where the points pile up
        r = 0.10f - 0.08f * t;
        g = 0.30f - 0.22f * t;
        b = 0.75f - 0.45f * t;
        a = 0.45f + 0.55f * t;
    }
    out[0] = static_cast<unsigned char>(std::clamp(r, 0.0f, 1.0f) * 255.0f);
    out[1] = static_cast<unsigned char>(std::clamp(g, 0.0f, 1.0f) * 255.0f);
    out[2] = static_cast<unsigned char>(std::clamp(b, 0.0f, 1.0f) * 255.0f);
    out[3] = static_cast<unsigned char>(std::clamp(a, 0.0f, 1.0f) * 255.0f);
}

void not_settled_color(bool dark, float t, unsigned char out[4]) {
    t = std::clamp(t, 0.0f, 1.0f);
    // Dark theme: from a dim grey to a light one; light theme: grey ink, more opaque where points pile up.
    const float v = dark ? 0.30f + 0.32f * t : 0.60f - 0.25f * t, a = dark ? 1.0f : 0.45f + 0.55f * t;
    out[0] = out[1] = out[2] = static_cast<unsigned char>(v * 255.0f);
    out[3] = static_cast<unsigned char>(a * 255.0f);
}

}  // namespace impactlab::gui
