#include "plot_raster.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "impactlab/raster.hpp"

namespace impactlab::gui {

namespace {

// Calls cover(index, coverage, t) for every pixel of a w x h image within reach of segment a-b drawn
// `width` px wide (core's capsule rasteriser, in float): coverage in [0, 1] from the distance to the
// segment, t in [0, 1] the position along it. Returns the rectangle visited (empty if off the image).
template <class Cover>
PixelRect rasterize_segment(int w, int h, PxPoint a, PxPoint b, float width, Cover&& cover) {
    const auto row = static_cast<std::size_t>(w);
    const raster::PixelBox r = raster::capsule(a.x, a.y, b.x, b.y, 0.5f * width, 0, 0, w, h, [&](int x, int y, float cov, float t) {
        cover(static_cast<std::size_t>(y) * row + static_cast<std::size_t>(x), cov, t);
    });
    return r.empty() ? PixelRect{} : PixelRect{r.x0, r.y0, r.x1, r.y1};
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

// Straight-alpha "over" of colour (r, g, b) at opacity sa (0..255) onto pixel d, in 8 bits. An empty
// pixel below is a plain store, an opaque one an integer mix (the opaque canvases' every pixel).
inline void over(std::uint8_t* d, unsigned r, unsigned g, unsigned b, unsigned sa) {
    if (d[3] == 0) {
        d[0] = static_cast<std::uint8_t>(r), d[1] = static_cast<std::uint8_t>(g), d[2] = static_cast<std::uint8_t>(b);
        d[3] = static_cast<std::uint8_t>(sa);
        return;
    }
    if (d[3] == 255) {
        const unsigned ia = 255 - sa;
        d[0] = static_cast<std::uint8_t>((r * sa + d[0] * ia + 127) / 255);
        d[1] = static_cast<std::uint8_t>((g * sa + d[1] * ia + 127) / 255);
        d[2] = static_cast<std::uint8_t>((b * sa + d[2] * ia + 127) / 255);
        return;
    }
    const float as = sa / 255.0f, ad = d[3] / 255.0f * (1.0f - as);
    const float ao = as + ad, k = 1.0f / ao;
    d[0] = static_cast<std::uint8_t>((r * as + d[0] * ad) * k + 0.5f);
    d[1] = static_cast<std::uint8_t>((g * as + d[1] * ad) * k + 0.5f);
    d[2] = static_cast<std::uint8_t>((b * as + d[2] * ad) * k + 0.5f);
    d[3] = static_cast<std::uint8_t>(ao * 255.0f + 0.5f);
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
    } else if (opaque_) {   // the last frame filled everything
        std::fill(rgba_.begin(), rgba_.end(), std::uint8_t{0});
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
    opaque_ = false;
}

void RasterCanvas::begin_opaque(PxPoint min, PxPoint max, PackedColor backdrop) {
    const PixelArea area = pixel_area(min, max);
    x0_ = area.x0;
    y0_ = area.y0;
    const std::size_t n = static_cast<std::size_t>(area.w) * static_cast<std::size_t>(area.h);
    if (area.w != w_ || area.h != h_) {
        w_ = area.w;
        h_ = area.h;
        cover_.assign(n, 0);
        rgba_.resize(n * 4);
    }
    const Rgba8 c = unpack(backdrop);
    const std::uint8_t px[4] = {c.r, c.g, c.b, 255};
    std::uint32_t word = 0;
    std::memcpy(&word, px, 4);
    std::uint32_t* dst = reinterpret_cast<std::uint32_t*>(rgba_.data());
    std::fill(dst, dst + n, word);
    drawn_ = PixelRect{0, 0, w_ - 1, h_ - 1};
    layer_rect_ = PixelRect{};
    layer_open_ = false;
    active_ = true;
    opaque_ = true;
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
    const Rgba8 col = unpack(color_);
    const unsigned ca = col.a;
    for (int y = layer_rect_.y0; y <= layer_rect_.y1; ++y) {
        const std::size_t row = static_cast<std::size_t>(y) * static_cast<std::size_t>(w_);
        for (int x = layer_rect_.x0; x <= layer_rect_.x1; ++x) {
            const std::size_t i = row + static_cast<std::size_t>(x);
            // Most of a layer's rectangle is empty: skip it eight pixels at a time.
            if (x + 8 <= layer_rect_.x1 + 1) {
                std::uint64_t eight;
                std::memcpy(&eight, &cover_[i], 8);
                if (!eight) {
                    x += 7;
                    continue;
                }
            }
            const unsigned c = cover_[i];
            if (!c) continue;
            cover_[i] = 0;
            over(&rgba_[i * 4], col.r, col.g, col.b, (ca * c + 127) / 255);
        }
    }
    drawn_.add(layer_rect_);
    layer_rect_ = PixelRect{};
    layer_open_ = false;
}

void RasterCanvas::segment(PxPoint a, PxPoint b, float width, float alpha_a, float alpha_b) {
    // Axis-aligned and of one opacity (grid lines, dashes, markers' lines): a bar, without a distance per pixel.
    if (alpha_a == 1.0f && alpha_b == 1.0f && width <= 6.0f && (a.x != b.x || a.y != b.y)) {
        if (a.x == b.x) {
            vspan(a.x, a.y, b.y, width);
            return;
        }
        if (a.y == b.y) {
            hspan(a.y, a.x, b.x, width);
            return;
        }
    }
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

void RasterCanvas::hspan(float y, float x0, float x1, float width) {
    const float hw = 0.5f * width;
    const float cy = y - static_cast<float>(y0_);
    const float left = std::min(x0, x1) - static_cast<float>(x0_) - hw, right = std::max(x0, x1) - static_cast<float>(x0_) + hw;
    PixelRect r;
    r.y0 = std::max(0, static_cast<int>(std::floor(cy - hw)));
    r.y1 = std::min(h_ - 1, static_cast<int>(std::floor(cy + hw)));
    r.x0 = std::max(0, static_cast<int>(std::floor(left)));
    r.x1 = std::min(w_ - 1, static_cast<int>(std::floor(right)));
    if (r.empty()) return;
    // Vertical coverage of each row: the overlap of [cy - hw, cy + hw] with [k, k + 1].
    const int nrows = std::min(8, r.y1 - r.y0 + 1);
    for (int k = 0; k < nrows; ++k) {
        const float a = static_cast<float>(r.y0 + k), b = a + 1.0f;
        const float rc = std::max(0.0f, std::min(b, cy + hw) - std::max(a, cy - hw));
        std::uint8_t* row = &cover_[static_cast<std::size_t>(r.y0 + k) * static_cast<std::size_t>(w_)];
        for (int x = r.x0; x <= r.x1; ++x) {
            const float px = static_cast<float>(x) + 0.5f;
            const float hc = std::min(1.0f, std::max(0.0f, std::min(px - left, right - px) + 0.5f));
            const auto c8 = static_cast<std::uint8_t>(hc * rc * 255.0f + 0.5f);
            row[x] = std::max(row[x], c8);
        }
    }
    r.y1 = r.y0 + nrows - 1;
    layer_rect_.add(r);
}

void RasterCanvas::fill_rect(PxPoint min, PxPoint max, float alpha) {
    const int x0 = std::max(0, static_cast<int>(std::lround(min.x)) - x0_);
    const int y0 = std::max(0, static_cast<int>(std::lround(min.y)) - y0_);
    const int x1 = std::min(w_, static_cast<int>(std::lround(max.x)) - x0_) - 1;
    const int y1 = std::min(h_, static_cast<int>(std::lround(max.y)) - y0_) - 1;
    if (x1 < x0 || y1 < y0) return;
    const auto c8 = static_cast<std::uint8_t>(std::clamp(alpha, 0.0f, 1.0f) * 255.0f + 0.5f);
    for (int y = y0; y <= y1; ++y) {
        std::uint8_t* row = &cover_[static_cast<std::size_t>(y) * static_cast<std::size_t>(w_)];
        for (int x = x0; x <= x1; ++x) row[x] = std::max(row[x], c8);
    }
    layer_rect_.add(PixelRect{x0, y0, x1, y1});
}

void RasterCanvas::blend_image(const std::uint8_t* rgba, int w, int h, float alpha) {
    flatten_layer();
    const int cw = std::min(w, w_), ch = std::min(h, h_);
    const unsigned k = static_cast<unsigned>(std::clamp(alpha, 0.0f, 1.0f) * 255.0f + 0.5f);
    PixelRect touched;
    // The alpha bytes of two RGBA pixels, as a 64-bit word read from memory (any byte order).
    const std::uint8_t alpha_bytes[8] = {0, 0, 0, 255, 0, 0, 0, 255};
    std::uint64_t alphas = 0;
    std::memcpy(&alphas, alpha_bytes, 8);
    for (int y = 0; y < ch; ++y) {
        const std::uint8_t* s = rgba + static_cast<std::size_t>(y) * static_cast<std::size_t>(w) * 4;
        std::uint8_t* d = &rgba_[static_cast<std::size_t>(y) * static_cast<std::size_t>(w_) * 4];
        int first = -1, last = -1;
        for (int x = 0; x < cw; ++x, s += 4, d += 4) {
            if (x + 2 <= cw) {   // mostly transparent: two pixels at a time
                std::uint64_t two;
                std::memcpy(&two, s, 8);
                if (!(two & alphas)) {
                    ++x, s += 4, d += 4;
                    continue;
                }
            }
            if (!s[3]) continue;
            const unsigned sa = k == 255 ? s[3] : (s[3] * k + 127) / 255;
            if (!sa) continue;
            over(d, s[0], s[1], s[2], sa);
            if (first < 0) first = x;
            last = x;
        }
        if (first >= 0) touched.add(PixelRect{first, y, last, y});
    }
    drawn_.add(touched);
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
