// The phase portrait (x, v): the trail of the last forcing periods, fading by age, the newest section
// points on it, the cart now, and the companion under it. A plain click starts the cart from (x, v) there.
#include "phase_panel.hpp"

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

namespace impactlab::gui {

namespace {
struct XY {
    double x, y;
};
}  // namespace

ViewAction PhasePanel::draw(const ViewContext& ctx) {
    const History<SimMsg>& tr = *ctx.traj;
    const History<SimMsg>& secs = *ctx.sections;
    const Params& p = *ctx.params;
    ViewAction act;
    const Palette& pal = palette();
    const std::size_t n = tr.size();
    const std::size_t first = ctx.trail_first;
    // Auto-fit to the trail (and keep the bumper in view when it is near).
    const auto xe = x_extent_.update(tr, first, [](const SimMsg& m) { return m.x; });
    const auto ve = v_extent_.update(tr, first, [](const SimMsg& m) { return m.v; });
    double xl = xe.lo, xh = xe.hi, vl = ve.lo, vh = ve.hi;
    if (first >= n) {
        xl = xh = ctx.last.x;
        vl = vh = 0;
    }
    if (ctx.xI > xh && ctx.xI - xh < 0.004) xh = ctx.xI;
    const double dt = ctx.frame_dt;
    x_.track({xl, xh}, 0.08, 0.004, dt);
    v_.track({vl, vh}, 0.08, 0.04, dt);
    Plot plot;
    Axes ax;
    ax.x_label = "x [mm]";
    ax.y_label = "v [m/s]";
    ax.x_scale = 1e3;
    if (!plot.begin("##phase", ImGui::GetContentRegionAvail(), x_.cur, v_.cur, ax)) return act;
    if (p.has_bumper()) {   // impact law "none": no bumper to draw
        plot.shade_right_of(ctx.xI_shown, pal.bumper);
        plot.vline(ctx.xI_shown, pal.bumper, 1.5f, true);
    }
    plot.hline(0.0, pal.grid, 1.0f);
    const History<SimMsg>& ct = ctx.companion->traj();   // the companion over the same stretch of time, under the cart
    const bool comp = ctx.companion_shown();
    const std::size_t cf = comp && first < n ? ct.lower_bound(tr[first].t, [](const SimMsg& m) { return m.t; }) : ct.size();
    if (comp)
        plot.path(ct.size() - cf, [&](std::size_t i) { const SimMsg& m = ct[cf + i]; return XY{m.x, m.v}; },
                  companion_color(0.6f), 1.3f);
    plot.trail(n - first, tr.seq_of(first), tr.generation(),
               [&](std::size_t i) { const SimMsg& m = tr[first + i]; return XY{m.x, m.v}; }, pal.trace, 1.6f);
    // The latest section points on the orbit, and the cart now.
    const std::size_t ns = secs.size(), s0 = ns > 64 ? ns - 64 : 0;
    plot.scatter(ns - s0, [&](std::size_t i) { const SimMsg& m = secs[s0 + i]; return XY{m.x, m.v}; }, pal.section, 4.0f);
    const ImVec2 c = plot.to_px(ctx.last.x, ctx.last.v);
    plot.draw()->AddCircleFilled(c, 4.5f * ctx.ui_scale, pal.trail_head);
    plot.draw()->AddCircle(c, 7.0f * ctx.ui_scale, pal.trace, 0, 1.5f);
    if (comp) plot.draw()->AddCircle(plot.to_px(ctx.companion->last().x, ctx.companion->last().v), 6.0f * ctx.ui_scale, companion_color(1.0f), 0, 2.0f);
    char buf[64];
    std::snprintf(buf, sizeof buf, "trail %.0f periods", static_cast<double>(ctx.trail_periods));
    plot.draw()->AddText(ImVec2(plot.area_min().x + 6, plot.area_min().y + 4), pal.axis_text, buf);
    // A plain click starts the cart from (x, v) there (drag, wheel and double-click keep zooming).
    const ImVec2 mp = ImGui::GetIO().MousePos;
    const double mx = plot.x_at(mp.x), mv = plot.y_at(mp.y);
    if (plot.hovered() && !plot.dragging())
        ImGui::SetTooltip("x = %+.2f mm, v = %+.3f m/s\nclick to start from here", mx * 1e3, mv);
    act.set_state = delayed_click(click_, plot.hovered(), plot.clicked(), mx, mv, ctx.now);
    plot.end();
    return act;
}

}  // namespace impactlab::gui
