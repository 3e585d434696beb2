// The capsule rasteriser, one for the PNG figures (core's plot module) and the visualiser's CPU plot
// layer: the pixels near a segment drawn `half_width` either side of it with round ends, each with its
// coverage clamp(half_width + 0.5 - distance, 0, 1) (one pixel of antialiasing: a 1-px line through pixel
// centres covers exactly one pixel per step).
#pragma once

#include <algorithm>
#include <cmath>

namespace impactlab::raster {

struct PixelBox {   // columns x0..x1, rows y0..y1, both inclusive; empty when x1 < x0 or y1 < y0
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
    bool empty() const { return x1 < x0 || y1 < y0; }
};

// Calls cover(x, y, coverage, t) once for each pixel of the clip [cx0, cx1) x [cy0, cy1) within reach of
// segment a-b (pixel (x, y) spans [x, x + 1) x [y, y + 1)), row by row: coverage in [0, 1] (0 at the
// ends of a row's run), t in [0, 1] where along the segment the nearest point lies. T is float for the
// visualiser's per-frame drawing (the inner loop is branch-free so it vectorises; build it with
// -fno-math-errno) and double for the figures. The coordinates must be finite and moderate (clip the
// segment first). Returns the box visited (empty when the segment's reach misses the clip).
template <class T, class Cover>
PixelBox capsule(T ax, T ay, T bx, T by, T half_width, int cx0, int cy0, int cx1, int cy1, Cover&& cover) {
    const T hw = half_width, one = 1, half = T(0.5), zero = 0;
    PixelBox r;
    r.x0 = std::max(cx0, static_cast<int>(std::floor(std::min(ax, bx) - hw - one)));
    r.y0 = std::max(cy0, static_cast<int>(std::floor(std::min(ay, by) - hw - one)));
    r.x1 = std::min(cx1 - 1, static_cast<int>(std::ceil(std::max(ax, bx) + hw + one)));
    r.y1 = std::min(cy1 - 1, static_cast<int>(std::ceil(std::max(ay, by) + hw + one)));
    if (r.empty()) return r;
    const T dx = bx - ax, dy = by - ay;
    const T len2 = dx * dx + dy * dy;
    const T inv = len2 > T(1e-12) ? one / len2 : zero;
    const T outer = hw + half;
    // Per row, only the pixels within `outer` of the segment's line can be covered: for a steep or
    // diagonal segment that is a short run, not the whole bounding box.
    const T len = std::sqrt(len2);
    const T nx = len > T(1e-6) ? -dy / len : zero, ny = len > T(1e-6) ? dx / len : one;
    const bool clip_rows = std::abs(nx) > T(0.2);
    for (int y = r.y0; y <= r.y1; ++y) {
        const T py = static_cast<T>(y) + half - ay;
        int xa = r.x0, xb = r.x1;
        if (clip_rows) {
            // |nx * px + ny * py| < outer  with px = x + 0.5 - ax
            const T c = -ny * py / nx, rr = outer / std::abs(nx);
            xa = std::max(r.x0, static_cast<int>(std::floor(ax + c - rr - half)));
            xb = std::min(r.x1, static_cast<int>(std::ceil(ax + c + rr - half)));
        }
        for (int x = xa; x <= xb; ++x) {
            const T px = static_cast<T>(x) + half - ax;
            const T t = std::min(one, std::max(zero, (px * dx + py * dy) * inv));
            const T ex = px - t * dx, ey = py - t * dy;
            const T cov = std::min(one, std::max(zero, outer - std::sqrt(ex * ex + ey * ey)));
            cover(x, y, cov, t);
        }
    }
    return r;
}

}  // namespace impactlab::raster
