// The rig, animated and drawn to scale (top view, metres) with the shaders of shaders/: rail, cart, the two
// coil springs, the repelling magnets with their field lines, the bumper at xI glowing with the contact
// force, the spinning unbalance disc. Rendered into its own framebuffer texture that an ImGui window
// shows; labels are added on top with ImDrawList. Main (GL) thread only.
#pragma once

#include <GL/gl.h>
#include <GL/glext.h>
#include <imgui.h>

#include <string>
#include <vector>

#include "window/layout.hpp"
#include "render/theme.hpp"

namespace impactlab::gui {

// What the rig shows this frame (from the latest sample and the UI's own parameters).
struct RigState {
    double x = 0, v = 0;          // cart [m], [m/s]
    double phi = 0;               // unbalance angle [rad]
    double phi_span = 0;          // how far phi turned since the last frame [rad] (motion blur)
    double xI = 0;                // bumper [m]
    bool bumper = true;           // false for the impact law "none": no bumper drawn
    double bumper_force = 0;      // [N]
    double flash = 0;             // 0..1: recent impact
    double magnet_force = 0;      // force of the magnets on the cart, along x [N]
    double spring_force = 0;      // force of the springs on the cart [N]
    bool in_contact = false;      // regime II or III, or a compliant bumper pressed
    double magnify = 1.0;         // displacement magnification of the drawing (x and xI about x = 0; layout.hpp)
};

// Geometry of the rig [m] (top view; x along the rail, y across it).
namespace rig {
inline constexpr double kCartHalfW = 0.040, kCartHalfH = 0.036;
inline constexpr double kRailY = 0.027, kRailHalfLen = 0.133;
inline constexpr double kWallX = 0.136;
inline constexpr double kSpringY = 0.017;
inline constexpr double kBumperY = -0.017, kBumperLen = 0.018, kBumperHalfH = 0.0085;
inline constexpr double kMagnetCartY = -0.043, kMagnetFixedY = -0.0655, kMagnetHalf = 0.0075;
inline constexpr double kDiscR = 0.022, kMassOrbit = 0.016;
inline constexpr double kRulerY = 0.047;
}  // namespace rig

class RigView {
public:
    // Compiles the shaders; false with a message if the driver refuses them.
    bool init(std::string& error);
    void shutdown();
    // Lays the rig out for a w x h pixel image and builds its shapes (CPU only: the UI thread, building).
    void prepare(int w, int h, const RigState& s, const Palette& pal);
    // Queues the prepared image in `dl` with its top left at `min` (display pixels): it is rendered there
    // when ImGui's draw data is, in the same pass as the rest of the window (no image of its own to wait for).
    void add_to(ImDrawList* dl, ImVec2 min);
    // Image pixel (top-left origin) of a world point, for the labels drawn over the image.
    ImVec2 to_image(double x, double y) const;
    float px_per_m() const { return px_per_m_; }
    // The magnification of the last render: drawn x = magnify().draw_x(x) (the mouse divides by its gain).
    const RigMagnify& magnify() const { return mag_; }

private:
    struct Shape {
        float p0[2], p1[2], p2[2];
        float shape[4];   // kind, radius, outline, style
        float fill[4];
        float line[4];
    };
    void build(const RigState& s, const Palette& pal);
    void capsule(double ax, double ay, double bx, double by, double r, const float* rgb, float a = 1, int style = 1,
                 double outline = 0, const float* line = nullptr, double glow = 0);
    void box(double cx, double cy, double hx, double hy, double corner, const float* rgb, float a = 1, int style = 0,
             double outline = 0, const float* line = nullptr, double glow = 0);
    // Capsule, box and disc are one instance record; `kind` selects the distance field in rig_shapes.frag.
    void push_shape(int kind, double p0x, double p0y, double p1x, double p1y, double size, const float* rgb, float a,
                    int style, double outline, const float* line, double glow);
    void disc(double cx, double cy, double r, double inner, const float* rgb, float a = 1, int style = 2,
              double outline = 0, const float* line = nullptr, double glow = 0);
    void triangle(double ax, double ay, double bx, double by, double cx, double cy, const float* rgb, float a = 1);
    void spring(double x0, double x1, double y, const Palette& pal);

    GLuint shapes_prog_ = 0, backdrop_prog_ = 0;
    GLuint vao_ = 0, vbo_ = 0, empty_vao_ = 0;
    void render(const ImVec4& clip_rect);   // GL thread, from the draw list's callback
    int fb_w_ = 0, fb_h_ = 0;            // the image's size [framebuffer px]
    ImVec2 at_{};                        // its top left [display px]
    RigState state_{};                   // what prepare() was given
    Palette pal_{};
    // The backdrop's static part (gradient and plate grid), drawn when its view or palette changes and
    // copied into the image each frame: under a software renderer it was a third of the rig's cost.
    GLuint backdrop_fbo_ = 0, backdrop_tex_ = 0, backdrop_img_ = 0;   // drawn into _tex_, shown from _img_
    std::vector<float> backdrop_key_;   // what it was drawn for
    std::vector<float> key_now_;        // what this frame would draw it for
    float px_per_m_ = 1000;
    double cx_ = 0, cy_ = 0;
    RigMagnify mag_;
    std::vector<Shape> shapes_;
    std::size_t static_count_ = 0;   // shapes_[0, static_count_) are the static layer's (walls, rails, ruler, fixed magnet)
    void draw_shapes(std::size_t first, std::size_t count);
    // render()'s pieces: a program with the view's uniforms, a rectangle through the backdrop program, and
    // the backdrop's image (its static part and the static shapes) drawn again when what it shows changed.
    void use_program(GLuint prog) const;
    void quad(double x0, double y0, double x1, double y1) const;
    void update_backdrop(double x_lo, double y_lo, double x_hi, double y_hi);
};

}  // namespace impactlab::gui
