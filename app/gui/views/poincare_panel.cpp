// The Poincare map: the settle detector's points only (views/poincare_panel.hpp), coloured by the impacts
// in the forcing period before them and fading with age in chaos, numbered in the order of the visits when
// periodic, under a label that says what the map knows.
#include "poincare_panel.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "render/plot2d.hpp"
#include "render/theme.hpp"
#include "render/widgets.hpp"

namespace impactlab::gui {

namespace {
struct XY {
    double x, y;
};

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

namespace {
// The clicker's orbits, one colour each, apart from the impacts' colours of the settled map.
ImU32 orbit_color(std::size_t k) {
    static constexpr ImU32 kColors[PoincarePanel::kMaxOrbits] = {
        IM_COL32(80, 220, 120, 255), IM_COL32(240, 110, 220, 255), IM_COL32(90, 170, 255, 255), IM_COL32(255, 150, 60, 255),
        IM_COL32(230, 230, 90, 255), IM_COL32(150, 110, 255, 255), IM_COL32(60, 220, 220, 255), IM_COL32(255, 90, 90, 255)};
    return kColors[k % PoincarePanel::kMaxOrbits];
}
}  // namespace

void PoincarePanel::start_orbit(double x, double v, std::uint32_t epoch) {
    if (orbits_.size() == kMaxOrbits) orbits_.erase(orbits_.begin());
    ClickedOrbit o;
    o.x0 = x;
    o.v0 = v;
    o.click_epoch = epoch;
    orbits_.push_back(std::move(o));
    clicker_ = true;
}

void PoincarePanel::feed_orbits(const ViewContext& ctx) {
    if (orbits_.empty()) return;
    ClickedOrbit& o = orbits_.back();   // only the newest runs; the others are kept as they ended
    if (o.waiting) {
        if (ctx.epoch == o.click_epoch) return;   // the restart has not come back yet
        o.waiting = false;
        o.epoch = ctx.epoch;
        o.taken = 0;
    }
    if (ctx.epoch != o.epoch) return;   // another change since: the orbit ended there
    const History<SimMsg>& secs = *ctx.sections;   // cleared at every new epoch: all of it is this orbit's
    for (std::size_t i = o.taken; i < secs.size() && o.pts.size() < kMaxOrbitPoints; ++i)
        o.pts.emplace_back(secs[i].x, secs[i].v);
    o.taken = secs.size();
}

namespace {
// The legend of the impacts' colours: its title, its dots' radius and its width at font size fs.
struct Legend {
    static constexpr const char* kNames[4] = {"0", "1", "2", "3+"};
    const char* title = "impacts/period";
    float r = 0, w = 0;
};

Legend legend_size(const bool (&impacts_seen)[4], float fs) {
    Legend lg;
    lg.r = 0.3f * fs;
    lg.w = ImGui::CalcTextSize(lg.title).x;
    for (int cat = 0; cat < 4; ++cat)
        if (impacts_seen[cat]) lg.w += 0.6f * fs + 2 * lg.r + 3 + ImGui::CalcTextSize(Legend::kNames[cat]).x;
    return lg;
}

// The label: what the map knows. The period is the settle detector's, never a guess from the transient.
// Replaying, the map is that of the replayed instant, and says so. Short words where area_w [px] is too narrow.
void map_label(const PoincareMap& map, const ViewContext& ctx, double area_w, char (&label)[160]) {
    const std::size_t n = map.points().size();
    const PoincareMap::Status status = map.status();
    const bool periodic = status == PoincareMap::Status::Periodic;
    const unsigned long long seen = map.seen();
    if (seen == 0) std::snprintf(label, sizeof label, "no section yet (one per forcing period)");
    else if (map.slow() && std::isfinite(map.decay()))
        std::snprintf(label, sizeof label, "settling (slow): the alternation shrinks x%.4f per period", map.decay());
    else if (map.slow()) std::snprintf(label, sizeof label, "settling (slow): an alternation dying out");
    else if (map.provisional())
        std::snprintf(label, sizeof label, "no period yet (provisional)  %zu of %llu points", n, seen);
    else if (status == PoincareMap::Status::Settling)
        std::snprintf(label, sizeof label, "settling...  %llu period%s, the transient is not drawn", seen, seen == 1 ? "" : "s");
    else if (periodic) std::snprintf(label, sizeof label, "period %d", map.period());
    else std::snprintf(label, sizeof label, "chaos: no period <= %d   %zu points", map.config().max_period, n);
    char when[48] = "";
    if (ctx.replay) std::snprintf(when, sizeof when, "  (replay, t = %.2f s)", ctx.last.t);
    else if (ctx.omega_moving) std::snprintf(when, sizeof when, "  (ω moving: %.3f rad/s)", ctx.last.omega);
    const auto too_wide = [&] { return ImGui::CalcTextSize(label).x + ImGui::CalcTextSize(when).x + 12 > area_w; };
    if (too_wide()) {   // a small tile or a large UI scale: the short words
        if (seen == 0) std::snprintf(label, sizeof label, "no section yet");
        else if (map.slow()) std::snprintf(label, sizeof label, "settling (slow)");
        else if (map.provisional()) std::snprintf(label, sizeof label, "no period yet  %zu", n);
        else if (status == PoincareMap::Status::Settling) std::snprintf(label, sizeof label, "settling... %llu", seen);
        else if (!periodic) std::snprintf(label, sizeof label, "chaos  %zu points", n);
        if (ctx.replay && too_wide()) std::snprintf(when, sizeof when, "  (replay)");
        if (ctx.omega_moving && too_wide()) std::snprintf(when, sizeof when, "  (ω moving)");
    }
    const std::size_t len = std::strlen(label);
    std::snprintf(label + len, sizeof label - len, "%s", when);
}

// The order of the visits, 1..k along the last cycle of a period-k map: points closer than a dot share one
// label ("1,4"), so a doubled orbit's close pairs read as pairs, not as single points.
void draw_visit_numbers(Plot& plot, const History<MapPoint>& pts, std::size_t k, float dot, float ring, float fs) {
    const std::size_t n = pts.size();
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
                             palette().axis_text, text);
    }
}

// The legend, right-aligned at height y: the impact counts seen, each with its colour's dot. A narrow tile
// (a large UI scale) takes the short title, or the dots alone, rather than clip it.
void draw_legend(Plot& plot, Legend lg, const bool (&impacts_seen)[4], float y, float fs) {
    const Palette& pal = palette();
    const float room = plot.area_max().x - plot.area_min().x - 12, dots = lg.w - ImGui::CalcTextSize(lg.title).x;
    if (dots + ImGui::CalcTextSize(lg.title).x > room) lg.title = dots + ImGui::CalcTextSize("impacts").x <= room ? "impacts" : "";
    float x = plot.area_max().x - 6;
    for (int cat = 3; cat >= 0; --cat) {
        if (!impacts_seen[cat]) continue;
        x -= ImGui::CalcTextSize(Legend::kNames[cat]).x;
        plot.draw()->AddText(ImVec2(x, y), pal.axis_text, Legend::kNames[cat]);
        x -= lg.r + 3;
        plot.draw()->AddCircleFilled(ImVec2(x, y + 0.5f * fs), lg.r, impacts_color(cat, 1.0f), 12);
        x -= lg.r + 0.6f * fs;
    }
    x -= ImGui::CalcTextSize(lg.title).x;
    plot.draw()->AddText(ImVec2(x, y), pal.axis_text, lg.title);
}
}  // namespace

