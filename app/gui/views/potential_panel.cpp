// The potential well V(x) of the springs and magnets, the energy as a level (its cuts are the turning
// points), the cart on the curve and the bumper. A plain click puts the cart at x there, at rest.
#include "potential_panel.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "impactlab/forces.hpp"
#include "render/plot2d.hpp"
#include "render/theme.hpp"

namespace impactlab::gui {

namespace {
struct XY {
    double x, y;
};
}  // namespace

ViewAction PotentialPanel::draw(const ViewContext& ctx) {
    const History<SimMsg>& tr = *ctx.traj;
    const Params& p = *ctx.params;
    ViewAction act;
    const Palette& pal = palette();
    const std::string key = p.stiffness_id + "#" + std::to_string(ctx.params_rev);   // k is editable
    if (curve_for_ != key) {
        curve_for_ = key;
        curve_x_.clear();
        curve_v_.clear();
        for (int i = 0; i <= 400; ++i) {
            const double x = -0.026 + 0.052 * i / 400.0;
            curve_x_.push_back(x);
            curve_v_.push_back(spring_magnet_potential(p, x));
        }
    }
    const double vmin = *std::min_element(curve_v_.begin(), curve_v_.end());
    const Range xr{-0.026, 0.026};
    // The y range follows the largest energy of the phase portrait's trail (grows at once, shrinks
    // slowly), with room for the "E = ..." label above the line.
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const auto ee = energy_extent_.update(tr, ctx.trail_first, [](const SimMsg& m) { return m.energy; });
    const double e_max = ee.empty ? ctx.last.energy : std::max(ee.hi, ctx.last.energy);
    e_max_ = e_max;
    const float fs = ImGui::GetFontSize();
    const AxisFit fy = potential_y_range(vmin, e_max, avail.y - fs * 2.8f, fs * 1.6f);
    y_.track({fy.lo, fy.hi}, 0.0, 1e-12, ctx.frame_dt);
    const Range yr = y_.cur;
    Plot plot;
    Axes ax;
    ax.x_label = "x [mm]";
    ax.y_label = "V(x), E [mJ]";
    ax.x_scale = 1e3;
    ax.y_scale = 1e3;
    if (!plot.begin("##potential", avail, xr, yr, ax)) return act;
    if (p.has_bumper()) {   // impact law "none": no bumper to draw
        plot.shade_right_of(ctx.xI_shown, pal.bumper);
        plot.vline(ctx.xI_shown, pal.bumper, 1.5f, true);
    }
    plot.path(curve_x_.size(), [&](std::size_t i) { return XY{curve_x_[i], curve_v_[i]}; }, pal.trace2, 2.0f);
    // Total mechanical energy as a level: where it cuts V(x) are the turning points.
    plot.hline(ctx.last.energy, pal.energy, 1.2f, true);
    char buf[48];
    std::snprintf(buf, sizeof buf, "E = %.2f mJ", ctx.last.energy * 1e3);
    plot.text(xr.lo + 0.001, ctx.last.energy, buf, pal.energy, ImVec2(0, 1.05f));
    const double vx = spring_magnet_potential(p, ctx.last.x);
    const ImVec2 c = plot.to_px(ctx.last.x, vx);
    plot.draw()->AddCircleFilled(c, 6.0f * ctx.ui_scale, pal.trace);
    plot.draw()->AddCircle(c, 6.0f * ctx.ui_scale, pal.trail_head, 0, 1.5f);
    if (ctx.companion_shown()) {
        const double xc = ctx.companion->last().x;
        plot.draw()->AddCircle(plot.to_px(xc, spring_magnet_potential(p, xc)), 8.0f * ctx.ui_scale, companion_color(1.0f), 0, 2.0f);
    }
    if (p.has_bumper()) plot.text(ctx.xI_shown, yr.hi, " bumper", pal.bumper, ImVec2(0, -0.2f));
    // A plain click puts the cart at x there, at rest.
    const double mx = plot.x_at(ImGui::GetIO().MousePos.x);
    if (plot.hovered() && !plot.dragging())
        ImGui::SetTooltip("x = %+.2f mm, V = %.2f mJ\nclick to start from here at rest", mx * 1e3,
                          spring_magnet_potential(p, mx) * 1e3);
    act.set_state = delayed_click(click_, plot.hovered(), plot.clicked(), mx, 0.0, ctx.now);
    plot.end();
    return act;
}

}  // namespace impactlab::gui
