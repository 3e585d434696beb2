#include "plot_raster.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace impactlab::gui {

namespace {

// Calls cover(index, coverage, t) for every pixel of a w x h image within reach of segment a-b drawn
// `width` px wide: coverage in [0, 1] from the distance to the segment (one pixel of antialiasing), t in
// [0, 1] the position along it. Returns the rectangle visited (empty if off the image).
template <class Cover>
PixelRect rasterize_segment(int w, int h, PxPoint a, PxPoint b, float width, Cover&& cover) {
    const float hw = 0.5f * width;
    PixelRect r;
    r.x0 = std::max(0, static_cast<int>(std::floor(std::min(a.x, b.x) - hw - 1.0f)));
    r.y0 = std::max(0, static_cast<int>(std::floor(std::min(a.y, b.y) - hw - 1.0f)));
    r.x1 = std::min(w - 1, static_cast<int>(std::ceil(std::max(a.x, b.x) + hw + 1.0f)));
    r.y1 = std::min(h - 1, static_cast<int>(std::ceil(std::max(a.y, b.y) + hw + 1.0f)));
    if (r.empty()) return r;
    const float dx = b.x - a.x, dy = b.y - a.y;
    const float len2 = dx * dx + dy * dy;
    const float inv = len2 > 1e-12f ? 1.0f / len2 : 0.0f;
    const float outer = hw + 0.5f;
    // Per row, only the pixels within `outer` of the segment's line can be covered: for a steep or
    // diagonal segment that is a short run, not the whole bounding box.
    const float len = std::sqrt(len2);
    const float nx = len > 1e-6f ? -dy / len : 0.0f, ny = len > 1e-6f ? dx / len : 1.0f;
    const bool clip_rows = std::abs(nx) > 0.2f;
    for (int y = r.y0; y <= r.y1; ++y) {
        const float py = static_cast<float>(y) + 0.5f - a.y;
        int xa = r.x0, xb = r.x1;
        if (clip_rows) {
            // |nx * px + ny * py| < outer  with px = x + 0.5 - a.x
            const float c = -ny * py / nx, rr = outer / std::abs(nx);
            xa = std::max(r.x0, static_cast<int>(std::floor(a.x + c - rr - 0.5f)));
            xb = std::min(r.x1, static_cast<int>(std::ceil(a.x + c + rr - 0.5f)));
        }
        const std::size_t row = static_cast<std::size_t>(y) * static_cast<std::size_t>(w);
        // Branch-free so the compiler can vectorize it (this file is built with -fno-math-errno).
        for (int x = xa; x <= xb; ++x) {
            const float px = static_cast<float>(x) + 0.5f - a.x;
            const float t = std::min(1.0f, std::max(0.0f, (px * dx + py * dy) * inv));
            const float ex = px - t * dx, ey = py - t * dy;
            const float cov = std::min(1.0f, std::max(0.0f, outer - std::sqrt(ex * ex + ey * ey)));
            cover(row + static_cast<std::size_t>(x), cov, t);
        }
    }
    return r;
}

// The whole pixels an area [min, max) of display pixels spans: origin and size (at least 1 x 1).
struct PixelArea {
    int x0, y0, w, h;
};
PixelArea pixel_area(PxPoint min, PxPoint max) {
    const int x0 = static_cast<int>(std::floor(min.x)), y0 = static_cast<int>(std::floor(min.y));
    return {x0, y0, std::max(1, static_cast<int>(std::ceil(max.x)) - x0), std::max(1, static_cast<int>(std::ceil(max.y)) - y0)};
}

// A packed colour's channels.
struct Rgba8 {
    std::uint8_t r, g, b, a;
};
Rgba8 unpack(PackedColor c) {
    return {static_cast<std::uint8_t>(c >> kColorRShift), static_cast<std::uint8_t>(c >> kColorGShift),
            static_cast<std::uint8_t>(c >> kColorBShift), static_cast<std::uint8_t>(c >> kColorAShift)};
}

}  // namespace