void PoincarePanel::sort_points(const History<MapPoint>& pts, bool periodic, bool (&impacts_seen)[4]) {
    // Four age bands (oldest first, fading) times four impact counts (0, 1, 2, 3+): one scatter call each.
    const std::size_t n = pts.size();
    for (auto& b : buckets_) b.clear();
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t age_band = periodic ? 3 : std::min<std::size_t>(3, 4 * i / n);
        const int cat = std::min(pts[i].impacts, 3);
        impacts_seen[cat] = true;
        buckets_[age_band * 4 + static_cast<std::size_t>(cat)].push_back(static_cast<std::uint32_t>(i));
    }
}

void PoincarePanel::fit_view(const ViewContext& ctx, const AutoRange& phase_x, const AutoRange& phase_v, double area_w,
                             double area_h, double edge, double label_band) {
    const History<MapPoint>& pts = ctx.map->points();
    const std::size_t n = pts.size();
    bool orbit_fit = false;
    for (const ClickedOrbit& o : orbits_) orbit_fit = orbit_fit || (clicker_ && !o.pts.empty());
    if (orbit_fit) {   // the clicker's orbits, and the map: the view holds them all
        double xl = 1e300, xh = -1e300, vl = 1e300, vh = -1e300;
        const auto add = [&](double x, double v) {
            xl = std::min(xl, x);
            xh = std::max(xh, x);
            vl = std::min(vl, v);
            vh = std::max(vh, v);
        };
        for (const ClickedOrbit& o : orbits_) {
            add(o.x0, o.v0);
            for (const auto& [x, v] : o.pts) add(x, v);
        }
        for (std::size_t i = 0; i < n; ++i) add(pts[i].x, pts[i].v);
        const AxisFit fx = fit_axis(xl, xh, 0.002, area_w, edge, edge);
        const AxisFit fv = fit_axis(vl, vh, 0.02, area_h, edge, edge + label_band);
        // The view a click is aimed in holds still: it only grows (to take in a new orbit), and not at all
        // while the mouse is over the map, so a click lands where it was aimed.
        if (!x_.init) {
            x_.snap({fx.lo, fx.hi}, 0.0, 1e-12);
            v_.snap({fv.lo, fv.hi}, 0.0, 1e-12);
        } else if (!ImGui::IsWindowHovered(ImGuiHoveredFlags_ChildWindows)) {
            x_.snap({std::min(fx.lo, x_.cur.lo), std::max(fx.hi, x_.cur.hi)}, 0.0, 1e-12);
            v_.snap({std::min(fv.lo, v_.cur.lo), std::max(fv.hi, v_.cur.hi)}, 0.0, 1e-12);
        }
        fit_generation_ = ~std::uint64_t{0};
    } else if (n == 0 && phase_x.init) {
        // Settling: an empty map in the phase portrait's view.
        x_ = phase_x;
        v_ = phase_v;
        fit_generation_ = ~std::uint64_t{0};
    } else if (n == 0) {
        // The phase portrait is not drawn (presentation mode): the trail's own extent, not an unset 0..1 m.
        const History<SimMsg>& tr = *ctx.traj;
        double xl = ctx.last.x, xh = ctx.last.x, vl = ctx.last.v, vh = ctx.last.v;
        for (std::size_t i = ctx.trail_first; i < tr.size(); ++i) {
            xl = std::min(xl, tr[i].x);
            xh = std::max(xh, tr[i].x);
            vl = std::min(vl, tr[i].v);
            vh = std::max(vh, tr[i].v);
        }
        x_.snap({xl, xh}, 0.08, 0.004);
        v_.snap({vl, vh}, 0.08, 0.04);
        fit_generation_ = ~std::uint64_t{0};
    } else {
        const auto xe = x_extent_.update(pts, 0, [](const MapPoint& m) { return m.x; });
        const auto ve = v_extent_.update(pts, 0, [](const MapPoint& m) { return m.v; });
        const AxisFit fx = fit_axis(xe.lo, xe.hi, 0.002, area_w, edge, edge);
        const AxisFit fv = fit_axis(ve.lo, ve.hi, 0.02, area_h, edge, edge + label_band);
        if (pts.generation() != fit_generation_) {
            // A new decision (period found, chaos said): the view jumps to it rather than gliding there.
            x_.snap({fx.lo, fx.hi}, 0.0, 1e-12);
            v_.snap({fv.lo, fv.hi}, 0.0, 1e-12);
            fit_generation_ = pts.generation();
        } else {
            x_.track({fx.lo, fx.hi}, 0.0, 1e-12, ctx.frame_dt);
            v_.track({fv.lo, fv.hi}, 0.0, 1e-12, ctx.frame_dt);
        }
    }
}

