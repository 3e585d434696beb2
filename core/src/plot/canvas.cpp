#include "plot/canvas.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace impactlab::plot::detail {

Canvas::Canvas(int width, int height)
    : w_(width), h_(height), rgb_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3, 255.0f) {}

void Canvas::fill(Rect r, const Paint& p) {
    r = intersect(r, bounds());
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) blend_unchecked(x, y, p, 1.0f);
}

Image Canvas::to_image() const {
    Image img;
    img.width = w_;
    img.height = h_;
    const std::size_t n = static_cast<std::size_t>(w_) * static_cast<std::size_t>(h_);
    img.rgba.resize(n * 4);
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t c = 0; c < 3; ++c)
            img.rgba[i * 4 + c] = static_cast<std::uint8_t>(std::clamp(rgb_[i * 3 + c] + 0.5f, 0.0f, 255.0f));
        img.rgba[i * 4 + 3] = 255;
    }
    return img;
}

bool clip_segment(double& x0, double& y0, double& x1, double& y1, double xlo, double ylo, double xhi, double yhi) {
    double t0 = 0.0, t1 = 1.0;
    const double dx = x1 - x0, dy = y1 - y0;
    const double p[4] = {-dx, dx, -dy, dy};
    const double q[4] = {x0 - xlo, xhi - x0, y0 - ylo, yhi - y0};
    for (int k = 0; k < 4; ++k) {
        if (p[k] == 0.0) {
            if (q[k] < 0.0) return false;
            continue;
        }
        const double t = q[k] / p[k];
        if (p[k] < 0.0)
            t0 = std::max(t0, t);
        else
            t1 = std::min(t1, t);
        if (t0 > t1) return false;
    }
    // Clamped: with far-away ends (1e300) the products lose all precision near the box.
    const double nx0 = x0 + t0 * dx, ny0 = y0 + t0 * dy, nx1 = x0 + t1 * dx, ny1 = y0 + t1 * dy;
    if (!std::isfinite(nx0) || !std::isfinite(ny0) || !std::isfinite(nx1) || !std::isfinite(ny1)) return false;
    x0 = std::clamp(nx0, xlo, xhi);
    y0 = std::clamp(ny0, ylo, yhi);
    x1 = std::clamp(nx1, xlo, xhi);
    y1 = std::clamp(ny1, ylo, yhi);
    return true;
}

Layer::Layer(Rect area)
    : area_(area),
      dirty_{std::numeric_limits<int>::max(), std::numeric_limits<int>::max(), std::numeric_limits<int>::min(),
             std::numeric_limits<int>::min()},
      cov_(static_cast<std::size_t>(std::max(0, area.width())) * static_cast<std::size_t>(std::max(0, area.height())),
           0.0f) {}

void Layer::composite(Canvas& canvas, const Paint& p) {
    const Rect d = intersect(dirty_, area_);
    for (int y = d.y0; y < d.y1; ++y) {
        float* row = &cov_[static_cast<std::size_t>(y - area_.y0) * static_cast<std::size_t>(area_.width())];
        for (int x = d.x0; x < d.x1; ++x) {
            float& c = row[x - area_.x0];
            if (c > 0.0f) {
                canvas.blend_unchecked(x, y, p, c);
                c = 0.0f;
            }
        }
    }
    dirty_ = {std::numeric_limits<int>::max(), std::numeric_limits<int>::max(), std::numeric_limits<int>::min(),
              std::numeric_limits<int>::min()};
}

void draw_text(Canvas& canvas, const TextMask& mask, double x, double y, HAlign h, VAlign v, const Paint& p,
               bool rotated) {
    if (mask.w == 0 || mask.h == 0) return;
    // Anchor in mask coordinates.
    const double ax = mask.origin_x + (h == HAlign::Left ? 0.0 : h == HAlign::Center ? mask.advance / 2 : mask.advance);
    double ay = mask.baseline;
    switch (v) {
        case VAlign::Top: ay -= mask.ascent; break;
        case VAlign::Middle: ay -= mask.cap_height / 2; break;
        case VAlign::Baseline: break;
        case VAlign::Bottom: ay -= mask.descent; break;
    }
    if (!rotated) {
        const int ox = static_cast<int>(std::lround(x - ax)), oy = static_cast<int>(std::lround(y - ay));
        for (int j = 0; j < mask.h; ++j)
            for (int i = 0; i < mask.w; ++i) {
                const std::uint8_t a = mask.alpha[static_cast<std::size_t>(j * mask.w + i)];
                if (a != 0) canvas.blend(ox + i, oy + j, p, a / 255.0f);
            }
    } else {
        // Mask pixel (i, j) -> image pixel (ox + j, oy - i): text runs upwards, its top faces left.
        const int ox = static_cast<int>(std::lround(x - ay)), oy = static_cast<int>(std::lround(y + ax)) - 1;
        for (int j = 0; j < mask.h; ++j)
            for (int i = 0; i < mask.w; ++i) {
                const std::uint8_t a = mask.alpha[static_cast<std::size_t>(j * mask.w + i)];
                if (a != 0) canvas.blend(ox + j, oy - i, p, a / 255.0f);
            }
    }
}

}  // namespace impactlab::plot::detail
