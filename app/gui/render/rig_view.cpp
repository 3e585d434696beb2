#include "rig_view.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "embedded_shaders.hpp"
#include "render/gl_util.hpp"
#include "render/opaque_image.hpp"

namespace impactlab::gui {

using namespace rig;

static_assert(RigMagnify::kWallX == kWallX && RigMagnify::kCartHalfW == kCartHalfW, "layout.hpp's copy of the rig");

namespace {
// The view and the base plate reach past the end walls (which move out with a large magnification).
constexpr double kViewMargin = 0.014, kPlateMargin = 0.010, kViewTop = 0.061, kViewBottom = -0.081;
constexpr double kPlateY0 = -0.078, kPlateY1 = 0.058;

const float kWhite[3] = {1, 1, 1};
const float kBlack[3] = {0, 0, 0};
const float kDark[3] = {0.10f, 0.11f, 0.13f};
const float kRubber[3] = {0.16f, 0.16f, 0.17f};
const float kBrass[3] = {0.78f, 0.62f, 0.30f};

void mix3(const float* a, const float* b, float t, float* out) {
    for (int i = 0; i < 3; ++i) out[i] = a[i] + (b[i] - a[i]) * t;
}
}  // namespace

bool RigView::init(std::string& error) {
    shapes_prog_ = build_program(shaders::rig_shapes_vert, shaders::rig_shapes_frag, "rig_shapes", error);
    if (!shapes_prog_) return false;
    backdrop_prog_ = build_program(shaders::rig_backdrop_vert, shaders::rig_backdrop_frag, "rig_backdrop", error);
    if (!backdrop_prog_) return false;

    glGenVertexArrays(1, &vao_);
    glGenBuffers(1, &vbo_);
    glGenVertexArrays(1, &empty_vao_);
    return true;
}

void RigView::draw_shapes(std::size_t first, std::size_t count) {
    if (count == 0) return;
    // GL 3.3 has no base instance: the attributes point at the range's first record.
    glBindVertexArray(vao_);
    glBindBuffer(GL_ARRAY_BUFFER, vbo_);
    const GLsizei stride = sizeof(Shape);
    auto attrib = [&](GLuint loc, GLint n, std::size_t offset) {
        glEnableVertexAttribArray(loc);
        glVertexAttribPointer(loc, n, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(first * sizeof(Shape) + offset));
        glVertexAttribDivisor(loc, 1);
    };
    attrib(0, 2, offsetof(Shape, p0));
    attrib(1, 2, offsetof(Shape, p1));
    attrib(2, 2, offsetof(Shape, p2));
    attrib(3, 4, offsetof(Shape, shape));
    attrib(4, 4, offsetof(Shape, fill));
    attrib(5, 4, offsetof(Shape, line));
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(count));
}

void RigView::shutdown() {
    if (backdrop_tex_) glDeleteTextures(1, &backdrop_tex_);
    if (backdrop_img_) glDeleteTextures(1, &backdrop_img_);
    backdrop_img_ = 0;
    if (backdrop_fbo_) glDeleteFramebuffers(1, &backdrop_fbo_);
    backdrop_tex_ = backdrop_fbo_ = 0;
    backdrop_key_.clear();
    if (vbo_) glDeleteBuffers(1, &vbo_);
    if (vao_) glDeleteVertexArrays(1, &vao_);
    if (empty_vao_) glDeleteVertexArrays(1, &empty_vao_);
    if (shapes_prog_) glDeleteProgram(shapes_prog_);
    if (backdrop_prog_) glDeleteProgram(backdrop_prog_);
    vbo_ = vao_ = empty_vao_ = shapes_prog_ = backdrop_prog_ = 0;
}

ImVec2 RigView::to_image(double x, double y) const {
    return ImVec2(static_cast<float>(0.5 * fb_w_ + (x - cx_) * px_per_m_),
                  static_cast<float>(0.5 * fb_h_ - (y - cy_) * px_per_m_));
}

