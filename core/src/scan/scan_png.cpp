// The scan's PNG: one map per measure, cells drawn as dots of one colour per class, a legend per map
// placed in a margin kept free to the right of the plane.
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "impactlab/plot.hpp"
#include "impactlab/scan.hpp"

namespace impactlab {

namespace {

struct ClassDef {
    std::string label;
    plot::Color color;
};

plot::Panel map_panel(const ScanSpec& spec, const std::vector<std::vector<ScanPoint>>& rows, const std::string& title,
                      const std::vector<ClassDef>& classes, const std::function<int(const ScanPoint&)>& classify,
                      float dot) {
    plot::Panel panel;
    panel.title = title;
    auto axis_label = [](const ScanAxis& a) {
        return a.param == ScanParam::Omega ? std::string("ω [rad/s]")
               : a.param == ScanParam::XI  ? std::string("x_I [m]")
                                           : std::string("m0e [kg m]");
    };
    panel.xlabel = axis_label(spec.x);
    panel.ylabel = axis_label(spec.y);
    panel.grid = false;
    std::vector<plot::Series> series(classes.size());
    for (std::size_t c = 0; c < classes.size(); ++c) {
        series[c].kind = plot::Series::Kind::Points;
        series[c].color = classes[c].color;
        series[c].size = dot;
        series[c].label = classes[c].label;
    }
    for (int j = 0; j < spec.y.n; ++j)
        for (int i = 0; i < spec.x.n; ++i) {
            const int c = classify(rows[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)]);
            if (c < 0) continue;
            series[static_cast<std::size_t>(c)].x.push_back(spec.x.at(i));
            series[static_cast<std::size_t>(c)].y.push_back(spec.y.at(j));
        }
    for (auto& s : series)
        if (s.x.empty()) {   // keep the legend entry, draw nothing
            s.x.push_back(std::nan(""));
            s.y.push_back(std::nan(""));
        }
    panel.series = std::move(series);
    // The plane, then a free margin for the legend.
    const double hx = spec.x.n > 1 ? 0.5 * (spec.x.hi - spec.x.lo) / (spec.x.n - 1) : 0.5;
    const double hy = spec.y.n > 1 ? 0.5 * (spec.y.hi - spec.y.lo) / (spec.y.n - 1) : 0.5;
    panel.xmin = spec.x.lo - hx;
    panel.xmax = spec.x.hi + hx + 0.32 * (spec.x.hi - spec.x.lo + 2 * hx);
    panel.ymin = spec.y.lo - hy;
    panel.ymax = spec.y.hi + hy;
    panel.legend = plot::LegendPlace::UpperRight;
    return panel;
}

}  // namespace

void save_scan_png(const ScanSpec& spec, const std::vector<std::vector<ScanPoint>>& rows, const std::string& model,
                   const std::string& path) {
    plot::Figure fig;
    fig.width = 1400;
    fig.panel_height = 520;
    fig.title = model + ": " + spec.x.name() + " x " + spec.y.name() + " plane, " + std::to_string(spec.x.n) + " x " +
                std::to_string(spec.y.n) + " points, " + (spec.start == ScanStart::Continue ? "continued along " : "each from rest, ") +
                (spec.start == ScanStart::Continue ? spec.x.name() : "");
    // A dot a little wider than a cell (the plot area is about 75 % of the width, 80 % of the height).
    const float dot = std::max(0.6f, 0.62f * std::max(0.75f * 0.77f * fig.width / static_cast<float>(spec.x.n),
                                                       0.8f * fig.panel_height / static_cast<float>(spec.y.n)));
    const ScanMeasures& m = spec.measures;
    if (m.period) {
        const std::vector<ClassDef> cls{{"period 1", {31, 119, 180}},  {"period 2", {44, 160, 44}},
                                        {"period 3", {255, 127, 14}},  {"period 4", {148, 103, 189}},
                                        {"period 5-16", {140, 86, 75}}, {"chaos (> 16)", {214, 39, 40}}};
        fig.panels.push_back(map_panel(spec, rows, "period of the section points", cls,
                                       [](const ScanPoint& p) {
                                           if (p.period == 0) return 5;
                                           if (p.period <= 4) return static_cast<int>(p.period) - 1;
                                           return 4;
                                       },
                                       dot));
    }
    if (m.lyapunov) {
        const std::vector<ClassDef> cls{{"λ < -1 1/s", {8, 48, 107}},     {"-1 ≤ λ < -0.1", {66, 146, 198}},
                                        {"-0.1 ≤ λ < 0.02", {198, 219, 239}}, {"0.02 ≤ λ < 0.5 (chaos)", {252, 146, 114}},
                                        {"λ ≥ 0.5 (chaos)", {203, 24, 29}}};
        fig.panels.push_back(map_panel(spec, rows, "largest Lyapunov exponent", cls,
                                       [](const ScanPoint& p) {
                                           if (!std::isfinite(p.lyapunov)) return -1;
                                           return p.lyapunov < -1 ? 0 : p.lyapunov < -0.1 ? 1 : p.lyapunov < 0.02 ? 2
                                                  : p.lyapunov < 0.5 ? 3 : 4;
                                       },
                                       dot));
    }
    if (m.impacts) {
        const std::vector<ClassDef> cls{{"no impact", {220, 220, 220}}, {"< 1 per period", {254, 217, 118}},
                                        {"1 per period", {253, 141, 60}}, {"1-3 per period", {227, 26, 28}},
                                        {"> 3 per period", {128, 0, 38}}};
        fig.panels.push_back(map_panel(spec, rows, "impacts per forcing period", cls,
                                       [](const ScanPoint& p) {
                                           if (p.impacts == 0) return 0;
                                           if (p.impacts < 0.99) return 1;
                                           if (p.impacts <= 1.01) return 2;
                                           return p.impacts <= 3 ? 3 : 4;
                                       },
                                       dot));
    }
    if (m.xrange) {
        const std::vector<ClassDef> cls{{"left well only", {31, 119, 180}}, {"right well only", {44, 160, 44}},
                                        {"both wells", {255, 127, 14}}, {"reaches the bumper", {214, 39, 40}}};
        // Distances from the bumper need its position per point: xI is an axis or the model's.
        fig.panels.push_back(map_panel(spec, rows, "x range over the recorded periods", cls,
                                       [](const ScanPoint& p) {
                                           if (p.xmin < 0 && p.xmax > 0) return 2;
                                           return p.xmax <= 0 ? 0 : 1;
                                       },
                                       dot));
        // Points whose x range reaches within 0.1 mm of the bumper: marked over the well classes.
        plot::Series& hit = fig.panels.back().series.back();
        hit.x.clear();
        hit.y.clear();
        for (int j = 0; j < spec.y.n; ++j)
            for (int i = 0; i < spec.x.n; ++i) {
                const ScanPoint& p = rows[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)];
                const double xI = spec.x.param == ScanParam::XI ? spec.x.at(i) : spec.y.param == ScanParam::XI ? spec.y.at(j) : NAN;
                if (std::isfinite(xI) && p.xmax >= xI - 1e-4) {
                    hit.x.push_back(spec.x.at(i));
                    hit.y.push_back(spec.y.at(j));
                }
            }
        if (hit.x.empty()) {
            hit.x.push_back(std::nan(""));
            hit.y.push_back(std::nan(""));
        }
    }
    plot::save_png(fig, path);
}

}  // namespace impactlab
