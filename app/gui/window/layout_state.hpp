// The layout's state between frames (tiles.cpp draws it, layout.hpp computes it): the mode, which panels are
// shown, hidden or maximised, each tile's active tab, the controls column's measured heights, and this
// frame's Layout. UI thread only.
#pragma once

#include <array>
#include <optional>

#include "window/layout.hpp"

namespace impactlab::gui {

struct LayoutState {
    // Presentation mode raises the UI scale to 1.5 at least; normal_scale is the user's scale to go back to.
    LayoutMode mode = LayoutMode::Normal;
    float normal_scale = 1.0f;
    std::array<bool, kPanelCount> panel_visible = default_visible();   // on-demand panels: open
    bool controls_visible = true;
    std::optional<PanelId> maximised;
    std::optional<PanelId> hovered_panel;         // the panel under the mouse at the last frame (key Z)
    std::optional<PanelId> focus_tab;             // an analysis tile just opened: its tab comes to the front
    PanelId featured = PanelId::Phase;            // presentation mode's plot
    std::array<PanelId, kPanelCount> tile_tab{};  // the active tab of the tile whose first panel is the index
    double magnify[2] = {1.0, 3.0};               // the rig's displacement magnification: normal, presentation
    float controls_group_h[3] = {};               // [px] the controls' groups as last drawn
    float controls_need_h = 0;                    // [px] all of them stacked (0: not all measured yet)
    float controls_measured_scale = 0;            // the UI scale they were measured at
    int controls_focus = -1;                      // the controls' group (0 Run, 1 View, 2 State) to bring to the front
    int controls_tab = -1;                        // the group shown when the controls are tabbed (-1: not tabbed)
    Layout frame;                                 // this frame's
};

}  // namespace impactlab::gui