void RigView::push_shape(int kind, double p0x, double p0y, double p1x, double p1y, double size, const float* rgb,
                         float a, int style, double outline, const float* line, double glow) {
    Shape s{};
    s.p0[0] = static_cast<float>(p0x);
    s.p0[1] = static_cast<float>(p0y);
    s.p1[0] = static_cast<float>(p1x);
    s.p1[1] = static_cast<float>(p1y);
    s.p2[0] = static_cast<float>(glow);
    s.shape[0] = static_cast<float>(kind);
    s.shape[1] = static_cast<float>(size);
    s.shape[2] = static_cast<float>(outline);
    s.shape[3] = static_cast<float>(style);
    for (int i = 0; i < 3; ++i) s.fill[i] = rgb[i];
    s.fill[3] = a;
    const float* l = line ? line : kBlack;
    for (int i = 0; i < 3; ++i) s.line[i] = l[i];
    s.line[3] = 1;
    shapes_.push_back(s);
}

void RigView::capsule(double ax, double ay, double bx, double by, double r, const float* rgb, float a, int style,
                      double outline, const float* line, double glow) {
    push_shape(0, ax, ay, bx, by, r, rgb, a, style, outline, line, glow);
}

void RigView::box(double cx, double cy, double hx, double hy, double corner, const float* rgb, float a, int style,
                  double outline, const float* line, double glow) {
    push_shape(1, cx, cy, hx, hy, corner, rgb, a, style, outline, line, glow);
}

void RigView::disc(double cx, double cy, double r, double inner, const float* rgb, float a, int style, double outline,
                   const float* line, double glow) {
    push_shape(2, cx, cy, inner, 0.0, r, rgb, a, style, outline, line, glow);
}

void RigView::triangle(double ax, double ay, double bx, double by, double cx, double cy, const float* rgb, float a) {
    Shape s{};
    s.p0[0] = static_cast<float>(ax);
    s.p0[1] = static_cast<float>(ay);
    s.p1[0] = static_cast<float>(bx);
    s.p1[1] = static_cast<float>(by);
    s.p2[0] = static_cast<float>(cx);
    s.p2[1] = static_cast<float>(cy);
    s.shape[0] = 3;
    for (int i = 0; i < 3; ++i) s.fill[i] = rgb[i];
    s.fill[3] = a;
    shapes_.push_back(s);
}

void RigView::spring(double x0, double x1, double y, const Palette& pal) {
    // A helix seen from above: back half-turns dark, front half-turns bright; the pitch follows the length.
    constexpr int kCoils = 9;
    constexpr double kAmp = 0.0068, kWire = 0.00115, kLead = 0.005;
    const double a = x0 + kLead, b = x1 - kLead;
    const double pitch = (b - a) / kCoils;
    capsule(x0, y, a, y - kAmp, kWire, pal.spring, 1, 1);
    for (int i = 0; i < kCoils; ++i) {
        const double s = a + pitch * i;
        capsule(s + 0.5 * pitch, y + kAmp, s + pitch, y - kAmp, kWire * 0.85, pal.spring_back, 1, 0);
    }
    for (int i = 0; i < kCoils; ++i) {
        const double s = a + pitch * i;
        capsule(s, y - kAmp, s + 0.5 * pitch, y + kAmp, kWire, pal.spring, 1, 1);
    }
    capsule(b, y - kAmp, x1, y, kWire, pal.spring, 1, 1);
}

