// Figure layout and rendering: panels stacked vertically, each a framed plot area with ticks, labels,
// a title and an optional legend.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include <stb_image_write.h>   // libstb exports the implementation: no STB_IMAGE_WRITE_IMPLEMENTATION here

#include "impactlab/atomic_file.hpp"
#include "impactlab/plot.hpp"
#include "plot/canvas.hpp"
#include "plot/font.hpp"

namespace impactlab::plot {
namespace {

using detail::Canvas;
using detail::HAlign;
using detail::Paint;
using detail::Rect;
using detail::VAlign;

constexpr int kMaxDimension = 32768;
constexpr int kMinPlotArea = 16;          // px, either direction
constexpr double kAutoMargin = 0.03;      // of the data range, on each side
constexpr float kMaxMarkSize = 50.0f;     // px

const Color kText{25, 25, 25, 255};
const Color kTickText{45, 45, 45, 255};
const Color kFrame{40, 40, 40, 255};
const Color kGrid{226, 226, 226, 255};
const Color kLegendBorder{190, 190, 190, 255};
const Color kWhite{255, 255, 255, 255};

// Pixel sizes of text and spacing, after the figure's font_scale.
struct Style {
    int title_px, panel_title_px, label_px, tick_px, legend_px;
    int pad, gap, tick_len;
    int title_lh, panel_title_lh, label_lh, tick_lh;   // line heights (ascent - descent)
};

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

int line_height(int px) {
    const auto& g = detail::glyphs(px);
    return static_cast<int>(std::ceil(g.ascent() - g.descent()));
}

Style make_style(const Figure& fig) {
    const float s = fig.font_scale;
    if (!(s > 0.0f) || !std::isfinite(s) || s > 20.0f)
        throw std::invalid_argument("impactlab::plot: font_scale must be in (0, 20], got " + num(s));
    auto scaled = [s](double v, int lo) { return std::max(lo, static_cast<int>(std::lround(v * s))); };
    Style st{};
    st.title_px = scaled(20, 6);
    st.panel_title_px = scaled(15, 6);
    st.label_px = scaled(14, 6);
    st.tick_px = scaled(12, 6);
    st.legend_px = scaled(12, 6);
    st.pad = scaled(8, 3);
    st.gap = scaled(5, 2);
    st.tick_len = scaled(5, 3);
    st.title_lh = line_height(st.title_px);
    st.panel_title_lh = line_height(st.panel_title_px);
    st.label_lh = line_height(st.label_px);
    st.tick_lh = line_height(st.tick_px);
    return st;
}

int title_height(const Figure& fig, const Style& st) {
    return fig.title.empty() ? 0 : st.title_lh + 2 * st.pad;
}

struct AxisTicks {
    std::vector<double> values;
    std::vector<std::string> labels;
    std::vector<float> widths;
    float max_width = 0;
};

// As many ticks over [lo, hi] as fit on an axis `length_px` long without their labels touching.
// horizontal: labels sit side by side (their widths count); otherwise stacked (their height counts).
// Starts from a generous count and lowers it until the labels keep a gap.
AxisTicks make_ticks(double lo, double hi, double length_px, bool horizontal, const Style& st) {
    const double per_tick = horizontal ? 7.0 * st.tick_px : 2.6 * st.tick_lh;
    int n = std::max(2, static_cast<int>(length_px / per_tick) + 1);
    AxisTicks t;
    for (;;) {
        t.values = nice_ticks(lo, hi, n);
        t.labels = format_ticks(t.values, nice_step(lo, hi, n));
        t.widths.clear();
        t.max_width = 0;
        for (const auto& l : t.labels) {
            t.widths.push_back(detail::text_width(l, st.tick_px));
            t.max_width = std::max(t.max_width, t.widths.back());
        }
        if (t.values.size() < 2) break;
        const double spacing = (t.values[1] - t.values[0]) / (hi - lo) * length_px;
        const double needed = horizontal ? t.max_width + 2.5 * st.gap : st.tick_lh + st.gap;
        if (spacing >= needed) break;
        n = static_cast<int>(t.values.size()) - 1;
        if (n < 2) {   // a single tick (in the middle) always fits
            n = 1;
            if (t.values.size() == 1) break;
        }
    }
    return t;
}

struct Extent {
    double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
    bool any() const { return lo <= hi; }
};

void data_extent(const Panel& panel, std::size_t panel_index, Extent& ex, Extent& ey) {
    for (std::size_t s = 0; s < panel.series.size(); ++s) {
        const Series& series = panel.series[s];
        if (series.x.size() != series.y.size())
            throw std::invalid_argument("impactlab::plot: panel " + std::to_string(panel_index) + " series " +
                                        std::to_string(s) + ": x has " + std::to_string(series.x.size()) +
                                        " values but y has " + std::to_string(series.y.size()));
        for (std::size_t i = 0; i < series.x.size(); ++i) {
            const double x = series.x[i], y = series.y[i];
            if (!std::isfinite(x) || !std::isfinite(y)) continue;
            ex.lo = std::min(ex.lo, x);
            ex.hi = std::max(ex.hi, x);
            ey.lo = std::min(ey.lo, y);
            ey.hi = std::max(ey.hi, y);
        }
    }
}

// Final axis range from the user's limits (non-finite = automatic) and the data.
void resolve_range(double user_lo, double user_hi, const Extent& data, const char* axis, std::size_t panel_index,
                   double& lo, double& hi) {
    const bool fix_lo = std::isfinite(user_lo), fix_hi = std::isfinite(user_hi);
    if (fix_lo && fix_hi && user_lo > user_hi)
        throw std::invalid_argument("impactlab::plot: panel " + std::to_string(panel_index) + ": " + axis + "min (" +
                                    num(user_lo) + ") > " + axis + "max (" + num(user_hi) + ")");
    double dlo = 0.0, dhi = 1.0;
    if (data.any()) {
        dlo = data.lo;
        dhi = data.hi;
        if (dlo == dhi) {
            const double p = dlo == 0.0 ? 0.5 : std::abs(dlo) * 0.05;
            dlo -= p;
            dhi += p;
        }
        const double m = kAutoMargin * (dhi / 2 - dlo / 2) * 2;   // halved first: +-1e308 cannot overflow
        if (std::isfinite(dlo - m) && std::isfinite(dhi + m)) {
            dlo -= m;
            dhi += m;
        }
    }
    lo = fix_lo ? user_lo : dlo;
    hi = fix_hi ? user_hi : dhi;
    const double span = dhi - dlo;
    if (!(hi > lo)) {
        if (fix_lo && fix_hi) {   // equal limits: pad them
            const double p = lo == 0.0 ? 0.5 : std::abs(lo) * 0.05;
            lo -= p;
            hi += p;
        } else if (fix_lo) {
            hi = lo + (std::isfinite(span) && span > 0 ? span : 1.0);
        } else {
            lo = hi - (std::isfinite(span) && span > 0 ? span : 1.0);
        }
    }
    if (!std::isfinite(hi - lo)) {   // a span beyond the doubles (data near +-1.8e308)
        lo = std::max(lo, -8e307);
        hi = std::min(hi, 8e307);
    }
    if (!(hi > lo)) {   // a span below the double resolution
        const double c = std::clamp(lo / 2 + hi / 2, -1e300, 1e300);
        const double p = std::max(std::abs(c) * 1e-6, 1e-300);
        lo = c - p;
        hi = c + p;
    }
}

struct PanelLayout {
    Mapping m;
    AxisTicks xt, yt;
    int band_top = 0;
};

struct FigureLayout {
    Style st;
    int width = 0, height = 0, title_h = 0;
    std::vector<PanelLayout> panels;
};

FigureLayout compute_layout(const Figure& fig) {
    if (fig.panels.empty()) throw std::invalid_argument("impactlab::plot: the figure has no panels");
    if (fig.width <= 0 || fig.panel_height <= 0 || fig.width > kMaxDimension || fig.panel_height > kMaxDimension)
        throw std::invalid_argument("impactlab::plot: figure width " + std::to_string(fig.width) +
                                    " and panel_height " + std::to_string(fig.panel_height) +
                                    " must be in 1.." + std::to_string(kMaxDimension));
    FigureLayout L;
    L.st = make_style(fig);
    const Style& st = L.st;
    L.width = fig.width;
    L.title_h = title_height(fig, st);
    const long long height = L.title_h + static_cast<long long>(fig.panel_height) * static_cast<long long>(fig.panels.size());
    if (height > kMaxDimension)
        throw std::invalid_argument("impactlab::plot: figure height " + std::to_string(height) + " exceeds " +
                                    std::to_string(kMaxDimension) + " px");
    L.height = static_cast<int>(height);

    auto too_small = [&](std::size_t p, int w, int h) {
        return std::invalid_argument("impactlab::plot: figure too small: panel " + std::to_string(p) +
                                     " would get a plot area of " + std::to_string(w) + "x" + std::to_string(h) +
                                     " px (width " + std::to_string(fig.width) + ", panel_height " +
                                     std::to_string(fig.panel_height) + "; a plot area needs at least " +
                                     std::to_string(kMinPlotArea) + "x" + std::to_string(kMinPlotArea) + ")");
    };

    // Vertical layout, ranges and y ticks (their label widths decide the common left edge).
    int left = 0;
    L.panels.resize(fig.panels.size());
    for (std::size_t p = 0; p < fig.panels.size(); ++p) {
        const Panel& panel = fig.panels[p];
        PanelLayout& pl = L.panels[p];
        Mapping& m = pl.m;
        pl.band_top = L.title_h + static_cast<int>(p) * fig.panel_height;
        m.top = pl.band_top + st.pad + (panel.title.empty() ? st.gap : st.panel_title_lh + st.gap);
        m.bottom = pl.band_top + fig.panel_height - st.pad - (panel.xlabel.empty() ? 0 : st.label_lh + st.gap) -
                   st.tick_lh - st.tick_len - 2;
        if (m.bottom - m.top < kMinPlotArea) throw too_small(p, fig.width, m.bottom - m.top);

        Extent ex, ey;
        data_extent(panel, p, ex, ey);
        resolve_range(panel.xmin, panel.xmax, ex, "x", p, m.xmin, m.xmax);
        resolve_range(panel.ymin, panel.ymax, ey, "y", p, m.ymin, m.ymax);

        pl.yt = make_ticks(m.ymin, m.ymax, m.bottom - m.top, false, st);
        const int need = st.pad + (panel.ylabel.empty() ? 0 : st.label_lh + st.gap) +
                         static_cast<int>(std::ceil(pl.yt.max_width)) + st.gap + st.tick_len;
        left = std::max(left, need);
    }

    // Horizontal layout: x ticks; widen the right margin until the last tick label fits in the image.
    int right_margin = 2 * st.pad;
    for (int attempt = 0; attempt < 3; ++attempt) {
        const int right = fig.width - right_margin;
        if (right - left < kMinPlotArea) throw too_small(0, right - left, L.panels[0].m.bottom - L.panels[0].m.top);
        int needed = right_margin;
        for (auto& pl : L.panels) {
            pl.m.left = left;
            pl.m.right = right;
            pl.xt = make_ticks(pl.m.xmin, pl.m.xmax, right - left, true, st);
            if (!pl.xt.values.empty()) {
                const double x_last = pl.m.px(pl.xt.values.back());
                const double overhang = x_last + pl.xt.widths.back() / 2 + 2 - fig.width;
                if (overhang > 0) needed = std::max(needed, right_margin + static_cast<int>(std::ceil(overhang)));
            }
        }
        if (needed == right_margin) break;
        right_margin = needed;
    }
    return L;
}

int tick_col(const Mapping& m, double v) { return std::clamp(static_cast<int>(std::floor(m.px(v))), m.left, m.right - 1); }
int tick_row(const Mapping& m, double v) { return std::clamp(static_cast<int>(std::floor(m.py(v))), m.top, m.bottom - 1); }

bool usable(double v, double lo, double hi) { return v >= lo && v <= hi; }   // false for NaN

void draw_points(Canvas& cv, const Mapping& m, const Rect& area, const Series& s) {
    const double r = std::isfinite(s.size) ? std::clamp(s.size, 0.0f, kMaxMarkSize) : 1.0;
    const double xlo = m.left - r - 1, xhi = m.right + r + 1, ylo = m.top - r - 1, yhi = m.bottom + r + 1;
    const Paint p = detail::paint(s.color);
    const std::size_t n = s.x.size();
    for (std::size_t i = 0; i < n; ++i) {
        const double fx = m.px(s.x[i]), fy = m.py(s.y[i]);
        if (!usable(fx, xlo, xhi) || !usable(fy, ylo, yhi)) continue;   // NaN, infinite or far outside
        detail::draw_dot(cv, fx, fy, r, area, p);
    }
}

void draw_line(Canvas& cv, detail::Layer& layer, const Mapping& m, const Series& s) {
    const double w = std::isfinite(s.size) ? std::clamp(s.size, 0.1f, kMaxMarkSize) : 1.0;
    const double hw = w / 2;
    const Rect& area = layer.area();
    // Segments are clipped to the plot area grown by the pen, so that off-screen ends stay moderate.
    const double xlo = area.x0 - hw - 2, xhi = area.x1 + hw + 2, ylo = area.y0 - hw - 2, yhi = area.y1 + hw + 2;
    auto plot = [&layer](int x, int y, float c) { layer.plot(x, y, c); };
    double px0 = 0, py0 = 0;
    std::size_t run = 0;   // finite points in the current piece
    auto end_piece = [&]() {
        if (run == 1 && usable(px0, xlo, xhi) && usable(py0, ylo, yhi))   // an isolated point: a round dot
            detail::raster_segment(px0, py0, px0, py0, hw, area, plot);
        run = 0;
    };
    const std::size_t n = s.x.size();
    for (std::size_t i = 0; i < n; ++i) {
        const double fx = m.px(s.x[i]), fy = m.py(s.y[i]);
        if (!std::isfinite(fx) || !std::isfinite(fy)) {   // also for non-finite data
            end_piece();
            continue;
        }
        if (run > 0) {
            double ax = px0, ay = py0, bx = fx, by = fy;
            if (detail::clip_segment(ax, ay, bx, by, xlo, ylo, xhi, yhi) && std::isfinite(ax) && std::isfinite(ay) &&
                std::isfinite(bx) && std::isfinite(by))
                detail::raster_segment(ax, ay, bx, by, hw, area, plot);
        }
        px0 = fx;
        py0 = fy;
        ++run;
    }
    end_piece();
    layer.composite(cv, detail::paint(s.color));
}

void draw_legend(Canvas& cv, const Panel& panel, const Mapping& m, const Style& st) {
    std::vector<const Series*> entries;
    for (const auto& s : panel.series)
        if (!s.label.empty()) entries.push_back(&s);
    if (entries.empty()) return;

    std::vector<detail::TextMask> masks;
    float text_w = 0;
    for (const auto* s : entries) {
        masks.push_back(detail::rasterize(s->label, st.legend_px));
        text_w = std::max(text_w, masks.back().advance);
    }
    const int inner = st.gap + 2;
    const int sample_w = std::max(12, static_cast<int>(std::lround(2.0 * st.legend_px)));
    const int row_h = line_height(st.legend_px) + 3;
    const int box_w = inner + sample_w + st.gap + static_cast<int>(std::ceil(text_w)) + inner;
    const int box_h = 2 * inner + static_cast<int>(entries.size()) * row_h - 3;
    const int inset = 2 * st.gap;

    const Rect corners[4] = {
        {m.right - inset - box_w, m.top + inset, m.right - inset, m.top + inset + box_h},        // upper right
        {m.left + inset, m.top + inset, m.left + inset + box_w, m.top + inset + box_h},          // upper left
        {m.right - inset - box_w, m.bottom - inset - box_h, m.right - inset, m.bottom - inset},  // lower right
        {m.left + inset, m.bottom - inset - box_h, m.left + inset + box_w, m.bottom - inset},    // lower left
    };
    int choice = 0;
    switch (panel.legend) {
        case LegendPlace::UpperRight: choice = 0; break;
        case LegendPlace::UpperLeft: choice = 1; break;
        case LegendPlace::LowerRight: choice = 2; break;
        case LegendPlace::LowerLeft: choice = 3; break;
        case LegendPlace::Auto: {
            // The corner hiding the fewest data points (sampled: at most ~4e5 points looked at).
            std::size_t total = 0;
            for (const auto& s : panel.series) total += s.x.size();
            const std::size_t stride = std::max<std::size_t>(1, total / 400000);
            std::size_t count[4] = {0, 0, 0, 0};
            for (const auto& s : panel.series)
                for (std::size_t i = 0; i < s.x.size(); i += stride) {
                    const double fx = m.px(s.x[i]), fy = m.py(s.y[i]);
                    for (int c = 0; c < 4; ++c)
                        if (fx >= corners[c].x0 && fx < corners[c].x1 && fy >= corners[c].y0 && fy < corners[c].y1)
                            ++count[c];
                }
            for (int c = 1; c < 4; ++c)
                if (count[c] < count[choice]) choice = c;
            break;
        }
    }
    const Rect box = corners[choice];
    const Rect area{m.left, m.top, m.right, m.bottom};
    cv.fill(detail::intersect(box, area), detail::paint(kWhite, 0.88f));
    const Paint border = detail::paint(kLegendBorder);
    cv.fill(detail::intersect({box.x0, box.y0, box.x1, box.y0 + 1}, area), border);
    cv.fill(detail::intersect({box.x0, box.y1 - 1, box.x1, box.y1}, area), border);
    cv.fill(detail::intersect({box.x0, box.y0, box.x0 + 1, box.y1}, area), border);
    cv.fill(detail::intersect({box.x1 - 1, box.y0, box.x1, box.y1}, area), border);

    for (std::size_t k = 0; k < entries.size(); ++k) {
        const Series& s = *entries[k];
        // On a pixel centre, so that a thin sample line is crisp.
        const double yc = box.y0 + inner + static_cast<int>(k) * row_h + (row_h - 3) / 2 + 0.5;
        const double x0 = box.x0 + inner;
        Color c = s.color;
        c.a = 255;   // a faint scatter colour would vanish in the legend
        const Paint p = detail::paint(c);
        const double size = std::isfinite(s.size) ? s.size : 1.0;
        if (s.kind == Series::Kind::Line) {
            const double hw = std::clamp(size, 0.5, 4.0) / 2;
            detail::raster_segment(x0, yc, x0 + sample_w, yc, hw, area,
                                   [&](int x, int y, float cov) { cv.blend_unchecked(x, y, p, cov); });
        } else {
            detail::draw_dot(cv, x0 + sample_w / 2.0, yc, std::clamp(size, 2.5, 6.0), area, p);
        }
        detail::draw_text(cv, masks[k], x0 + sample_w + st.gap, yc, HAlign::Left, VAlign::Middle,
                          detail::paint(kText));
    }
}

void draw_panel(Canvas& cv, const Panel& panel, const PanelLayout& pl, const Style& st) {
    const Mapping& m = pl.m;
    const Rect area{m.left, m.top, m.right, m.bottom};

    // Shaded x-intervals, with anti-aliased edges.
    for (const auto& [a, b] : panel.shade_x) {
        if (std::isnan(a) || std::isnan(b)) continue;
        const double pa = std::clamp(m.px(std::min(a, b)), double(m.left), double(m.right));
        const double pb = std::clamp(m.px(std::max(a, b)), double(m.left), double(m.right));
        const Paint p = detail::paint(panel.shade_color);
        for (int x = static_cast<int>(std::floor(pa)); x < pb && x < m.right; ++x) {
            const float cov = static_cast<float>(std::min<double>(x + 1, pb) - std::max<double>(x, pa));
            if (cov <= 0) continue;
            for (int y = m.top; y < m.bottom; ++y) cv.blend_unchecked(x, y, p, cov);
        }
    }

    // Grid.
    if (panel.grid) {
        const Paint g = detail::paint(kGrid);
        for (double v : pl.xt.values) cv.fill({tick_col(m, v), m.top, tick_col(m, v) + 1, m.bottom}, g);
        for (double v : pl.yt.values) cv.fill({m.left, tick_row(m, v), m.right, tick_row(m, v) + 1}, g);
    }

    // Data.
    detail::Layer layer(area);
    for (const auto& s : panel.series) {
        if (s.kind == Series::Kind::Points)
            draw_points(cv, m, area, s);
        else
            draw_line(cv, layer, m, s);
    }

    // Marker lines.
    for (double v : panel.vlines) {
        const double x = m.px(v);
        if (!usable(x, m.left - 2.0, m.right + 2.0)) continue;
        const Paint p = detail::paint(panel.vline_color);
        detail::raster_segment(x, m.top, x, m.bottom, 0.75, area,
                               [&](int px, int py, float cov) { cv.blend_unchecked(px, py, p, cov); });
    }

    // Frame and ticks.
    const Paint frame = detail::paint(kFrame);
    cv.fill({m.left, m.top, m.right, m.top + 1}, frame);
    cv.fill({m.left, m.bottom - 1, m.right, m.bottom}, frame);
    cv.fill({m.left, m.top, m.left + 1, m.bottom}, frame);
    cv.fill({m.right - 1, m.top, m.right, m.bottom}, frame);
    const Paint tick_text = detail::paint(kTickText);
    for (std::size_t i = 0; i < pl.xt.values.size(); ++i) {
        const int c = tick_col(m, pl.xt.values[i]);
        cv.fill({c, m.bottom, c + 1, m.bottom + st.tick_len}, frame);
        detail::draw_text(cv, detail::rasterize(pl.xt.labels[i], st.tick_px), c + 0.5, m.bottom + st.tick_len + 2,
                          HAlign::Center, VAlign::Top, tick_text);
    }
    for (std::size_t i = 0; i < pl.yt.values.size(); ++i) {
        const int r = tick_row(m, pl.yt.values[i]);
        cv.fill({m.left - st.tick_len, r, m.left, r + 1}, frame);
        detail::draw_text(cv, detail::rasterize(pl.yt.labels[i], st.tick_px), m.left - st.tick_len - st.gap, r + 0.5,
                          HAlign::Right, VAlign::Middle, tick_text);
    }

    // Labels and title.
    const Paint text = detail::paint(kText);
    if (!panel.xlabel.empty())
        detail::draw_text(cv, detail::rasterize(panel.xlabel, st.label_px), (m.left + m.right) / 2.0,
                          m.bottom + st.tick_len + 2 + st.tick_lh + st.gap, HAlign::Center, VAlign::Top, text);
    if (!panel.ylabel.empty())
        detail::draw_text(cv, detail::rasterize(panel.ylabel, st.label_px), st.pad, (m.top + m.bottom) / 2.0,
                          HAlign::Center, VAlign::Top, text, /*rotated=*/true);
    if (!panel.title.empty())
        detail::draw_text(cv, detail::rasterize(panel.title, st.panel_title_px), (m.left + m.right) / 2.0,
                          m.top - st.gap, HAlign::Center, VAlign::Bottom, text);

    draw_legend(cv, panel, m, st);
}

}  // namespace

Size image_size(const Figure& fig) {
    const FigureLayout L = compute_layout(fig);
    return {L.width, L.height};
}

std::vector<Mapping> layout(const Figure& fig) {
    const FigureLayout L = compute_layout(fig);
    std::vector<Mapping> out;
    out.reserve(L.panels.size());
    for (const auto& pl : L.panels) out.push_back(pl.m);
    return out;
}

Image render(const Figure& fig) {
    const FigureLayout L = compute_layout(fig);
    Canvas cv(L.width, L.height);
    if (!fig.title.empty())
        detail::draw_text(cv, detail::rasterize(fig.title, L.st.title_px), L.width / 2.0, L.st.pad, HAlign::Center,
                          VAlign::Top, detail::paint(kText));
    for (std::size_t p = 0; p < fig.panels.size(); ++p) draw_panel(cv, fig.panels[p], L.panels[p], L.st);
    return cv.to_image();
}

void save_png(const Image& image, const std::string& path) {
    if (image.width <= 0 || image.height <= 0 ||
        image.rgba.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 4)
        throw std::invalid_argument("impactlab::plot: " + path + ": image has inconsistent size");
    const std::size_t n = image.rgba.size() / 4;
    bool opaque = true;
    for (std::size_t i = 0; i < n && opaque; ++i) opaque = image.rgba[i * 4 + 3] == 255;
    // Encoded in memory, then written whole by write_file_whole: stb's own file writer leaves its fwrite and
    // fclose unchecked, so a full disk gave an empty PNG and success.
    std::string png;
    const auto append = [](void* ctx, void* data, int size) {
        static_cast<std::string*>(ctx)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
    };
    int ok = 0;
    if (opaque) {   // what render() makes: store RGB, a quarter smaller
        std::vector<std::uint8_t> rgb(n * 3);
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t c = 0; c < 3; ++c) rgb[i * 3 + c] = image.rgba[i * 4 + c];
        ok = stbi_write_png_to_func(append, &png, image.width, image.height, 3, rgb.data(), image.width * 3);
    } else {
        ok = stbi_write_png_to_func(append, &png, image.width, image.height, 4, image.rgba.data(), image.width * 4);
    }
    if (ok == 0) throw std::runtime_error(path + ": cannot encode the PNG");
    write_file_whole(path, png);
}

void save_png(const Figure& fig, const std::string& path) { save_png(render(fig), path); }

}  // namespace impactlab::plot
