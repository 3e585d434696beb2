// The x(t) strip: the displacement over the last seconds with the section points and the bumper, and
// beside it, with a companion cart, their separation log10 |dx| since the restart.
#include "views/strip_panel.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "plot2d.hpp"
#include "theme.hpp"

namespace impactlab::gui {

namespace {
struct XY {
    double x, y;
};
}  // namespace

ViewAction StripPanel::draw(const ViewContext& ctx) {
    const History<SimMsg>& tr = *ctx.traj;
    const History<SimMsg>& secs = *ctx.sections;
    const Params& p = *ctx.params;
    ViewAction act;
    const Palette& pal = palette();
    const std::size_t n = tr.size();
    const double t_now = n ? tr.back().t : 0.0;
    const double window = ctx.bench_window && n ? std::max(1e-3, t_now - tr[n > ctx.bench_window ? n - ctx.bench_window : 0].t)
                                             : ctx.strip_window;
    // Scrolls once the history covers the window; before that the axis starts at the first sample.
    const double t_from = n ? std::min(std::max(t_now - window, tr[0].t), t_now - 0.5) : t_now - window;
    const std::size_t first = tr.lower_bound(t_from, [](const SimMsg& m) { return m.t; });
    const auto xe = x_extent_.update(tr, first, [](const SimMsg& m) { return m.x; });
    double lo = xe.lo, hi = xe.hi;
    if (first >= n) lo = hi = ctx.last.x;
    y_.track({lo, hi}, 0.08, 0.004, ctx.frame_dt);
    Plot plot;
    Axes ax;
    ax.x_label = "t [s]";
    ax.y_label = "x [mm]";
    ax.y_scale = 1e3;
    // With a companion cart, its separation |dx| on a log scale takes the right part of the tile.
    const bool comp = ctx.companion_mode != CompanionMode::Off;
    ImVec2 size = ImGui::GetContentRegionAvail();
    const float sep_w = comp ? std::round(size.x * 0.3f) : 0.0f;
    size.x -= comp ? sep_w + ImGui::GetStyle().ItemSpacing.x : 0.0f;
    if (!plot.begin("##strip", size, {t_from, t_now}, y_.cur, ax)) return act;
    if (p.has_bumper()) plot.hline(ctx.xI_shown, pal.bumper, 1.5f, true);
    plot.hline(0.0, pal.grid, 1.0f);
    if (comp) {
        const History<SimMsg>& ct = ctx.companion->traj();
        const std::size_t c0 = ct.lower_bound(t_from, [](const SimMsg& m) { return m.t; });
        plot.series(ct.size() - c0, [&](std::size_t i) { const SimMsg& m = ct[c0 + i]; return XY{m.t, m.x}; },
                    companion_color(0.75f), 1.5f);
    }
    plot.series(n - first, [&](std::size_t i) { const SimMsg& m = tr[first + i]; return XY{m.t, m.x}; }, pal.trace, 1.5f);
    const std::size_t s0 = secs.lower_bound(t_from, [](const SimMsg& m) { return m.t; });
    plot.scatter(secs.size() - s0, [&](std::size_t i) { const SimMsg& m = secs[s0 + i]; return XY{m.t, m.x}; },
                 pal.section, 4.0f);
    plot.end();
    if (comp) {
        ImGui::SameLine();
        draw_separation(ctx, ImVec2(sep_w, size.y));
    }
    return act;
}

void StripPanel::draw_separation(const ViewContext& ctx, ImVec2 size) {
    const Palette& pal = palette();
    const History<Separation>& sep = ctx.companion->separation();
    const double t_now = sep.empty() ? ctx.last.t : sep.back().t;
    // From the restart (the growth from 1 um is the point), the last two minutes at most.
    const double t_from = sep.empty() ? t_now - ctx.strip_window : std::max(sep[0].t, t_now - 120.0);
    Plot plot;
    Axes ax;
    ax.x_label = "t [s]";
    ax.y_label = "log10 |Δx| [m]";
    if (!plot.begin("##separation", size, {t_from, std::max(t_now, t_from + 0.1)}, {-9.0, -1.0}, ax)) return;
    const std::size_t first = sep.lower_bound(t_from, [](const Separation& s) { return s.t; });
    plot.series(sep.size() - first, [&](std::size_t i) {
        const Separation& s = sep[first + i];
        struct { double x, y; } p{s.t, std::log10(std::max(s.dx, 1e-9))};
        return p;
    }, companion_color(1.0f), 1.5f);
    plot.hline(-6.0, pal.grid, 1.0f, true);
    const char* what = ctx.companion_mode == CompanionMode::Twin ? "twin: |Δx| from 1 µm" : "ghost: |Δx|";
    plot.draw()->AddText(ImVec2(plot.area_min().x + 6, plot.area_min().y + 4), pal.axis_text, what);
    plot.end();
}

}  // namespace impactlab::gui
