// The scan's PNG: one map per measure, each cell painted as the rectangle it stands for (one colour per
// class), a legend per map placed in a margin kept free to the right of the plane.
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

// A map: the panel (axes, the legend's entries) and every cell's colour, painted after rendering.
struct MapLayer {
    plot::Panel panel;
    std::vector<int> cell_class;   // per cell (x fastest); -1: not drawn
    std::vector<plot::Color> colors;
};

// Half a grid step along an axis: a cell reaches that far either side of its point.
double half_step(const ScanAxis& a) { return a.n > 1 ? 0.5 * (a.hi - a.lo) / (a.n - 1) : 0.5; }

MapLayer map_panel(const ScanSpec& spec, const std::vector<std::vector<ScanPoint>>& rows, const std::string& title,
                   const std::vector<ClassDef>& classes, const std::function<int(const ScanPoint&)>& classify) {
    MapLayer layer;
    plot::Panel& panel = layer.panel;
    panel.title = title;
    auto axis_label = [](const ScanAxis& a) {
        return a.param == ScanParam::Omega ? std::string("ω [rad/s]")
               : a.param == ScanParam::XI  ? std::string("x_I [m]")
                                           : std::string("m0e [kg m]");
    };
    panel.xlabel = axis_label(spec.x);
    panel.ylabel = axis_label(spec.y);
    panel.grid = false;
    // Legend entries only (a non-finite point draws nothing); the cells are painted into the image.
    std::vector<plot::Series> series(classes.size());
    for (std::size_t c = 0; c < classes.size(); ++c) {
        series[c].kind = plot::Series::Kind::Points;
        series[c].color = classes[c].color;
        series[c].size = 5.0f;
        series[c].label = classes[c].label;
        series[c].x.push_back(std::nan(""));
        series[c].y.push_back(std::nan(""));
        layer.colors.push_back(classes[c].color);
    }
    for (int j = 0; j < spec.y.n; ++j)
        for (int i = 0; i < spec.x.n; ++i)
            layer.cell_class.push_back(classify(rows[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)]));
    panel.series = std::move(series);
    // The plane, then a free margin for the legend.
    const double hx = half_step(spec.x), hy = half_step(spec.y);
    panel.xmin = spec.x.lo - hx;
    panel.xmax = spec.x.hi + hx + 0.32 * (spec.x.hi - spec.x.lo + 2 * hx);
    panel.ymin = spec.y.lo - hy;
    panel.ymax = spec.y.hi + hy;
    panel.legend = plot::LegendPlace::UpperRight;
    return layer;
}

MapLayer period_layer(const ScanSpec& spec, const std::vector<std::vector<ScanPoint>>& rows) {
    const std::vector<ClassDef> cls{{"period 1", {31, 119, 180}},  {"period 2", {44, 160, 44}},
                                    {"period 3", {255, 127, 14}},  {"period 4", {148, 103, 189}},
                                    {"period 5-16", {140, 86, 75}}, {"chaos (> 16)", {214, 39, 40}},
                                    {"not settled", {150, 150, 150}}};
    return map_panel(spec, rows, "period of the section points", cls, [](const ScanPoint& p) {
        if (p.period == kNotSettled) return 6;
        if (p.period == 0) return 5;
        if (p.period <= 4) return static_cast<int>(p.period) - 1;
        return 4;
    });
}

MapLayer lyapunov_layer(const ScanSpec& spec, const std::vector<std::vector<ScanPoint>>& rows) {
    const std::vector<ClassDef> cls{{"λ < -1 1/s", {8, 48, 107}},     {"-1 ≤ λ < -0.1", {66, 146, 198}},
                                    {"-0.1 ≤ λ < 0.02", {198, 219, 239}}, {"0.02 ≤ λ < 0.5 (chaos)", {252, 146, 114}},
                                    {"λ ≥ 0.5 (chaos)", {203, 24, 29}}};
    return map_panel(spec, rows, "largest Lyapunov exponent", cls, [](const ScanPoint& p) {
        if (!std::isfinite(p.lyapunov)) return -1;
        return p.lyapunov < -1 ? 0 : p.lyapunov < -0.1 ? 1 : p.lyapunov < 0.02 ? 2
               : p.lyapunov < 0.5 ? 3 : 4;
    });
}

