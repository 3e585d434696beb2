// The raster side of the plotting layer: dense curves and markers are drawn on the CPU into an RGBA canvas
// the size of the plot's data area (antialiased by distance to each segment, one layer per colour, layers
// composited "over"), uploaded as one texture and shown with one ImDrawList image. The cost grows with the
// pixels touched, not with the primitives, which keeps 100,000-point plots cheap even on Mesa's software
// rasterizer (where every GPU triangle costs set-up time). Main (GL) thread only.
#pragma once

#include <imgui.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace impactlab::gui {

class RasterCanvas {
public:
    RasterCanvas() = default;
    ~RasterCanvas();
    RasterCanvas(const RasterCanvas&) = delete;
    RasterCanvas& operator=(const RasterCanvas&) = delete;

    // Starts a frame over the area [min, max) (display pixels); clears to transparent.
    void begin(ImVec2 min, ImVec2 max);
    bool active() const { return active_; }
    // A layer of one colour: segments and dots combine by maximum opacity (no dark joints), then the layer
    // is composited over what is below when the next layer starts or the canvas ends.
    void layer(ImU32 color);
    // Segment a-b (display pixels) `width` px wide with opacities at its ends (linearly interpolated).
    void segment(ImVec2 a, ImVec2 b, float width, float alpha_a, float alpha_b);
    void dot(ImVec2 c, float diameter, float alpha = 1.0f);
    // The texture that will hold the canvas (valid after begin(); filled by finish()).
    unsigned texture() const { return tex_; }
    // Uploads the canvas into texture().
    unsigned finish();

private:
    void flatten_layer();
    bool active_ = false;
    int x0_ = 0, y0_ = 0, w_ = 0, h_ = 0;
    std::vector<std::uint8_t> cover_;   // current layer's opacity (max-combined)
    int lx0_ = 0, ly0_ = 0, lx1_ = -1, ly1_ = -1;   // dirty rectangle of the current layer
    ImVec4 color_{};
    bool layer_open_ = false;
    std::vector<float> rgba_;           // premultiplied, composited layers
    std::vector<std::uint8_t> out_;
    unsigned tex_ = 0;
    int tex_w_ = 0, tex_h_ = 0;
    bool drawn_ = false;
};

}  // namespace impactlab::gui