void RigView::build(const RigState& st, const Palette& pal) {
    shapes_.clear();
    // Displacements are drawn magnified about x = 0 (cart and bumper alike: a contact stays a contact).
    const double x = mag_.draw_x(st.x);
    const double wall_x = mag_.wall_x(), wall_in = wall_x - 0.004, rail_half = wall_x - 0.003;
    const double gain = mag_.gain;

    // Frame: the two end blocks (hatched: fixed to the ground) and the rails.
    float hatch[3];
    mix3(pal.wall, kBlack, 0.45f, hatch);
    box(-wall_x - 0.005, -0.010, 0.008, 0.055, 0.002, pal.wall, 1, 4, 0, hatch);
    box(wall_x + 0.005, -0.010, 0.008, 0.055, 0.002, pal.wall, 1, 4, 0, hatch);
    for (double ry : {kRailY, -kRailY}) {
        capsule(-rail_half, ry, rail_half, ry, 0.0034, pal.rail, 1, 1);
        for (double bx : {-rail_half + 0.006, rail_half - 0.006}) disc(bx, ry, 0.0022, 0, kDark, 1, 0);
    }

    // Ruler fixed to the frame, with the cart's pointer (numbers are drawn over the image).
    float tick[3];
    mix3(pal.rig_grid, pal.text, 0.5f, tick);
    // Its millimetres are magnified with the displacement: the pointer reads the true x.
    capsule(-0.025 * gain, kRulerY, 0.025 * gain, kRulerY, 0.0004, tick, 0.9f, 0);
    for (int mm = -25; mm <= 25; ++mm) {
        const double len = (mm % 10 == 0) ? 0.0050 : (mm % 5 == 0) ? 0.0034 : 0.0020;
        const double xx = mm * 1e-3 * gain;
        capsule(xx, kRulerY, xx, kRulerY + len, mm % 10 == 0 ? 0.00032 : 0.00020, tick, 0.9f, 0);
    }

    // Fixed magnet on its bracket under the rail, at x = 0.
    box(0.0, kMagnetFixedY - 0.0095, 0.016, 0.0028, 0.001, pal.wall, 1, 4, 0, hatch);
    box(0.0, kMagnetFixedY + 0.5 * kMagnetHalf, kMagnetHalf, 0.5 * kMagnetHalf, 0.0008, pal.magnet_n, 1, 1);
    box(0.0, kMagnetFixedY - 0.5 * kMagnetHalf, kMagnetHalf, 0.5 * kMagnetHalf, 0.0008, pal.magnet_s, 1, 1);

    // Everything above depends only on the view (magnification, palette): the static layer (render()).
    static_count_ = shapes_.size();

    // Bumper: a block on a threaded rod from the right end, rubber face at the contact plane xI + half cart.
    if (st.bumper) {
        const double face = mag_.bumper_face(st.xI);
        const double F = std::max(0.0, st.bumper_force);
        const double heat = std::clamp(std::max(st.flash, std::log10(1.0 + F) / 2.2), 0.0, 1.0);   // 1 at ~160 N
        capsule(face + kBumperLen, kBumperY, wall_in, kBumperY, 0.0028, kBrass, 1, 1);
        for (int i = 0; i < 2; ++i) {   // lock nuts
            const double nx = face + kBumperLen + 0.006 + 0.006 * i;
            box(nx, kBumperY, 0.0022, 0.0052, 0.0006, pal.rail, 1, 1, 0.0004, kDark);
        }
        box(face + 0.5 * kBumperLen + 0.002, kBumperY, 0.5 * kBumperLen - 0.002, kBumperHalfH, 0.0015, pal.bumper_body, 1, 1,
            0.0006, kDark);
        float pad[3];
        mix3(kRubber, pal.hot, static_cast<float>(heat), pad);
        if (heat > 0.02) {
            float glow[3];
            mix3(pal.hot, kWhite, static_cast<float>(0.4 * heat), glow);
            box(face + 0.002, kBumperY, 0.002, kBumperHalfH, 0.0012, glow, static_cast<float>(std::min(1.0, 0.35 + heat)), 3, 0,
                nullptr, 0.005 + 0.016 * heat);
        }
        box(face + 0.002, kBumperY, 0.002, kBumperHalfH, 0.0012, pad, 1, 0, 0.0005, kDark);
    }

    // Springs from the end blocks to the cart's ends.
    spring(-wall_in, x - kCartHalfW, kSpringY, pal);
    spring(x + kCartHalfW, wall_in, kSpringY, pal);

    // Cart: body with wheels over the rails, the moving magnet under it (N facing the fixed N).
    float body_edge[3];
    mix3(pal.cart, kBlack, 0.55f, body_edge);
    for (double wy : {kRailY, -kRailY})
        for (double wx : {-0.026, 0.026}) box(x + wx, wy, 0.0070, 0.0045, 0.002, kDark, 1, 1);
    box(x, 0.0, kCartHalfW, kCartHalfH, 0.004, pal.cart, 1, 2, 0.0012, body_edge);
    box(x, kMagnetCartY + 0.0015 - 0.5 * kMagnetHalf, kMagnetHalf, 0.5 * kMagnetHalf, 0.0008, pal.magnet_n, 1, 1);
    box(x, kMagnetCartY + 0.0015 + 0.5 * kMagnetHalf, kMagnetHalf, 0.5 * kMagnetHalf, 0.0008, pal.magnet_s, 1, 1);
    // Cart contact plate on the bumper side, and the hook plates of the springs.
    box(x + kCartHalfW - 0.0015, kBumperY, 0.0015, kBumperHalfH * 0.8, 0.0005, pal.rail, 1, 1);
    box(x - kCartHalfW + 0.0015, kSpringY, 0.0015, 0.004, 0.0005, pal.rail, 1, 1);
    box(x + kCartHalfW - 0.0015, kSpringY, 0.0015, 0.004, 0.0005, pal.rail, 1, 1);

    // Magnetic force on the cart: an arrow at its magnet (0.9 mm per newton, capped).
    if (std::abs(st.magnet_force) > 0.05) {
        const double L = std::clamp(st.magnet_force * 0.0009, -0.03, 0.03);
        const double y = kMagnetCartY - 0.0005;
        const double x0 = x + (L > 0 ? kMagnetHalf : -kMagnetHalf);
        const double x1 = x0 + L;
        const double head = std::min(0.0045, std::abs(L));
        const double dir = L > 0 ? 1.0 : -1.0;
        capsule(x0, y, x1 - dir * head * 0.8, y, 0.0009, pal.field, 0.95f, 0);
        triangle(x1, y, x1 - dir * head, y + 0.0028, x1 - dir * head, y - 0.0028, pal.field, 0.95f);
    }

    // Unbalance: the motor's disc spinning on the cart, its eccentric mass at angle phi; x-offset e*sin(phi)
    // (the forcing m0e phi'^2 sin(phi) points along the mass's arm).
    const double dcx = x - 0.004, dcy = 0.002;
    float disc_col[3], disc_dark[3];
    mix3(pal.disc, kBlack, 0.25f, disc_col);
    mix3(pal.disc, kBlack, 0.65f, disc_dark);
    disc(dcx, dcy, kDiscR + 0.0015, 0, kDark, 0.6f, 0);
    disc(dcx, dcy, kDiscR, 0, disc_col, 1, 2, 0.0008, disc_dark);
    // Motion blur: when the disc turns a lot between two frames, ghosts along the arc; a full turn or more
    // per frame shows as a blurred ring, as a camera would see it.
    constexpr double kTurn = 2.0 * 3.14159265358979;
    if (std::abs(st.phi_span) >= kTurn)
        disc(dcx, dcy, kMassOrbit + 0.0055, kMassOrbit - 0.0055, pal.mass, 0.28f, 0);
    const double span = std::abs(st.phi_span) >= kTurn ? 0.0 : std::abs(st.phi_span);
    const int ghosts = span > 0.35 ? std::min(10, static_cast<int>(span / 0.35)) : 0;
    for (int g = ghosts; g >= 1; --g) {
        const double a = st.phi - span * g / (ghosts + 1);
        const float alpha = static_cast<float>(0.35 * (1.0 - static_cast<double>(g) / (ghosts + 1)));
        capsule(dcx, dcy, dcx + kMassOrbit * std::sin(a), dcy + kMassOrbit * std::cos(a), 0.0016, disc_dark, alpha, 0);
        disc(dcx + kMassOrbit * std::sin(a), dcy + kMassOrbit * std::cos(a), 0.0055, 0, pal.mass, alpha, 0);
    }
    const double mx = dcx + kMassOrbit * std::sin(st.phi), my = dcy + kMassOrbit * std::cos(st.phi);
    capsule(dcx, dcy, mx, my, 0.0018, disc_dark, 1, 1);
    capsule(dcx, dcy, dcx - 0.55 * kMassOrbit * std::sin(st.phi), dcy - 0.55 * kMassOrbit * std::cos(st.phi), 0.0012,
            disc_dark, 1, 1);
    disc(dcx, dcy, 0.0042, 0, pal.rail, 1, 2, 0.0006, kDark);
    disc(mx, my, 0.0058, 0, pal.mass, 1, 2, 0.0006, kDark);

    // The ruler's pointer on the cart's centre line.
    triangle(x, kRulerY - 0.0005, x - 0.0022, kRulerY - 0.0055, x + 0.0022, kRulerY - 0.0055, pal.hot, 1);
    capsule(x, kRulerY - 0.0055, x, kCartHalfH, 0.0004, pal.hot, 0.8f, 0);
}