void PixelRect::add(const PixelRect& r) {
    if (r.empty()) return;
    if (empty()) {
        *this = r;
        return;
    }
    x0 = std::min(x0, r.x0), y0 = std::min(y0, r.y0), x1 = std::max(x1, r.x1), y1 = std::max(y1, r.y1);
}

// ---- RasterCanvas -----------------------------------------------------------------------------------------

void RasterCanvas::begin(PxPoint min, PxPoint max) {
    const PixelArea area = pixel_area(min, max);
    x0_ = area.x0;
    y0_ = area.y0;
    const int w = area.w, h = area.h;
    const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    if (w != w_ || h != h_) {
        w_ = w;
        h_ = h;
        cover_.assign(n, 0);
        rgba_.assign(n * 4, 0);
    } else if (!drawn_.empty()) {
        // Only what the last frame drew is dirty.
        const std::size_t cols = static_cast<std::size_t>(drawn_.x1 - drawn_.x0 + 1) * 4;
        for (int y = drawn_.y0; y <= drawn_.y1; ++y)
            std::memset(&rgba_[(static_cast<std::size_t>(y) * static_cast<std::size_t>(w_) + static_cast<std::size_t>(drawn_.x0)) * 4], 0, cols);
    }
    drawn_ = PixelRect{};
    layer_rect_ = PixelRect{};
    layer_open_ = false;
    active_ = true;
}

void RasterCanvas::layer(PackedColor color) {
    flatten_layer();
    color_ = color;
    layer_open_ = true;
}

void RasterCanvas::flatten_layer() {
    if (!layer_open_ || layer_rect_.empty()) {
        layer_open_ = false;
        return;
    }
    // Straight-alpha "over" in 8 bits: the common case (an empty pixel below) is a plain store.
    const Rgba8 col = unpack(color_);
    const std::uint8_t cr = col.r, cg = col.g, cb = col.b;
    const unsigned ca = col.a;
    for (int y = layer_rect_.y0; y <= layer_rect_.y1; ++y) {
        const std::size_t row = static_cast<std::size_t>(y) * static_cast<std::size_t>(w_);
        for (int x = layer_rect_.x0; x <= layer_rect_.x1; ++x) {
            const std::size_t i = row + static_cast<std::size_t>(x);
            const unsigned c = cover_[i];
            if (!c) continue;
            cover_[i] = 0;
            const unsigned sa = (ca * c + 127) / 255;
            std::uint8_t* d = &rgba_[i * 4];
            if (d[3] == 0) {
                d[0] = cr, d[1] = cg, d[2] = cb, d[3] = static_cast<std::uint8_t>(sa);
                continue;
            }
            const float as = sa / 255.0f, ad = d[3] / 255.0f * (1.0f - as);
            const float ao = as + ad, k = 1.0f / ao;
            d[0] = static_cast<std::uint8_t>((cr * as + d[0] * ad) * k + 0.5f);
            d[1] = static_cast<std::uint8_t>((cg * as + d[1] * ad) * k + 0.5f);
            d[2] = static_cast<std::uint8_t>((cb * as + d[2] * ad) * k + 0.5f);
            d[3] = static_cast<std::uint8_t>(ao * 255.0f + 0.5f);
        }
    }
    drawn_.add(layer_rect_);
    layer_rect_ = PixelRect{};
    layer_open_ = false;
}

void RasterCanvas::segment(PxPoint a, PxPoint b, float width, float alpha_a, float alpha_b) {
    const PxPoint o{static_cast<float>(x0_), static_cast<float>(y0_)};
    const float da = alpha_a * 255.0f, db = (alpha_b - alpha_a) * 255.0f;
    std::uint8_t* cover = cover_.data();
    const PixelRect r = rasterize_segment(w_, h_, PxPoint{a.x - o.x, a.y - o.y}, PxPoint{b.x - o.x, b.y - o.y}, width,
                                          [&](std::size_t i, float cov, float t) {
                                              const auto c8 = static_cast<std::uint8_t>(cov * (da + db * t) + 0.5f);
                                              cover[i] = std::max(cover[i], c8);
                                          });
    layer_rect_.add(r);
}

