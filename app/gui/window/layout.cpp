#include "layout.hpp"

#include <algorithm>
#include <cmath>

namespace impactlab::gui {

namespace {

// A row of the normal layout: its tiles, their width shares, and the row's share of the height.
struct Row {
    std::vector<std::vector<PanelId>> tiles;
    float weight = 1;      // share of the height
    bool strip = false;    // only the x(t) strip: it may be lower than a plot
};

// Heights with every row at least its minimum and otherwise in proportion to the weights (the rows under
// their minimum are fixed there and the rest share what is left).
std::vector<float> share_heights(float total, const std::vector<float>& weights, const std::vector<float>& mins) {
    const std::size_t n = weights.size();
    std::vector<float> h(n, 0.0f);
    std::vector<bool> fixed(n, false);
    for (std::size_t pass = 0; pass <= n; ++pass) {
        float free_total = total, free_weight = 0;
        for (std::size_t i = 0; i < n; ++i) {
            if (fixed[i]) free_total -= mins[i];
            else free_weight += weights[i];
        }
        bool changed = false;
        for (std::size_t i = 0; i < n; ++i) {
            if (fixed[i]) {
                h[i] = mins[i];
                continue;
            }
            h[i] = free_weight > 0 ? free_total * weights[i] / free_weight : 0.0f;
            if (h[i] < mins[i]) {
                fixed[i] = true;
                changed = true;
            }
        }
        if (!changed) break;
    }
    return h;
}

// Splits [x, x + w) into n integer widths in proportion to `shares`, each at least `min_w` where it can be.
std::vector<float> share_widths(float w, const std::vector<float>& shares, float min_w) {
    std::vector<float> mins(shares.size(), std::min(min_w, w / static_cast<float>(shares.size())));
    return share_heights(w, shares, mins);
}

void normal_tiles(const LayoutRequest& r, const Rect& area, Layout& out) {
    const float s = r.scale;
    auto shown = [&](PanelId p) { return r.visible[static_cast<std::size_t>(p)]; };
    if (r.maximised && shown(*r.maximised)) {
        out.tiles.push_back({area, {*r.maximised}});
        return;
    }
    // The rows as the view table has them, hidden panels left out.
    std::vector<std::pair<std::vector<PanelId>, float>> wanted;
    for (int row = 0; row < kViewRows; ++row) {
        wanted.push_back({{}, kViewRowWeight[row]});
        for (const ViewInfo& v : kViews)
            if (v.row == row) wanted.back().first.push_back(v.id);
    }
    const float min_w = min_tile_w(s);
    std::vector<Row> rows;
    for (const auto& [panels, weight] : wanted) {
        std::vector<PanelId> vis;
        for (PanelId p : panels)
            if (shown(p)) vis.push_back(p);
        if (vis.empty()) continue;
        // As many tiles side by side as the width holds at their minimum; the rest become tabs of the last.
        const float per_row = std::floor(area.w / std::max(min_w, 1.0f));
        const std::size_t fit = per_row >= static_cast<float>(vis.size()) ? vis.size()
                                                                          : static_cast<std::size_t>(std::max(1.0f, per_row));
        Row row;
        row.weight = weight;
        row.strip = vis.size() == 1 && vis[0] == PanelId::Strip;
        for (std::size_t i = 0; i < vis.size(); ++i) {
            if (i < fit) row.tiles.push_back({vis[i]});
            else row.tiles.back().push_back(vis[i]);
        }
        rows.push_back(std::move(row));
    }
    if (rows.empty()) return;
    // Rows that do not fit the height give their panels to the row above (as tabs of its least loaded tile).
    auto min_h = [&](const Row& row) { return row.strip ? min_strip_h(s) : min_tile_h(s); };
    for (;;) {
        float need = 0;
        for (const Row& row : rows) need += min_h(row);
        if (need <= area.h || rows.size() == 1) break;
        Row last = std::move(rows.back());
        rows.pop_back();
        Row& above = rows.back();
        for (auto& t : last.tiles) {
            // The least loaded tile of the row above takes them.
            std::size_t best = above.tiles.size() - 1;
            for (std::size_t i = above.tiles.size(); i-- > 0;)
                if (above.tiles[i].size() < above.tiles[best].size()) best = i;
            above.tiles[best].insert(above.tiles[best].end(), t.begin(), t.end());
        }
        above.weight += last.weight;
        above.strip = false;
    }
    std::vector<float> weights, mins;
    for (const Row& row : rows) {
        weights.push_back(row.weight);
        mins.push_back(std::min(min_h(row), area.h / static_cast<float>(rows.size())));
    }
    const std::vector<float> heights = share_heights(area.h, weights, mins);
    float y = area.y;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const float y1 = i + 1 == rows.size() ? area.bottom() : std::round(y + heights[i]);
        const Row& row = rows[i];
        std::vector<float> shares;   // a tile of tabs takes its first panel's share (the rig is wide)
        for (const auto& t : row.tiles) shares.push_back(view_info(t[0]).width_share);
        const std::vector<float> widths = share_widths(area.w, shares, min_w);
        float x = area.x;
        for (std::size_t k = 0; k < row.tiles.size(); ++k) {
            const float x1 = k + 1 == row.tiles.size() ? area.right() : std::round(x + widths[k]);
            out.tiles.push_back({{x, y, x1 - x, y1 - y}, row.tiles[k]});
            x = x1;
        }
        y = y1;
    }
}

void presentation_tiles(const LayoutRequest& r, Layout& out) {
    const float s = r.scale;
    const Rect a = r.area;
    // The bar: one row of controls where the width holds them (about 1150 scaled pixels), else two.
    out.bar_lines = a.w >= 1150.0f * s ? 1 : 2;
    const float bar_h = std::round(static_cast<float>(out.bar_lines) * (r.frame_h + 5.0f * s) + 9.0f * s);
    out.bar = {a.x, a.y, a.w, bar_h};
    const Rect rest{a.x, a.y + bar_h, a.w, a.h - bar_h};
    const PanelId plot = r.featured == PanelId::Rig ? PanelId::Phase : r.featured;
    if (r.maximised && (*r.maximised == PanelId::Rig || *r.maximised == plot)) {
        out.tiles.push_back({rest, {*r.maximised}});
        return;
    }
    // Side by side on a landscape screen (the rig is about twice as wide as high), else one above the other.
    if (rest.w >= 1.25f * rest.h) {
        const float rig_w = std::round(rest.w * 0.58f);
        out.tiles.push_back({{rest.x, rest.y, rig_w, rest.h}, {PanelId::Rig}});
        out.tiles.push_back({{rest.x + rig_w, rest.y, rest.w - rig_w, rest.h}, {plot}});
    } else {
        const float rig_h = std::round(rest.h * 0.42f);
        out.tiles.push_back({{rest.x, rest.y, rest.w, rig_h}, {PanelId::Rig}});
        out.tiles.push_back({{rest.x, rest.y + rig_h, rest.w, rest.h - rig_h}, {plot}});
    }
}

}  // namespace