void RigView::prepare(int w, int h, const RigState& s, const Palette& pal) {
    fb_w_ = std::max(w, 16);
    fb_h_ = std::max(h, 16);
    state_ = s;
    pal_ = pal;
    // Fit the rig (to scale: one zoom for both axes).
    mag_.gain = std::clamp(s.magnify, RigMagnify::kMin, RigMagnify::kMax);
    const double view_half_w = mag_.wall_x() + kViewMargin;
    px_per_m_ = static_cast<float>(std::min(fb_w_ / (2.0 * view_half_w), fb_h_ / (kViewTop - kViewBottom)));
    cx_ = 0.0;
    cy_ = 0.5 * (kViewTop + kViewBottom);
    build(s, pal);
}

void RigView::add_to(ImDrawList* dl, ImVec2 min) {
    at_ = min;
    dl->AddCallback(
        [](const ImDrawList*, const ImDrawCmd* cmd) { static_cast<RigView*>(cmd->UserCallbackData)->render(cmd->ClipRect); }, this);
    dl->AddCallback(ImDrawCallback_ResetRenderState, nullptr);
}

// The uniforms every program of the rig takes: the view's centre, its scale, the image's size.
void RigView::use_program(GLuint prog) const {
    glUseProgram(prog);
    glUniform2f(glGetUniformLocation(prog, "u_center"), static_cast<float>(cx_), static_cast<float>(cy_));
    glUniform1f(glGetUniformLocation(prog, "u_px_per_m"), px_per_m_);
    glUniform2f(glGetUniformLocation(prog, "u_viewport"), static_cast<float>(fb_w_), static_cast<float>(fb_h_));
}