void RasterCanvas::dot(PxPoint c, float diameter, float alpha) { segment(c, c, diameter, alpha, alpha); }

void RasterCanvas::vspan(float x, float y0, float y1, float width) {
    const float hw = 0.5f * width;
    const float cx = x - static_cast<float>(x0_);
    const float top = std::min(y0, y1) - static_cast<float>(y0_) - hw, bottom = std::max(y0, y1) - static_cast<float>(y0_) + hw;
    PixelRect r;
    r.x0 = std::max(0, static_cast<int>(std::floor(cx - hw)));
    r.x1 = std::min(w_ - 1, static_cast<int>(std::floor(cx + hw)));
    r.y0 = std::max(0, static_cast<int>(std::floor(top)));
    r.y1 = std::min(h_ - 1, static_cast<int>(std::floor(bottom)));
    if (r.empty()) return;
    // Horizontal coverage of each column: the overlap of [cx - hw, cx + hw] with [k, k + 1].
    float colcov[8];
    const int ncols = std::min(8, r.x1 - r.x0 + 1);
    for (int k = 0; k < ncols; ++k) {
        const float a = static_cast<float>(r.x0 + k), b = a + 1.0f;
        colcov[k] = std::max(0.0f, std::min(b, cx + hw) - std::max(a, cx - hw));
    }
    for (int y = r.y0; y <= r.y1; ++y) {
        const float py = static_cast<float>(y) + 0.5f;
        const float vc = std::min(1.0f, std::max(0.0f, std::min(py - top, bottom - py) + 0.5f));
        std::uint8_t* row = &cover_[static_cast<std::size_t>(y) * static_cast<std::size_t>(w_) + static_cast<std::size_t>(r.x0)];
        for (int k = 0; k < ncols; ++k) {
            const auto c8 = static_cast<std::uint8_t>(vc * colcov[k] * 255.0f + 0.5f);
            row[k] = std::max(row[k], c8);
        }
    }
    r.x1 = r.x0 + ncols - 1;
    layer_rect_.add(r);
}

PixelRect RasterCanvas::finish() {
    flatten_layer();
    active_ = false;
    return drawn_;
}

// ---- TrailCanvas ------------------------------------------------------------------------------------------

bool TrailCanvas::same_view(const Frame& f) const {
    const PixelArea area = pixel_area(f.min, f.max);
    if (area.w != w_ || area.h != h_ || f.color != color_ || f.thickness != thickness_) return false;
    // The mappings are affine: if the area's corners land within half a pixel, every point does.
    const double xs[2] = {(f.min.x - f.map.ax) / f.map.bx, (f.max.x - f.map.ax) / f.map.bx};
    const double ys[2] = {(f.min.y - f.map.ay) / f.map.by, (f.max.y - f.map.ay) / f.map.by};
    for (double x : xs)
        for (double y : ys) {
            const PxPoint now = f.map.to_px(x, y), then = map_.to_px(x, y);
            if (std::abs((now.x - static_cast<float>(area.x0)) - (then.x - static_cast<float>(x0_))) > 0.5f ||
                std::abs((now.y - static_cast<float>(area.y0)) - (then.y - static_cast<float>(y0_))) > 0.5f)
                return false;
        }
    return true;
}

