// The one list of the visualiser's tiled views: each one's key (the flags --hide, --maximise and
// --presentation, --state-json and session files), its titles, its place in the default layout and whether
// presentation mode may feature it. The layout, the options, the tiles and the sessions read it from here.
// GL- and ImGui-free.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace impactlab::gui {

// The plot tiles (the controls column is laid out apart), in the table's order.
enum class PanelId : int { Rig, Bifurcation, Phase, Poincare, Potential, Strip };
inline constexpr int kPanelCount = 6;

struct ViewInfo {
    PanelId id;
    const char* key;
    const char* titles[3];   // the tile's title, longest first (nullptr where there are fewer)
    int row;                 // the default layout's row: 0 rig and diagram, 1 the three plots, 2 x(t)
    float width_share;       // of its row, against the other tiles'
    int presentation_order;  // 1, 2, ...: presentation mode may show it beside the rig, in this order (V); 0 never
};

inline constexpr ViewInfo kViews[kPanelCount] = {
    {PanelId::Rig, "rig", {"Rig (top view, to scale)", "Rig", nullptr}, 0, 0.58f, 0},
    {PanelId::Bifurcation, "bifurcation", {"Bifurcation diagram", "Bifurcation", nullptr}, 0, 0.42f, 5},
    {PanelId::Phase, "phase", {"Phase portrait (x, v)", "Phase (x, v)", nullptr}, 1, 1.0f, 1},
    {PanelId::Poincare, "poincare", {"Poincaré map (φ = 2πn)", "Poincaré map", "Poincaré"}, 1, 1.0f, 2},
    {PanelId::Potential, "potential", {"Potential well V(x)", "V(x)", nullptr}, 1, 1.0f, 3},
    {PanelId::Strip, "strip",
     {"Displacement x(t)        dots: Poincaré sections (φ = 2πn)    dashed: bumper x_I",
      "x(t)    dots: sections (φ = 2πn)    dashed: x_I", "x(t)"},
     2, 1.0f, 4},
};
inline constexpr int kViewRows = 3;
inline constexpr float kViewRowWeight[kViewRows] = {0.41f, 0.34f, 0.25f};   // shares of the height

inline const ViewInfo& view_info(PanelId p) { return kViews[static_cast<int>(p)]; }
inline const char* panel_key(PanelId p) { return view_info(p).key; }
std::optional<PanelId> panel_from_key(const std::string& key);
// The panel keys joined with ", " (for error messages); presentable: only those presentation mode shows, in order.
std::string panel_keys(bool presentable = false);
// The panels presentation mode may show, in their order (the bar's combo, the View menu, key V).
std::vector<PanelId> presentation_plots();

}  // namespace impactlab::gui
