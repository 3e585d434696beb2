// The one list of the visualiser's tiled views: each one's key (the flags --hide, --maximise and
// --presentation, --state-json and session files), its titles, its place in the default layout and whether
// presentation mode may feature it. The layout, the options, the tiles and the sessions read it from here.
// GL- and ImGui-free.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace impactlab::gui {

// The plot tiles (the controls column is laid out apart), in the table's order.
enum class PanelId : int { Rig, Bifurcation, Phase, Poincare, Potential, Strip, Plane, Basins };
inline constexpr int kPanelCount = 8;

struct ViewInfo {
    PanelId id;
    const char* key;
    const char* titles[3];   // the tile's title, longest first (nullptr where there are fewer)
    int row;                 // the default layout's row: 0 rig and diagram, 1 the three plots, 2 the analysis
                             // maps, 3 x(t)
    float width_share;       // of its row, against the other tiles'
    int presentation_order;  // 1, 2, ...: presentation mode may show it beside the rig, in this order (V); 0 never
    bool on_demand = false;  // not in the default layout: opened (F2, F3, a job started) and closed, never
                             // "hidden" (View > Panels > Show all leaves it as it is; sessions do not save it)
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
     3, 1.0f, 4},
    {PanelId::Plane, "plane", {"Parameter plane", "Plane", nullptr}, 2, 1.0f, 0, true},
    {PanelId::Basins, "basins", {"Basins of attraction (φ = 0)", "Basins", nullptr}, 2, 1.0f, 0, true},
};
inline constexpr int kViewRows = 4;
// Shares of the height; a row with no panel shown gives its share away (the analysis row is empty unless
// a plane or the basins are open).
inline constexpr float kViewRowWeight[kViewRows] = {0.41f, 0.34f, 0.5f, 0.25f};

inline const ViewInfo& view_info(PanelId p) { return kViews[static_cast<int>(p)]; }
inline const char* panel_key(PanelId p) { return view_info(p).key; }
inline bool on_demand(PanelId p) { return view_info(p).on_demand; }
// Which panels a fresh window shows: all but the on-demand ones.
constexpr std::array<bool, kPanelCount> default_visible() {
    std::array<bool, kPanelCount> v{};
    for (int i = 0; i < kPanelCount; ++i) v[static_cast<std::size_t>(i)] = !kViews[i].on_demand;
    return v;
}
std::optional<PanelId> panel_from_key(const std::string& key);
// The panel keys joined with ", " (for error messages); presentable: only those presentation mode shows, in order.
std::string panel_keys(bool presentable = false);
// The panels presentation mode may show, in their order (the bar's combo, the View menu, key V).
std::vector<PanelId> presentation_plots();

}  // namespace impactlab::gui
