// The time strip: one or two traces (x by default; v, E, the bumper force, the drive) over the last seconds
// with the section points (and the bumper on x), and beside them, with a companion cart, their separation
// log10 |dx| since the restart.
#include "strip_panel.hpp"
#include "views/strip_keys.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "render/plot2d.hpp"
#include "render/theme.hpp"

namespace impactlab::gui {

namespace {
struct XY {
    double x, y;
};

struct QuantityInfo {
    const char* key;
    const char* label;       // the y axis
    const char* short_label; // where that is longer than the plot is high
    const char* menu;        // the right-click menu
    double scale;            // SI -> the axis's unit
    double min_span;         // [SI] the smallest y span the auto-fit shows
};
constexpr QuantityInfo kQuantities[kStripQuantities] = {
    {"x", "x [mm]", "x [mm]", "x: displacement", 1e3, 0.004},
    {"v", "v [m/s]", "v [m/s]", "v: velocity", 1.0, 0.04},
    {"E", "E [mJ]", "E [mJ]", "E: mechanical energy", 1e3, 1e-3},
    {"F", "F_I [N]", "F_I [N]", "F_I: bumper force", 1.0, 1.0},
    {"drive", "m0e ω² cos φ [N]", "drive [N]", "drive: the unbalance's force m0e ω² cos φ", 1.0, 0.1},
};
const QuantityInfo& info(StripQuantity q) { return kQuantities[static_cast<int>(q)]; }
// The flag and the session files read strip_keys.hpp's list: the same keys in the same order.
constexpr bool keys_match() {
    for (int i = 0; i < kStripQuantities; ++i)
        if (std::string_view(kQuantities[i].key) != kStripKeys[i]) return false;
    return std::size(kStripKeys) == kStripQuantities;
}
static_assert(keys_match(), "strip_keys.hpp and kQuantities disagree");

// The quantity of one record (a sample or a section point; m0e for the drive).
double value_of(StripQuantity q, const SimMsg& m, double m0e) {
    switch (q) {
        case StripQuantity::X: return m.x;
        case StripQuantity::V: return m.v;
        case StripQuantity::Energy: return m.energy;
        case StripQuantity::Force: return m.force;
        case StripQuantity::Drive: return m0e * m.omega * m.omega * std::cos(m.phi);
    }
    return 0.0;
}

}  // namespace

const char* strip_key(StripQuantity q) { return info(q).key; }

std::optional<StripQuantity> strip_from_key(const std::string& key) {
    for (int i = 0; i < kStripQuantities; ++i)
        if (key == kQuantities[i].key) return static_cast<StripQuantity>(i);
    return std::nullopt;
}

void StripPanel::set_traces(StripQuantity first, std::optional<StripQuantity> second) {
    if (traces_[0].q != first) traces_[0] = Trace{first, {}, {}};
    second_ = second.has_value();
    if (second && traces_[1].q != *second) traces_[1] = Trace{*second, {}, {}};
}

ViewAction StripPanel::draw(const ViewContext& ctx) {
    const History<SimMsg>& tr = *ctx.traj;
    ViewAction act;
    const std::size_t n = tr.size();
    const double t_now = n ? tr.back().t : 0.0;
    const double window = ctx.bench_window && n ? std::max(1e-3, t_now - tr[n > ctx.bench_window ? n - ctx.bench_window : 0].t)
                                             : ctx.strip_window;
    // Scrolls once the history covers the window; before that the axis starts at the first sample.
    const double t_from = n ? std::min(std::max(t_now - window, tr[0].t), t_now - 0.5) : t_now - window;
    const std::size_t first = tr.lower_bound(t_from, [](const SimMsg& m) { return m.t; });
    // With a companion cart, its separation |dx| on a log scale takes the right part of the tile.
    const bool comp = ctx.companion_mode != CompanionMode::Off;
    ImVec2 size = ImGui::GetContentRegionAvail();
    const float sep_w = comp ? std::round(size.x * 0.3f) : 0.0f;
    size.x -= comp ? sep_w + ImGui::GetStyle().ItemSpacing.x : 0.0f;
    const ImVec2 origin = ImGui::GetCursorPos();
    if (second_) {   // one above the other, on the same time axis
        const float gap = ImGui::GetStyle().ItemSpacing.y;
        const ImVec2 half(size.x, std::floor(0.5f * (size.y - gap)));
        draw_trace(ctx, traces_[0], "##strip", half, t_from, t_now, first);
        draw_trace(ctx, traces_[1], "##strip2", ImVec2(size.x, size.y - half.y - gap), t_from, t_now, first);
    } else {
        draw_trace(ctx, traces_[0], "##strip", size, t_from, t_now, first);
    }
    draw_menu();
    if (comp) {
        ImGui::SetCursorPos(ImVec2(origin.x + size.x + ImGui::GetStyle().ItemSpacing.x, origin.y));
        draw_separation(ctx, ImVec2(sep_w, size.y));
    }
    return act;
}

void StripPanel::draw_trace(const ViewContext& ctx, Trace& trace, const char* id, ImVec2 size, double t_from,
                            double t_now, std::size_t first) {
    // One loop per quantity, without a switch per sample (100k samples a frame in --bench-plot).
    const double m0e = ctx.params->m0e;
    switch (trace.q) {
        case StripQuantity::X: draw_trace_with(ctx, trace, id, size, t_from, t_now, first, [](const SimMsg& m) { return m.x; }); break;
        case StripQuantity::V: draw_trace_with(ctx, trace, id, size, t_from, t_now, first, [](const SimMsg& m) { return m.v; }); break;
        case StripQuantity::Energy:
            draw_trace_with(ctx, trace, id, size, t_from, t_now, first, [](const SimMsg& m) { return m.energy; });
            break;
        case StripQuantity::Force:
            draw_trace_with(ctx, trace, id, size, t_from, t_now, first, [](const SimMsg& m) { return m.force; });
            break;
        case StripQuantity::Drive:
            draw_trace_with(ctx, trace, id, size, t_from, t_now, first,
                            [m0e](const SimMsg& m) { return value_of(StripQuantity::Drive, m, m0e); });
            break;
    }
}

template <class Key>
void StripPanel::draw_trace_with(const ViewContext& ctx, Trace& trace, const char* id, ImVec2 size, double t_from,
                                 double t_now, std::size_t first, Key key) {
    const History<SimMsg>& tr = *ctx.traj;
    const History<SimMsg>& secs = *ctx.sections;
    const Params& p = *ctx.params;
    const Palette& pal = palette();
    const std::size_t n = tr.size();
    const StripQuantity q = trace.q;
    const auto e = trace.extent.update(tr, first, key);
    double lo = e.lo, hi = e.hi;
    if (first >= n) lo = hi = key(ctx.last);
    trace.y.track({lo, hi}, 0.08, info(q).min_span, ctx.frame_dt);
    Plot plot;
    Axes ax;
    ax.x_label = "t [s]";
    ax.y_label = info(q).label;
    ax.y_label_short = info(q).short_label;
    ax.y_scale = info(q).scale;
    if (!plot.begin(id, size, {t_from, t_now}, trace.y.cur, ax)) return;
    if (q == StripQuantity::X && p.has_bumper()) plot.hline(ctx.xI_shown, pal.bumper, 1.5f, true);
    plot.hline(0.0, pal.grid, 1.0f);
    if (ctx.companion_mode != CompanionMode::Off) {
        const History<SimMsg>& ct = ctx.companion->traj();
        const std::size_t c0 = ct.lower_bound(t_from, [](const SimMsg& m) { return m.t; });
        plot.series(ct.size() - c0, [&](std::size_t i) { const SimMsg& m = ct[c0 + i]; return XY{m.t, key(m)}; },
                    companion_color(0.75f), 1.5f);
    }
    plot.series(n - first, [&](std::size_t i) { const SimMsg& m = tr[first + i]; return XY{m.t, key(m)}; }, pal.trace, 1.5f);
    const std::size_t s0 = secs.lower_bound(t_from, [](const SimMsg& m) { return m.t; });
    plot.scatter(secs.size() - s0, [&](std::size_t i) { const SimMsg& m = secs[s0 + i]; return XY{m.t, key(m)}; },
                 pal.section, 4.0f);
    if (plot.hovered() && !plot.dragging()) ImGui::SetTooltip("t = %.3f s\nright-click: choose the traces", plot.x_at(ImGui::GetIO().MousePos.x));
    if (plot.hovered() && ImGui::IsMouseClicked(ImGuiMouseButton_Right)) ImGui::OpenPopup("##strip_menu");
    plot.end();
}

void StripPanel::draw_menu() {
    if (!ImGui::BeginPopup("##strip_menu")) return;
    ImGui::TextDisabled("trace");
    for (int i = 0; i < kStripQuantities; ++i) {
        const auto q = static_cast<StripQuantity>(i);
        if (ImGui::MenuItem(kQuantities[i].menu, nullptr, traces_[0].q == q)) set_traces(q, second());
    }
    ImGui::Separator();
    ImGui::TextDisabled("second trace, below it");
    if (ImGui::MenuItem("none", nullptr, !second_)) set_traces(first(), std::nullopt);
    for (int i = 0; i < kStripQuantities; ++i) {
        const auto q = static_cast<StripQuantity>(i);
        if (ImGui::MenuItem((std::string(kQuantities[i].menu) + "##2").c_str(), nullptr, second_ && traces_[1].q == q))
            set_traces(first(), q);
    }
    ImGui::EndPopup();
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