std::size_t TrailCanvas::begin(const Frame& f) {
    first_ = f.first_seq;
    last_ = f.last_seq;
    const bool keep = generation_ == f.generation && same_view(f) && f.first_seq >= base_ &&
                      next_seq_ >= f.first_seq && next_seq_ <= f.last_seq + 1 && f.last_seq - base_ < (1ull << 31);
    // The image stays where it was drawn relative to the area (it is shown over the area).
    const PixelArea area = pixel_area(f.min, f.max);
    if (keep) {
        map_.ax += static_cast<double>(area.x0 - x0_);
        map_.ay += static_cast<double>(area.y0 - y0_);
        x0_ = area.x0;
        y0_ = area.y0;
        full_ = false;
        return static_cast<std::size_t>(next_seq_ - f.first_seq);
    }
    full_ = true;
    x0_ = area.x0;
    y0_ = area.y0;
    const int w = area.w, h = area.h;
    const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    if (w != w_ || h != h_) rgba_.assign(n * 4, 0);
    w_ = w;
    h_ = h;
    stamp_.assign(n, 0);
    cover_.assign(n, 0);
    map_ = f.map;
    color_ = f.color;
    thickness_ = f.thickness;
    generation_ = f.generation;
    base_ = f.first_seq;
    next_seq_ = f.first_seq;
    have_prev_ = false;
    return 0;
}

void TrailCanvas::feed(std::uint64_t seq, double x, double y) {
    const PxPoint p = map_.to_px(x, y);
    const PxPoint q{p.x - static_cast<float>(x0_), p.y - static_cast<float>(y0_)};
    next_seq_ = seq + 1;
    if (!have_prev_) {
        have_prev_ = true;
        prev_ = q;
        return;
    }
    // Steps under 1.5 px add nothing visible to a 1.6 px line; the newest sample is always drawn so the
    // next frame continues from it.
    const float dx = q.x - prev_.x, dy = q.y - prev_.y;
    if (dx * dx + dy * dy < 2.25f && seq != last_) return;
    segment(prev_, q, static_cast<std::uint32_t>(seq - base_ + 1));
    prev_ = q;
}

void TrailCanvas::segment(PxPoint a, PxPoint b, std::uint32_t stamp) {
    // A pixel takes the new sample if it covers it at least as strongly as the old one did, or if the old
    // one has left the trail: the newest opacity wins, as a max-combine at the time of drawing would.
    const std::uint32_t expired = static_cast<std::uint32_t>(first_ >= base_ ? first_ - base_ + 1 : 0);
    std::uint32_t* st = stamp_.data();
    std::uint8_t* cv = cover_.data();
    rasterize_segment(w_, h_, a, b, thickness_, [&](std::size_t i, float cov, float) {
        const auto c8 = static_cast<std::uint8_t>(cov * 255.0f + 0.5f);
        if (c8 && (c8 >= cv[i] || st[i] < expired)) {
            cv[i] = c8;
            st[i] = stamp;
        }
    });
}

void TrailCanvas::finish() {
    // Opacity ((seq - first + 1) / n)^2 by the age of each pixel's newest sample.
    const std::uint32_t s_first = static_cast<std::uint32_t>(first_ - base_ + 1);
    const float inv_n = 1.0f / static_cast<float>(last_ - first_ + 1);
    const Rgba8 col = unpack(color_);
    const float ca = col.a / 255.0f;
    const std::uint8_t cr = col.r, cg = col.g, cb = col.b;
    const std::size_t n = stamp_.size();
    for (std::size_t i = 0; i < n; ++i) {
        std::uint8_t* d = &rgba_[i * 4];
        const std::uint8_t c = cover_[i];
        if (!c) {
            d[3] = 0;
            continue;
        }
        if (stamp_[i] < s_first) {   // left the trail: forget it
            cover_[i] = 0;
            d[3] = 0;
            continue;
        }
        const float f = static_cast<float>(stamp_[i] - s_first + 1) * inv_n;
        d[0] = cr, d[1] = cg, d[2] = cb;
        d[3] = static_cast<std::uint8_t>(ca * c * f * f + 0.5f);
    }
}

}  // namespace impactlab::gui
