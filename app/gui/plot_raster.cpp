#include "plot_raster.hpp"

#include <algorithm>
#include <cmath>

#include "gl_util.hpp"

namespace impactlab::gui {

RasterCanvas::~RasterCanvas() {
    if (tex_) {
        const GLuint t = tex_;
        glDeleteTextures(1, &t);
    }
}

void RasterCanvas::begin(ImVec2 min, ImVec2 max) {
    x0_ = static_cast<int>(std::floor(min.x));
    y0_ = static_cast<int>(std::floor(min.y));
    w_ = std::max(1, static_cast<int>(std::ceil(max.x)) - x0_);
    h_ = std::max(1, static_cast<int>(std::ceil(max.y)) - y0_);
    const std::size_t n = static_cast<std::size_t>(w_) * static_cast<std::size_t>(h_);
    cover_.assign(n, 0);
    rgba_.assign(n * 4, 0.0f);
    lx0_ = ly0_ = 0;
    lx1_ = ly1_ = -1;
    layer_open_ = false;
    drawn_ = false;
    active_ = true;
    if (!tex_) {
        GLuint t = 0;
        glGenTextures(1, &t);
        tex_ = t;
    }
}

void RasterCanvas::layer(ImU32 color) {
    flatten_layer();
    color_ = ImGui::ColorConvertU32ToFloat4(color);
    layer_open_ = true;
}

void RasterCanvas::flatten_layer() {
    if (!layer_open_ || lx1_ < lx0_) {
        layer_open_ = false;
        return;
    }
    for (int y = ly0_; y <= ly1_; ++y) {
        for (int x = lx0_; x <= lx1_; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(w_) + static_cast<std::size_t>(x);
            const std::uint8_t c = cover_[i];
            if (!c) continue;
            cover_[i] = 0;
            const float a = color_.w * (c / 255.0f);
            float* d = &rgba_[i * 4];
            const float k = 1.0f - a;
            d[0] = color_.x * a + d[0] * k;
            d[1] = color_.y * a + d[1] * k;
            d[2] = color_.z * a + d[2] * k;
            d[3] = a + d[3] * k;
        }
    }
    lx0_ = ly0_ = 0;
    lx1_ = ly1_ = -1;
    layer_open_ = false;
    drawn_ = true;
}

void RasterCanvas::segment(ImVec2 a, ImVec2 b, float width, float alpha_a, float alpha_b) {
    const float hw = 0.5f * width;
    const float ax = a.x - static_cast<float>(x0_), ay = a.y - static_cast<float>(y0_);
    const float bx = b.x - static_cast<float>(x0_), by = b.y - static_cast<float>(y0_);
    const int ix0 = std::max(0, static_cast<int>(std::floor(std::min(ax, bx) - hw - 1.0f)));
    const int iy0 = std::max(0, static_cast<int>(std::floor(std::min(ay, by) - hw - 1.0f)));
    const int ix1 = std::min(w_ - 1, static_cast<int>(std::ceil(std::max(ax, bx) + hw + 1.0f)));
    const int iy1 = std::min(h_ - 1, static_cast<int>(std::ceil(std::max(ay, by) + hw + 1.0f)));
    if (ix0 > ix1 || iy0 > iy1) return;
    if (lx1_ < lx0_) {
        lx0_ = ix0, ly0_ = iy0, lx1_ = ix1, ly1_ = iy1;
    } else {
        lx0_ = std::min(lx0_, ix0), ly0_ = std::min(ly0_, iy0), lx1_ = std::max(lx1_, ix1), ly1_ = std::max(ly1_, iy1);
    }
    const float dx = bx - ax, dy = by - ay;
    const float len2 = dx * dx + dy * dy;
    const float inv = len2 > 1e-12f ? 1.0f / len2 : 0.0f;
    const float outer = hw + 0.5f;
    const float da = alpha_a * 255.0f, db = (alpha_b - alpha_a) * 255.0f;
    // Per row, only the pixels within `outer` of the segment's line can be covered: for a steep or
    // diagonal segment that is a short run, not the whole bounding box.
    const float len = std::sqrt(len2);
    const float nx = len > 1e-6f ? -dy / len : 0.0f, ny = len > 1e-6f ? dx / len : 1.0f;
    const bool clip_rows = std::abs(nx) > 0.2f;
    for (int y = iy0; y <= iy1; ++y) {
        const float py = static_cast<float>(y) + 0.5f - ay;
        int xa = ix0, xb = ix1;
        if (clip_rows) {
            // |nx * px + ny * py| < outer  with px = x + 0.5 - ax
            const float c = -ny * py / nx, r = outer / std::abs(nx);
            xa = std::max(ix0, static_cast<int>(std::floor(ax + c - r - 0.5f)));
            xb = std::min(ix1, static_cast<int>(std::ceil(ax + c + r - 0.5f)));
        }
        std::uint8_t* row = &cover_[static_cast<std::size_t>(y) * static_cast<std::size_t>(w_)];
        // Branch-free so the compiler vectorizes it (this file is built with -fno-math-errno).
        for (int x = xa; x <= xb; ++x) {
            const float px = static_cast<float>(x) + 0.5f - ax;
            const float t = std::min(1.0f, std::max(0.0f, (px * dx + py * dy) * inv));
            const float ex = px - t * dx, ey = py - t * dy;
            const float cov = std::min(1.0f, std::max(0.0f, outer - std::sqrt(ex * ex + ey * ey)));
            const auto c8 = static_cast<std::uint8_t>(cov * (da + db * t) + 0.5f);
            row[x] = std::max(row[x], c8);
        }
    }
}

void RasterCanvas::dot(ImVec2 c, float diameter, float alpha) { segment(c, c, diameter, alpha, alpha); }

unsigned RasterCanvas::finish() {
    flatten_layer();
    active_ = false;
    if (!drawn_) std::fill(rgba_.begin(), rgba_.end(), 0.0f);   // the image is already placed: make it empty
    // Straight alpha for ImGui's blending.
    out_.resize(static_cast<std::size_t>(w_) * static_cast<std::size_t>(h_) * 4);
    for (std::size_t i = 0, n = out_.size() / 4; i < n; ++i) {
        const float* s = &rgba_[i * 4];
        const float a = s[3];
        const float inv = a > 1e-6f ? 1.0f / a : 0.0f;
        out_[i * 4 + 0] = static_cast<std::uint8_t>(std::min(1.0f, s[0] * inv) * 255.0f + 0.5f);
        out_[i * 4 + 1] = static_cast<std::uint8_t>(std::min(1.0f, s[1] * inv) * 255.0f + 0.5f);
        out_[i * 4 + 2] = static_cast<std::uint8_t>(std::min(1.0f, s[2] * inv) * 255.0f + 0.5f);
        out_[i * 4 + 3] = static_cast<std::uint8_t>(std::min(1.0f, a) * 255.0f + 0.5f);
    }
    if (tex_w_ != w_ || tex_h_ != h_) {
        tex_ = upload_rgba_texture(tex_, w_, h_, out_.data());
        tex_w_ = w_;
        tex_h_ = h_;
    } else {
        glBindTexture(GL_TEXTURE_2D, tex_);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w_, h_, GL_RGBA, GL_UNSIGNED_BYTE, out_.data());
        glBindTexture(GL_TEXTURE_2D, 0);
    }
    return tex_;
}

}  // namespace impactlab::gui