MapLayer impacts_layer(const ScanSpec& spec, const std::vector<std::vector<ScanPoint>>& rows) {
    const std::vector<ClassDef> cls{{"no impact", {220, 220, 220}}, {"< 1 per period", {254, 217, 118}},
                                    {"1 per period", {253, 141, 60}}, {"1-3 per period", {227, 26, 28}},
                                    {"> 3 per period", {128, 0, 38}}};
    return map_panel(spec, rows, "impacts per forcing period", cls, [](const ScanPoint& p) {
        if (p.impacts == 0) return 0;
        if (p.impacts < 0.99) return 1;
        if (p.impacts <= 1.01) return 2;
        return p.impacts <= 3 ? 3 : 4;
    });
}

MapLayer xrange_layer(const ScanSpec& spec, const std::vector<std::vector<ScanPoint>>& rows) {
    const std::vector<ClassDef> cls{{"left well only", {31, 119, 180}}, {"right well only", {44, 160, 44}},
                                    {"both wells", {255, 127, 14}}, {"reaches the bumper", {214, 39, 40}}};
    // Distances from the bumper need its position per point: xI is an axis or the model's.
    MapLayer l = map_panel(spec, rows, "x range over the recorded periods", cls, [](const ScanPoint& p) {
        if (p.xmin < 0 && p.xmax > 0) return 2;
        return p.xmax <= 0 ? 0 : 1;
    });
    // Points whose x range reaches within 0.1 mm of the bumper (xI an axis): marked over the well classes.
    for (int j = 0; j < spec.y.n; ++j)
        for (int i = 0; i < spec.x.n; ++i) {
            const ScanPoint& p = rows[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)];
            const double xI = spec.x.param == ScanParam::XI ? spec.x.at(i) : spec.y.param == ScanParam::XI ? spec.y.at(j) : NAN;
            if (std::isfinite(xI) && p.xmax >= xI - 1e-4) l.cell_class[static_cast<std::size_t>(j * spec.x.n + i)] = 3;
        }
    return l;
}

// One map per measure asked for, in a fixed order.
std::vector<MapLayer> scan_layers(const ScanSpec& spec, const std::vector<std::vector<ScanPoint>>& rows) {
    std::vector<MapLayer> layers;
    const ScanMeasures& m = spec.measures;
    if (m.period) layers.push_back(period_layer(spec, rows));
    if (m.lyapunov) layers.push_back(lyapunov_layer(spec, rows));
    if (m.impacts) layers.push_back(impacts_layer(spec, rows));
    if (m.xrange) layers.push_back(xrange_layer(spec, rows));
    return layers;
}

// Each cell is the rectangle half a grid step either side of its point, clipped to the plot area.
void paint_cells(plot::Image& img, const std::vector<plot::Mapping>& maps, const ScanSpec& spec, const std::vector<MapLayer>& layers) {
    const double hx = half_step(spec.x), hy = half_step(spec.y);
    for (std::size_t k = 0; k < layers.size(); ++k) {
        const plot::Mapping& map = maps[k];
        for (int j = 0; j < spec.y.n; ++j)
            for (int i = 0; i < spec.x.n; ++i) {
                const int c = layers[k].cell_class[static_cast<std::size_t>(j * spec.x.n + i)];
                if (c < 0) continue;
                const plot::Color col = layers[k].colors[static_cast<std::size_t>(c)];
                const int c0 = std::max(map.left, static_cast<int>(std::lround(map.px(spec.x.at(i) - hx))));
                const int c1 = std::min(map.right, static_cast<int>(std::lround(map.px(spec.x.at(i) + hx))));
                const int r0 = std::max(map.top, static_cast<int>(std::lround(map.py(spec.y.at(j) + hy))));
                const int r1 = std::min(map.bottom, static_cast<int>(std::lround(map.py(spec.y.at(j) - hy))));
                for (int r = r0; r < r1; ++r)
                    for (int cc = c0; cc < c1; ++cc) {
                        std::uint8_t* px = &img.rgba[(static_cast<std::size_t>(r) * static_cast<std::size_t>(img.width) +
                                                      static_cast<std::size_t>(cc)) * 4];
                        px[0] = col.r;
                        px[1] = col.g;
                        px[2] = col.b;
                        px[3] = 255;
                    }
            }
    }
}

