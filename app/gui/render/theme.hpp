// Dark and light themes: the ImGui style plus the colours the plots and the rig use. UI thread only.
#pragma once

#include <imgui.h>

namespace impactlab::gui {

struct Palette {
    bool dark = true;
    ImU32 plot_bg, plot_frame, grid, grid_minor, axis_text, title_text;
    ImU32 trace, trace2, trail_head, section, section_new, bumper, energy, cursor, warn;
    // Rig (linear RGB floats for the shaders)
    float bg_top[3], bg_bottom[3], rig_grid[3], field[3];
    float rail[3], cart[3], cart_edge[3], spring[3], spring_back[3], magnet_n[3], magnet_s[3];
    float wall[3], bumper_body[3], disc[3], mass[3], hot[3], text[3];
};

// Applies the theme to ImGui's style (scaled) and returns the matching palette.
const Palette& apply_theme(bool dark, float ui_scale);
const Palette& palette();

// Colour maps for force and density: t in [0, 1].
ImU32 heat_color(float t, float alpha = 1.0f);
void density_color(bool dark, float t, unsigned char rgba[4]);
// The same scale in grey, for the points of a diagram level that has not settled (a transient or chaos).
void not_settled_color(bool dark, float t, unsigned char rgba[4]);

}  // namespace impactlab::gui
