// Where the visualiser's tiles go: the pure arithmetic of the window's layout, GL- and
// ImGui-free so that it is unit-tested (tests/app/layout_test.cpp). Given the viewport, the UI scale, which
// panels are shown or maximised and the mode, it returns rectangles; App::layout_and_draw only draws them.
//
// The layout reflows with the scale: every tile has a minimum size in scaled pixels; a row that cannot hold
// its tiles side by side stacks the extra panels as tabs in its last tile, and rows that do not fit the
// height hand their panels to the row above as tabs. Hidden panels give their space to the others.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "views/view_table.hpp"

namespace impactlab::gui {

enum class LayoutMode { Normal, Presentation };

struct Rect {
    float x = 0, y = 0, w = 0, h = 0;   // [px] top-left corner and size
    float right() const { return x + w; }
    float bottom() const { return y + h; }
    bool empty() const { return w <= 0 || h <= 0; }
};

struct LayoutRequest {
    Rect area;                        // the viewport below the menu and above the status bar
    float scale = 1.0f;               // the UI scale (fonts and chrome grow with it)
    float frame_h = 23.0f;            // [px] ImGui's frame height at this scale (a slider, a button)
    LayoutMode mode = LayoutMode::Normal;
    bool controls_visible = true;
    float controls_need_h = 0;        // [px] the controls' content, all sections stacked (0: not measured yet)
    std::array<bool, kPanelCount> visible = default_visible();
    std::optional<PanelId> maximised; // fills the plot area
    PanelId featured = PanelId::Phase;   // presentation mode: the plot beside the rig
};

// One tile: a window with one panel, or several stacked as tabs (the first is the default tab).
struct Tile {
    Rect rect;
    std::vector<PanelId> panels;
};

struct Layout {
    Rect controls;                    // empty when hidden (and in presentation mode)
    bool controls_tabbed = false;     // the column is too short for every section: Run / State / View tabs
    bool controls_narrow = false;     // narrower than the controls' natural width: short labels
    Rect bar;                         // presentation mode: the slim control bar (empty otherwise)
    int bar_lines = 0;                // its rows of controls
    std::vector<Tile> tiles;
};

// Minimum sizes [px] at a scale: a plot keeps room for its axes, ticks and some data.
float min_tile_w(float scale);
float min_tile_h(float scale);
float min_strip_h(float scale);
// The controls column's natural width at a scale (its labels unclipped).
float controls_natural_w(float scale);

Layout compute_layout(const LayoutRequest& r);

// Labels over a drawing (the rig's): each is placed only where it is wholly inside the bounds and clear of
// the labels placed before it, so the first placed win and none overprints another. GL-free.
class LabelPlacer {
public:
    explicit LabelPlacer(Rect bounds) : bounds_(bounds) {}
    // True (and the box is kept) when `box` fits inside the bounds and overlaps no kept box.
    bool place(const Rect& box);
    // Marks a box taken without placing anything there (a drawn part no label may cover), even one that
    // reaches beyond the bounds.
    void reserve(const Rect& box) { placed_.push_back(box); }
    // Tries the candidates in order; the index of the one placed, or -1.
    int place_first(const std::vector<Rect>& candidates);
    const std::vector<Rect>& placed() const { return placed_; }

private:
    Rect bounds_;
    std::vector<Rect> placed_;
};

bool overlaps(const Rect& a, const Rect& b);
bool contains(const Rect& outer, const Rect& inner);

// The rig's displacement magnification, in the drawing only: positions are magnified
// about x = 0 (the hilltop, where the springs are relaxed and the magnets face each other) for the cart and
// the bumper alike, so a contact still looks like one. The end walls move out when the magnified travel
// needs the room.
struct RigMagnify {
    double gain = 1.0;                 // drawn displacement per true displacement
    // [m, drawing] the cart's centre (kept off the end walls), its face towards the bumper, the bumper's face.
    double draw_x(double x) const;
    double cart_face(double x) const { return draw_x(x) + kCartHalfW; }
    double bumper_face(double xI) const { return gain * xI + kCartHalfW; }
    // [m, drawing] the inner face of the end walls: the rig as built, moved out when the magnified travel
    // (+/- kTravel) needs the room.
    double wall_x() const;
    static constexpr double kTravel = 0.026;   // [m] the cart's usual reach (the wells and the chaos)
    // The rig's geometry this needs (rig_view.hpp's rig::kWallX and rig::kCartHalfW; checked there).
    static constexpr double kWallX = 0.136, kCartHalfW = 0.040, kSpringRoom = 0.024;
    static constexpr double kMin = 1.0, kMax = 10.0;
};

}  // namespace impactlab::gui
