// The colours and legends the map views share (the parameter plane, the basins): period classes, a
// continuous ramp, attractor labels, a legend swatch and the plane's axis names. UI thread (ImGui).
#pragma once

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace impactlab::gui::maps {

struct Rgb {
    unsigned char r, g, b;
};
inline ImU32 col(Rgb c, float a = 1.0f) { return IM_COL32(c.r, c.g, c.b, static_cast<int>(255 * a)); }

// Period classes of a plane (the scan's `period`: 1..16 section values, 0 for more: chaos or a long period,
// -1 for a point that had not settled).
inline Rgb period_rgb(int k) {
    switch (k) {
        case 1: return {66, 120, 205};
        case 2: return {72, 178, 92};
        case 3: return {222, 196, 62};
        case 4: return {238, 136, 44};
        case 5: return {150, 96, 210};
        case 6: return {64, 196, 196};
        case 7:
        case 8: return {226, 100, 168};
        case 0: return {196, 36, 36};
        case -1: return {70, 70, 70};      // not settled (impactlab::kNotSettled): dark grey
        default: return {150, 150, 150};   // 9..16
    }
}
inline const char* period_name(int k) {
    static char buf[24];
    if (k == -1) return "not settled";
    if (k == 0) return "chaos / > 16";
    if (k >= 9) return "period 9-16";
    if (k == 7 || k == 8) return "period 7-8";
    std::snprintf(buf, sizeof buf, "period %d", k);
    return buf;
}
inline int period_class(int k) { return k >= 9 ? 9 : k == 8 ? 7 : k < 0 ? 8 : k; }   // 8: not settled

// A continuous measure (impacts, lyapunov, x range): dark blue to yellow, t in [0, 1].
inline Rgb ramp_rgb(double t) {
    static const Rgb stops[] = {{48, 18, 92}, {40, 96, 160}, {32, 160, 140}, {120, 200, 80}, {250, 230, 40}};
    t = std::clamp(t, 0.0, 1.0) * 4.0;
    const int i = std::min(static_cast<int>(t), 3);
    const double f = t - i;
    auto mix = [f](unsigned char a, unsigned char b) { return static_cast<unsigned char>(a + (b - a) * f); };
    return {mix(stops[i].r, stops[i + 1].r), mix(stops[i].g, stops[i + 1].g), mix(stops[i].b, stops[i + 1].b)};
}

// Attractors of a basin map: the label's colour.
inline Rgb label_rgb(int id) {
    static const Rgb c[] = {{66, 120, 205}, {238, 136, 44}, {72, 178, 92}, {196, 56, 56}, {150, 96, 210},
                            {64, 196, 196}, {222, 196, 62}, {226, 100, 168}, {130, 90, 60}, {160, 160, 160}};
    return c[static_cast<std::size_t>(id) % (sizeof c / sizeof c[0])];
}

// A legend swatch and its text on one line.
inline void swatch(Rgb c, const char* text) {
    const float h = ImGui::GetTextLineHeight();
    const ImVec2 p = ImGui::GetCursorScreenPos();
    ImGui::GetWindowDrawList()->AddRectFilled(ImVec2(p.x, p.y + 2), ImVec2(p.x + h, p.y + h - 1), col(c));
    ImGui::Dummy(ImVec2(h, h));
    ImGui::SameLine();
    ImGui::TextUnformatted(text);
}

inline double axis_scale(const std::string& name) { return name == "xI" ? 1e3 : 1.0; }
inline const char* axis_label(const std::string& name) {
    if (name == "omega") return "omega [rad/s]";
    if (name == "xI") return "xI [mm]";
    return "m0e [kg m]";
}

}  // namespace impactlab::gui::maps