// A rectangle of the drawing [m] through the backdrop program.
void RigView::quad(double x0, double y0, double x1, double y1) const {
    glUniform4f(glGetUniformLocation(backdrop_prog_, "u_quad"), static_cast<float>(x0), static_cast<float>(y0), static_cast<float>(x1),
                static_cast<float>(y1));
    glBindVertexArray(empty_vao_);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
}

// render(): the view spans [x_lo, x_hi] x [y_lo, y_hi] [m].
void RigView::update_backdrop(double x_lo, double y_lo, double x_hi, double y_hi) {
    const int w = fb_w_, h = fb_h_;
    const Palette& pal = pal_;
    const GLuint bp = backdrop_prog_;
    // The backdrop's static part and the static shapes, when what they show has changed (size, zoom,
    // magnification, palette): drawn into their own image, which each frame copies.
    const double plate_x = mag_.wall_x() + kPlateMargin;
    std::vector<float>& key = key_now_;   // kept between frames: no allocation per frame
    key.assign({static_cast<float>(w), static_cast<float>(h), px_per_m_, static_cast<float>(cx_), static_cast<float>(cy_),
                static_cast<float>(plate_x)});
    key.insert(key.end(), pal.bg_top, pal.bg_top + 3);
    key.insert(key.end(), pal.bg_bottom, pal.bg_bottom + 3);
    key.insert(key.end(), pal.rig_grid, pal.rig_grid + 3);
    for (std::size_t i = 0; i < static_count_; ++i) {
        const float* f = reinterpret_cast<const float*>(&shapes_[i]);
        key.insert(key.end(), f, f + sizeof(Shape) / sizeof(float));
    }
    if (key != backdrop_key_) {
        backdrop_key_ = key;
        if (!backdrop_fbo_) glGenFramebuffers(1, &backdrop_fbo_);
        backdrop_tex_ = upload_rgba_texture(backdrop_tex_, w, h, nullptr);
        GLint prev = 0;
        glGetIntegerv(GL_FRAMEBUFFER_BINDING, &prev);
        glBindFramebuffer(GL_FRAMEBUFFER, backdrop_fbo_);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, backdrop_tex_, 0);
        glViewport(0, 0, w, h);
        glDisable(GL_SCISSOR_TEST);
        glDisable(GL_BLEND);
        use_program(bp);
        glUniform1i(glGetUniformLocation(bp, "u_mode"), 0);
        glUniform3fv(glGetUniformLocation(bp, "u_bg_top"), 1, pal.bg_top);
        glUniform3fv(glGetUniformLocation(bp, "u_bg_bottom"), 1, pal.bg_bottom);
        glUniform3fv(glGetUniformLocation(bp, "u_grid"), 1, pal.rig_grid);
        glUniform4f(glGetUniformLocation(bp, "u_plate"), static_cast<float>(-plate_x), static_cast<float>(kPlateY0),
                    static_cast<float>(plate_x), static_cast<float>(kPlateY1));
        glUniform1f(glGetUniformLocation(bp, "u_view_top"), static_cast<float>(y_hi));
        glUniform1f(glGetUniformLocation(bp, "u_view_bottom"), static_cast<float>(y_lo));
        quad(x_lo, y_lo, x_hi, y_hi);
        glEnable(GL_BLEND);
        glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
        use_program(shapes_prog_);
        draw_shapes(0, static_count_);
        // Read back into a plain texture: under llvmpipe, sampling a texture that has been a render target
        // made every frame wait for the renderer (5 ms); an uploaded one does not.
        std::vector<unsigned char> px(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glPixelStorei(GL_PACK_ROW_LENGTH, 0);
        glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
        backdrop_img_ = upload_rgba_texture(backdrop_img_, w, h, px.data());
        glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(prev));
    }
}