void PoincarePanel::draw_points(Plot& plot, const History<MapPoint>& pts, float dot, float ring, float ui_scale) {
    // Newest band first over one shared pixel bitmap: a pixel a newer point covers is not drawn again
    // for an older one (100k points cost one pass, not sixteen).
    static constexpr float kAlpha[4] = {0.22f, 0.42f, 0.68f, 1.0f};
    plot.share_dots(true);
    // With the clicker's orbits the running one is drawn in its colour instead of the map's.
    for (std::size_t b = (clicker_ && !orbits_.empty()) ? 0 : 4; b-- > 0;) {
        for (int cat = 0; cat < 4; ++cat) {
            const auto& idx = buckets_[b * 4 + static_cast<std::size_t>(cat)];
            plot.scatter(idx.size(), [&](std::size_t j) { const MapPoint& m = pts[idx[j]]; return XY{m.x, m.v}; },
                         impacts_color(cat, kAlpha[b]), dot);
        }
    }
    plot.share_dots(false);
    for (std::size_t k = 0; k < orbits_.size(); ++k) {   // the clicker's orbits over the map, each its colour
        const auto& op = orbits_[k].pts;
        plot.scatter(op.size(), [&](std::size_t j) { return XY{op[j].first, op[j].second}; }, orbit_color(k),
                     std::max(3.0f, 3.5f * ui_scale));
        const ImVec2 c0 = plot.to_px(orbits_[k].x0, orbits_[k].v0);   // where it was started: a cross
        const float r = 4.0f * ui_scale;
        plot.draw()->AddLine(ImVec2(c0.x - r, c0.y - r), ImVec2(c0.x + r, c0.y + r), orbit_color(k), 2.0f);
        plot.draw()->AddLine(ImVec2(c0.x - r, c0.y + r), ImVec2(c0.x + r, c0.y - r), orbit_color(k), 2.0f);
    }
    if (pts.size() != 0) {
        const ImVec2 c = plot.to_px(pts.back().x, pts.back().v);
        plot.draw()->AddCircle(c, ring, palette().section_new, 0, 2.0f);
    }
}