// The curves over the cells: 3 x 3 black dots every half pixel along each segment, clipped to the plane.
void draw_curves(plot::Image& img, const std::vector<plot::Mapping>& maps, const ScanSpec& spec, std::size_t nlayers,
                 const std::vector<ScanCurve>& curves) {
    const double hx = half_step(spec.x);
    for (std::size_t k = 0; k < nlayers; ++k) {
        const plot::Mapping& map = maps[k];
        const double x_end = spec.x.hi + hx;   // not into the legend's margin
        for (const ScanCurve& c : curves) {
            double dash_pos = 0;   // pixels along the curve so far
            for (std::size_t i = 0; i + 1 < c.x.size() && i + 1 < c.y.size(); ++i) {
                const double x0 = map.px(c.x[i]), y0 = map.py(c.y[i]), x1 = map.px(c.x[i + 1]), y1 = map.py(c.y[i + 1]);
                if (!std::isfinite(x0 + y0 + x1 + y1)) continue;
                const int n = 1 + static_cast<int>(2 * std::hypot(x1 - x0, y1 - y0));
                for (int s = 0; s <= n; ++s) {
                    const double f = static_cast<double>(s) / n;
                    // Dashed: 8 pixels on, 6 off along the curve's length in pixels; dotted: 3 on, 4 off.
                    if (c.dashed && std::fmod(dash_pos + 0.5 * s, 14.0) >= 8.0) continue;
                    if (c.dotted && std::fmod(dash_pos + 0.5 * s, 7.0) >= 3.0) continue;   // 3 on, 4 off
                    const int cx = static_cast<int>(std::lround(x0 + f * (x1 - x0))), cy = static_cast<int>(std::lround(y0 + f * (y1 - y0)));
                    for (int r = cy - 1; r <= cy + 1; ++r)
                        for (int cc = cx - 1; cc <= cx + 1; ++cc) {
                            if (r < map.top || r >= map.bottom || cc < map.left || cc >= std::min(map.right, static_cast<int>(map.px(x_end)))) continue;
                            std::uint8_t* px = &img.rgba[(static_cast<std::size_t>(r) * static_cast<std::size_t>(img.width) +
                                                          static_cast<std::size_t>(cc)) * 4];
                            px[0] = px[1] = px[2] = 0;
                            px[3] = 255;
                        }
                }
                dash_pos += 0.5 * n;
            }
        }
    }
}

}  // namespace

void save_scan_png(const ScanSpec& spec, const std::vector<std::vector<ScanPoint>>& rows, const std::string& model,
                   const std::string& path, const std::vector<ScanCurve>& curves) {
    plot::Figure fig;
    fig.width = 1400;
    fig.panel_height = 520;
    fig.title = model + ": " + spec.x.name() + " x " + spec.y.name() + " plane, " + std::to_string(spec.x.n) + " x " +
                std::to_string(spec.y.n) + " points, " + (spec.start == ScanStart::Continue ? "continued along " : "each from rest, ") +
                (spec.start == ScanStart::Continue ? spec.x.name() : "");
    std::vector<MapLayer> layers = scan_layers(spec, rows);
    for (auto& l : layers) {
        for (const ScanCurve& c : curves) {   // a legend entry; the curve itself is drawn over the cells below
            plot::Series sr;
            sr.kind = plot::Series::Kind::Line;
            sr.color = {0, 0, 0};
            sr.size = 2.0f;
            sr.label = c.label;
            sr.x.push_back(std::nan(""));
            sr.y.push_back(std::nan(""));
            l.panel.series.push_back(std::move(sr));
        }
        fig.panels.push_back(l.panel);
    }
    plot::Image img = plot::render(fig);
    const std::vector<plot::Mapping> maps = plot::layout(fig);
    paint_cells(img, maps, spec, layers);
    draw_curves(img, maps, spec, layers.size(), curves);
    plot::save_png(img, path);
}

}  // namespace impactlab