void RigView::render(const ImVec4& clip_rect) {
    const ImDrawData* dd = ImGui::GetDrawData();
    if (!dd || !shapes_prog_) return;
    const int w = fb_w_, h = fb_h_;
    const Palette& pal = pal_;
    const RigState& s = state_;
    // Where the image goes, in framebuffer pixels from the lower left, and the clip rectangle likewise.
    const ImVec2 scale = dd->FramebufferScale;
    const float fb_h = dd->DisplaySize.y * scale.y;
    const GLint vx = static_cast<GLint>(std::lround((at_.x - dd->DisplayPos.x) * scale.x));
    const GLint vy = static_cast<GLint>(std::lround(fb_h - (at_.y - dd->DisplayPos.y) * scale.y)) - h;
    const float cx0 = (clip_rect.x - dd->DisplayPos.x) * scale.x, cy0 = (clip_rect.y - dd->DisplayPos.y) * scale.y;
    const float cx1 = (clip_rect.z - dd->DisplayPos.x) * scale.x, cy1 = (clip_rect.w - dd->DisplayPos.y) * scale.y;
    const GLint sx0 = std::max(vx, static_cast<GLint>(cx0)), sx1 = std::min(vx + w, static_cast<GLint>(cx1));
    const GLint sy0 = std::max(vy, static_cast<GLint>(fb_h - cy1)), sy1 = std::min(vy + h, static_cast<GLint>(fb_h - cy0));
    if (sx1 <= sx0 || sy1 <= sy0) return;
    const auto scissor = [&](GLint x0, GLint y0, GLint x1, GLint y1) {   // image pixels, clipped to the clip rectangle
        const GLint a = std::max(sx0, vx + x0), b = std::max(sy0, vy + y0);
        const GLint c = std::min(sx1, vx + x1), d = std::min(sy1, vy + y1);
        glScissor(a, b, std::max(0, c - a), std::max(0, d - b));
    };

    const float view_h = static_cast<float>(h / px_per_m_);
    const float view_w = static_cast<float>(w / px_per_m_);
    const GLuint bp = backdrop_prog_;
    const double x_lo = cx_ - 0.5 * view_w, x_hi = cx_ + 0.5 * view_w, y_lo = cy_ - 0.5 * view_h, y_hi = cy_ + 0.5 * view_h;
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    // The shapes are uploaded now, when the frame before (which drew the last ones) is done.
    glBindBuffer(GL_ARRAY_BUFFER, vbo_);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(shapes_.size() * sizeof(Shape)), shapes_.data(), GL_STREAM_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);

    update_backdrop(x_lo, y_lo, x_hi, y_hi);
    glEnable(GL_SCISSOR_TEST);
    scissor(0, 0, w, h);
    // The copy: one unblended plain texture copy, which the renderer draws at memory speed (a blit between
    // the two formats costs it twice as much). Its rows run bottom-up, as the image was rendered.
    const ImVec2 size(static_cast<float>(w) / scale.x, static_cast<float>(h) / scale.y);
    if (!opaque_image::draw(backdrop_img_, at_, ImVec2(at_.x + size.x, at_.y + size.y), ImVec2(0, 1), ImVec2(1, 0))) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, backdrop_fbo_);
        glBlitFramebuffer(0, 0, w, h, vx, vy, vx + w, vy + h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    }
    glViewport(vx, vy, w, h);

    // The magnets' field lines over it, only in a box round the magnets (they fade out before its edge).
    constexpr double kFieldReach = 0.045;
    const double cart_mx = mag_.draw_x(s.x);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
    use_program(bp);
    glUniform1i(glGetUniformLocation(bp, "u_mode"), 1);
    glUniform3fv(glGetUniformLocation(bp, "u_field"), 1, pal.field);
    glUniform2f(glGetUniformLocation(bp, "u_mag_cart"), static_cast<float>(cart_mx), static_cast<float>(kMagnetCartY));
    glUniform2f(glGetUniformLocation(bp, "u_mag_fixed"), 0.0f, static_cast<float>(kMagnetFixedY));
    glUniform1f(glGetUniformLocation(bp, "u_field_gain"),
                static_cast<float>(std::clamp(std::abs(s.magnet_force) / 8.0, 0.0, 1.0)));
    glUniform1f(glGetUniformLocation(bp, "u_field_reach"), static_cast<float>(kFieldReach));
    const double fx0 = std::max(x_lo, std::min(cart_mx, 0.0) - kFieldReach), fy0 = std::max(y_lo, kMagnetFixedY - kFieldReach);
    const double fx1 = std::min(x_hi, std::max(cart_mx, 0.0) + kFieldReach), fy1 = std::min(y_hi, kMagnetCartY + kFieldReach);
    quad(fx0, fy0, fx1, fy1);
    // The static shapes the lines crossed (the lower rail, the fixed magnet) go back over them, in the box only.
    use_program(shapes_prog_);
    const auto px_x = [&](double x) { return static_cast<GLint>(std::floor(0.5 * w + (x - cx_) * px_per_m_)); };
    const auto px_y = [&](double y) { return static_cast<GLint>(std::floor(0.5 * h + (y - cy_) * px_per_m_)); };
    scissor(px_x(fx0), px_y(fy0), px_x(fx1) + 1, px_y(fy1) + 1);
    draw_shapes(0, static_count_);
    // The moving shapes, premultiplied alpha, in the order built.
    scissor(0, 0, w, h);
    draw_shapes(static_count_, shapes_.size() - static_count_);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glUseProgram(0);
    // ImGui restores its own state (viewport, scissor, blending) with the ResetRenderState after this.
}

}  // namespace impactlab::gui