void PoincarePanel::draw_clicker(Plot& plot, const ViewContext& ctx, ViewAction& act) {
    const float fs = ImGui::GetFontSize();
    char note[64];
    std::snprintf(note, sizeof note, "clicker: %zu orbit%s", orbits_.size(), orbits_.size() == 1 ? "" : "s");
    plate_text(plot.draw(), ImVec2(plot.area_min().x + 6, plot.area_max().y - fs - 6), note, palette().axis_text);
    const ImVec2 mp = ImGui::GetIO().MousePos;
    const double mx = plot.x_at(mp.x), mv = plot.y_at(mp.y);
    if (plot.hovered() && !plot.dragging())
        ImGui::SetTooltip("x = %+.2f mm, v = %+.3f m/s\nclick: a new orbit from here (kept in its own colour)\n"
                          "right-click: clicker off, clear the orbits", mx * 1e3, mv);
    act.start_orbit = delayed_click(click_, plot.hovered(), plot.clicked(), mx, mv, ctx.now);
    if (act.start_orbit) start_orbit(mx, mv, ctx.epoch);
}

namespace {
// The row under the plot: the section's phase phi0.
void draw_phase_row(const ViewContext& ctx, ViewAction& act) {
    float phi0 = static_cast<float>(ctx.section_phase);
    char fmt[64];
    std::snprintf(fmt, sizeof fmt, "section φ0 = %%.2f rad (%.0f°)", ctx.section_phase * 360.0 / kTwoPi);
    ImGui::SetNextItemWidth(-1);
    if (ImGui::SliderFloat("##phi0", &phi0, 0.0f, static_cast<float>(kTwoPi), fmt))
        act.section_phase = std::clamp(static_cast<double>(phi0), 0.0, kTwoPi);
    tooltip("The section's phase: a point each time the unbalance passes φ = φ0 + 2πk (0: the stroboscopic\n"
            "section). A change starts the map afresh and clears the clicker's orbits.");
}
}  // namespace