float min_tile_w(float scale) { return 190.0f * scale; }
float min_tile_h(float scale) { return 140.0f * scale; }
float min_strip_h(float scale) { return 105.0f * scale; }
float controls_natural_w(float scale) { return 292.0f * scale; }

Layout compute_layout(const LayoutRequest& req) {
    Layout out;
    LayoutRequest r = req;
    // A degenerate request (no window yet, a scale of 0) lays out nothing or at scale 1, never crashes.
    if (!(r.scale > 0) || !std::isfinite(r.scale)) r.scale = 1.0f;
    if (!std::isfinite(r.frame_h) || r.frame_h < 0) r.frame_h = 0;
    for (float v : {r.area.x, r.area.y, r.area.w, r.area.h})
        if (!std::isfinite(v)) return out;
    if (r.area.empty()) return out;
    if (r.mode == LayoutMode::Presentation) {
        presentation_tiles(r, out);
        return out;
    }
    Rect plots = r.area;
    if (r.controls_visible) {
        // At most a third of the width (and never so much that no plot fits beside it).
        const float natural = std::round(controls_natural_w(r.scale));
        const float cap = std::max(std::min(240.0f, r.area.w), std::round(0.34f * r.area.w));
        const float w = std::min({natural, cap, std::max(r.area.w - min_tile_w(r.scale), 0.5f * r.area.w)});
        out.controls = {r.area.x, r.area.y, w, r.area.h};
        out.controls_narrow = w < natural - 0.5f;
        // Unknown (0) until all sections have been drawn stacked once: the App measures them on that frame.
        out.controls_tabbed = r.controls_need_h > r.area.h;
        plots = {r.area.x + w, r.area.y, r.area.w - w, r.area.h};
    }
    normal_tiles(r, plots, out);
    return out;
}

bool overlaps(const Rect& a, const Rect& b) {
    return a.x < b.right() && b.x < a.right() && a.y < b.bottom() && b.y < a.bottom();
}

bool contains(const Rect& outer, const Rect& inner) {
    return inner.x >= outer.x && inner.y >= outer.y && inner.right() <= outer.right() && inner.bottom() <= outer.bottom();
}

bool LabelPlacer::place(const Rect& box) {
    if (!contains(bounds_, box)) return false;
    for (const Rect& p : placed_)
        if (overlaps(p, box)) return false;
    placed_.push_back(box);
    return true;
}

int LabelPlacer::place_first(const std::vector<Rect>& candidates) {
    for (std::size_t i = 0; i < candidates.size(); ++i)
        if (place(candidates[i])) return static_cast<int>(i);
    return -1;
}

double RigMagnify::wall_x() const { return std::max(kWallX, gain * kTravel + kCartHalfW + kSpringRoom); }

double RigMagnify::draw_x(double x) const {
    // Beyond the usual reach (never at the bumper, |xI| <= 20 mm) the cart stops short of the walls.
    const double room = wall_x() - kCartHalfW - 0.5 * kSpringRoom;
    return std::clamp(gain * x, -room, room);
}

}  // namespace impactlab::gui
