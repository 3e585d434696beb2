// Internal: a floating-point RGB canvas with alpha blending, and the primitive rasterisers of the plot
// module (anti-aliased dots, capsule-shaped line segments, rectangles, text masks).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "impactlab/plot.hpp"
#include "impactlab/raster.hpp"
#include "plot/font.hpp"

namespace impactlab::plot::detail {

struct Rect {   // columns [x0, x1), rows [y0, y1)
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool empty() const { return x1 <= x0 || y1 <= y0; }
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
};

inline Rect intersect(const Rect& a, const Rect& b) {
    return {std::max(a.x0, b.x0), std::max(a.y0, b.y0), std::min(a.x1, b.x1), std::min(a.y1, b.y1)};
}

struct Paint {   // colour channels 0..255, opacity 0..1
    float r, g, b, a;
};
inline Paint paint(Color c, float opacity = 1.0f) {
    return {static_cast<float>(c.r), static_cast<float>(c.g), static_cast<float>(c.b),
            static_cast<float>(c.a) / 255.0f * opacity};
}

class Canvas {
public:
    Canvas(int width, int height);   // white
    int width() const { return w_; }
    int height() const { return h_; }
    Rect bounds() const { return {0, 0, w_, h_}; }

    // dst = dst + (colour - dst) * paint.a * coverage; the caller guarantees (x, y) is inside.
    void blend_unchecked(int x, int y, const Paint& p, float coverage) {
        float* d = &rgb_[(static_cast<std::size_t>(y) * static_cast<std::size_t>(w_) + static_cast<std::size_t>(x)) * 3];
        const float a = p.a * coverage;
        d[0] += (p.r - d[0]) * a;
        d[1] += (p.g - d[1]) * a;
        d[2] += (p.b - d[2]) * a;
    }
    void blend(int x, int y, const Paint& p, float coverage) {
        if (x >= 0 && y >= 0 && x < w_ && y < h_) blend_unchecked(x, y, p, coverage);
    }
    void fill(Rect r, const Paint& p);
    Image to_image() const;

private:
    int w_, h_;
    std::vector<float> rgb_;
};

// Calls plot(x, y, coverage) for the pixels within half_width + 0.5 px of the segment (x0,y0)-(x1,y1)
// (image coordinates) that it covers, coverage = clamp(half_width + 0.5 - distance, 0, 1) > 0: the capsule
// rasteriser the visualiser draws with too (impactlab/raster.hpp). Only pixels inside `clip` are visited,
// each at most once. The coordinates must be finite and moderate (clip the segment first).
template <class Plot>
void raster_segment(double x0, double y0, double x1, double y1, double half_width, const Rect& clip, Plot&& plot) {
    raster::capsule(x0, y0, x1, y1, half_width, clip.x0, clip.y0, clip.x1, clip.y1, [&](int x, int y, double cov, double) {
        if (cov > 0.0) plot(x, y, static_cast<float>(cov));
    });
}

// Liang-Barsky: clips the segment to the rectangle [xlo, xhi] x [ylo, yhi]; false if nothing is left.
// The ends it leaves are finite and inside the rectangle.
bool clip_segment(double& x0, double& y0, double& x1, double& y1, double xlo, double ylo, double xhi, double yhi);

// A coverage buffer over a rectangle: primitives of one series write max(coverage) into it, then it is
// composited once, so overlapping segments of a polyline never blend twice.
class Layer {
public:
    explicit Layer(Rect area);
    void plot(int x, int y, float coverage) {
        float& c = cov_[static_cast<std::size_t>(y - area_.y0) * static_cast<std::size_t>(area_.width())
                        + static_cast<std::size_t>(x - area_.x0)];
        if (coverage > c) c = coverage;
        dirty_.x0 = std::min(dirty_.x0, x);
        dirty_.x1 = std::max(dirty_.x1, x + 1);
        dirty_.y0 = std::min(dirty_.y0, y);
        dirty_.y1 = std::max(dirty_.y1, y + 1);
    }
    const Rect& area() const { return area_; }
    // Blends the colour with the accumulated coverage onto the canvas and clears the layer.
    void composite(Canvas& canvas, const Paint& p);

private:
    Rect area_, dirty_;
    std::vector<float> cov_;
};

// Round anti-aliased dot of the given radius centred at (cx, cy); radius <= 0.5 splats one pixel's worth
// of ink bilinearly onto the 2x2 nearest pixels.
inline void draw_dot(Canvas& canvas, double cx, double cy, double radius, const Rect& clip, const Paint& p) {
    if (radius <= 0.5) {
        const double u = cx - 0.5, v = cy - 0.5;
        const int i = static_cast<int>(std::floor(u)), j = static_cast<int>(std::floor(v));
        const float fx = static_cast<float>(u - i), fy = static_cast<float>(v - j);
        const float w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
        for (int k = 0; k < 4; ++k) {
            const int x = i + (k & 1), y = j + (k >> 1);
            if (x >= clip.x0 && x < clip.x1 && y >= clip.y0 && y < clip.y1 && w[k] > 0)
                canvas.blend_unchecked(x, y, p, w[k]);
        }
        return;
    }
    const double R = radius + 0.5;
    const int x0 = std::max(clip.x0, static_cast<int>(std::floor(cx - R)));
    const int x1 = std::min(clip.x1 - 1, static_cast<int>(std::floor(cx + R)));
    const int y0 = std::max(clip.y0, static_cast<int>(std::floor(cy - R)));
    const int y1 = std::min(clip.y1 - 1, static_cast<int>(std::floor(cy + R)));
    for (int y = y0; y <= y1; ++y) {
        const double dy = y + 0.5 - cy;
        for (int x = x0; x <= x1; ++x) {
            const double dx = x + 0.5 - cx;
            const double c = R - std::sqrt(dx * dx + dy * dy);
            if (c > 0.0) canvas.blend_unchecked(x, y, p, static_cast<float>(std::min(c, 1.0)));
        }
    }
}

// Anchor of a text box: horizontally along the text, vertically across it.
enum class HAlign { Left, Center, Right };
enum class VAlign { Top, Middle, Baseline, Bottom };   // Top = ascent line, Middle = half the digit height

// Draws the mask so that its anchor point lands at image position (x, y). rotated: turned 90 degrees
// counter-clockwise (reads bottom to top; "Top" is then the left side of the text).
void draw_text(Canvas& canvas, const TextMask& mask, double x, double y, HAlign h, VAlign v, const Paint& p,
               bool rotated = false);

}  // namespace impactlab::plot::detail