ViewAction PoincarePanel::draw(const ViewContext& ctx, const AutoRange& phase_x, const AutoRange& phase_v) {
    ViewAction act;
    feed_orbits(ctx);
    const Params& p = *ctx.params;
    const Palette& pal = palette();
    const PoincareMap& map = *ctx.map;   // replaying: as it stood at the cursor
    const History<MapPoint>& pts = map.points();
    const std::size_t n = pts.size();
    const bool periodic = map.status() == PoincareMap::Status::Periodic;
    // A periodic orbit is a few points: large. A chaotic one is thousands: small enough to show structure.
    const float dot = periodic ? std::max(7.0f, 8.0f * ctx.ui_scale) : std::max(3.0f, 3.5f * ctx.ui_scale);
    const float ring = std::max(dot * 0.5f + 3.0f, 6.0f * ctx.ui_scale);
    bool impacts_seen[4] = {};
    sort_points(pts, periodic, impacts_seen);
    const bool legend = impacts_seen[1] || impacts_seen[2] || impacts_seen[3];
    const float fs = ImGui::GetFontSize();
    const Legend lg = legend_size(impacts_seen, fs);

    // The fit, in the data area Plot::begin will lay out (its margins): the newest point's ring stays off
    // the frame, and a band at the top for the label and the legend (a second line when they do not fit
    // side by side) stays free of points.
    // A row under the plot for the section's phase, unless the tile is too small to spare it.
    ImVec2 avail = ImGui::GetContentRegionAvail();
    const bool phase_row = avail.y > 8.0f * ImGui::GetFrameHeightWithSpacing();
    if (phase_row) avail.y -= ImGui::GetFrameHeightWithSpacing();
    const double area_w = avail.x - fs * 4.4f, area_h = avail.y - fs * 2.8f;
    char label[160];
    map_label(map, ctx, area_w, label);
    const bool two_lines = legend && ImGui::CalcTextSize(label).x + lg.w + 24 > area_w;
    const double edge = ring + 3.0 + 0.06 * std::min(area_w, area_h);
    const double label_band = (two_lines ? 2.1 : 1.0) * fs + 10.0;
    fit_view(ctx, phase_x, phase_v, area_w, area_h, edge, label_band);

    Plot plot;
    Axes ax;
    ax.x_label = "x [mm]";
    ax.y_label = "v [m/s]";
    ax.x_scale = 1e3;
    if (!plot.begin("##poincare", avail, x_.cur, v_.cur, ax)) return act;
    if (p.has_bumper()) {   // impact law "none": no bumper to draw
        plot.shade_right_of(ctx.xI, pal.bumper);
        plot.vline(ctx.xI, pal.bumper, 1.5f, true);
    }
    draw_points(plot, pts, dot, ring, ctx.ui_scale);
    if (periodic && n >= static_cast<std::size_t>(map.period()))
        draw_visit_numbers(plot, pts, static_cast<std::size_t>(map.period()), dot, ring, fs);
    const ImVec2 lp(plot.area_min().x + 6, plot.area_min().y + 4);
    plate_text(plot.draw(), lp, label, pal.title_text);
    if (legend) draw_legend(plot, lg, impacts_seen, two_lines ? lp.y + fs + 4 : lp.y, fs);   // beside the label or below it
    if (clicker_) draw_clicker(plot, ctx, act);
    if (plot.hovered() && ImGui::IsMouseClicked(ImGuiMouseButton_Right)) ImGui::OpenPopup("##poincare_menu");
    plot.end();
    if (ImGui::BeginPopup("##poincare_menu")) {
        if (ImGui::MenuItem("Clicker: each click starts an orbit in its own colour", nullptr, clicker_)) clicker_ = !clicker_;
        if (ImGui::MenuItem("Clear the orbits", nullptr, false, !orbits_.empty())) orbits_.clear();
        if (ImGui::MenuItem("Section at φ = 2πn (phase 0)", nullptr, false, ctx.section_phase != 0.0)) act.section_phase = 0.0;
        ImGui::EndPopup();
    }
    if (phase_row) draw_phase_row(ctx, act);
    return act;
}

}  // namespace impactlab::gui
