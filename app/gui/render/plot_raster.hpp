// The raster side of the plotting layer: dense curves and markers are drawn on the CPU into an RGBA image
// the size of the plot's data area (antialiased by distance to each segment), uploaded as one texture and
// shown as one image. The cost grows with the pixels touched, not with the primitives, which keeps
// 100,000-point plots cheap on Mesa's software rasterizer (where every GPU fragment is CPU time).
//
//   RasterCanvas - redrawn every frame: layers of one colour each (segments and dots combine by maximum
//                  opacity, so no dark joints), composited "over" in 8-bit straight alpha, only over the
//                  pixels drawn. The plots begin it opaque (backdrop and grid included: the whole area is
//                  the image, drawn unblended); begun transparent, only the rectangle drawn is cleared,
//                  uploaded and shown.
//   TrailCanvas  - a fading path kept between frames: each pixel remembers the sequence number of the
//                  newest sample that covered it, so a frame draws only the samples added since the last
//                  one and fades the rest by their age in one pass. A full redraw happens only when the axes
//                  move by half a pixel, the history is cleared or the trail grows backwards.
// CPU only (no GL, no ImGui): plot2d uploads the images (CanvasTexture). The UI thread only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace impactlab::gui {

// A point in display pixels.
struct PxPoint {
    float x = 0, y = 0;
};
// Colours are packed as ImGui's ImU32: R in the lowest byte, then G, B, A.
using PackedColor = std::uint32_t;
inline constexpr unsigned kColorRShift = 0, kColorGShift = 8, kColorBShift = 16, kColorAShift = 24;

// An integer pixel rectangle [x0, x1] x [y0, y1]; empty when x1 < x0.
struct PixelRect {
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
    bool empty() const { return x1 < x0 || y1 < y0; }
    void add(const PixelRect& r);
};

class RasterCanvas {
public:
    // Starts a frame over the area [min, max) (display pixels); clears what the last frame drew.
    void begin(PxPoint min, PxPoint max);
    // Starts a frame over [min, max) filled with the opaque `backdrop`: what is drawn is composited onto it
    // and the whole area is the frame's image (every pixel opaque, so it can be shown without blending).
    void begin_opaque(PxPoint min, PxPoint max, PackedColor backdrop);
    bool opaque() const { return opaque_; }
    bool active() const { return active_; }
    // A layer of one colour: segments and dots combine by maximum opacity (no dark joints), then the layer
    // is composited over what is below when the next layer starts or the canvas ends.
    void layer(PackedColor color);
    // Segment a-b (display pixels) `width` px wide with opacities at its ends (linearly interpolated).
    void segment(PxPoint a, PxPoint b, float width, float alpha_a, float alpha_b);
    void dot(PxPoint c, float diameter, float alpha = 1.0f);
    // A vertical bar over [y0, y1] (display pixels) `width` px wide centred on x, with rounded-off ends:
    // what a dense series draws per pixel column (much cheaper than the segments it stands for).
    void vspan(float x, float y0, float y1, float width);
    // The same across: a horizontal bar over [x0, x1] `width` px high centred on y.
    void hspan(float y, float x0, float x1, float width);
    // The whole pixels of [min, max) (display pixels, rounded to the nearest pixel edges) at opacity alpha.
    void fill_rect(PxPoint min, PxPoint max, float alpha = 1.0f);
    // Composites a straight-alpha image (w x h, rows top-down; at most the canvas's size is used) over what
    // is drawn so far, at `alpha` times its own opacity. Closes the open layer first (draw order).
    void blend_image(const std::uint8_t* rgba, int w, int h, float alpha = 1.0f);
    // Composites the last layer. Returns the pixels drawn this frame (canvas coordinates; empty if nothing
    // was drawn): all that needs uploading and showing.
    PixelRect finish();
    const std::uint8_t* rgba() const { return rgba_.data(); }   // w x h, straight alpha
    int width() const { return w_; }
    int height() const { return h_; }

private:
    void flatten_layer();
    bool active_ = false, opaque_ = false;
    int x0_ = 0, y0_ = 0, w_ = 0, h_ = 0;
    std::vector<std::uint8_t> cover_;   // current layer's opacity (max-combined)
    PixelRect layer_rect_;              // dirty rectangle of the current layer
    PixelRect drawn_;                   // pixels drawn this frame (cleared at the next begin)
    PackedColor color_ = 0;
    bool layer_open_ = false;
    std::vector<std::uint8_t> rgba_;    // straight alpha
};

// Where the data of a plot lands on screen: px = ax + bx * x, py = ay + by * y.
struct PlotMapping {
    double ax = 0, bx = 1, ay = 0, by = 1;
    PxPoint to_px(double x, double y) const {
        return {static_cast<float>(ax + bx * x), static_cast<float>(ay + by * y)};
    }
};

class TrailCanvas {
public:
    // What one frame shows: samples with sequence numbers [first_seq, last_seq] of history `generation`,
    // fading from transparent (oldest) to `color` (newest) with opacity ((seq - first + 1) / n)^2.
    struct Frame {
        PxPoint min, max;          // the plot area (display pixels)
        PlotMapping map;           // data -> display pixels, this frame
        std::uint64_t generation = 0;
        std::uint64_t first_seq = 0, last_seq = 0;
        PackedColor color = 0;
        float thickness = 1.5f;
    };
    // Prepares the frame; returns the index of the first sample to feed (0 after a full redraw) given
    // that the samples of [first_seq, last_seq] are indices [0, last_seq - first_seq].
    std::size_t begin(const Frame& f);
    // Feeds sample `seq` at data point (x, y), in increasing seq order, from the index begin() returned.
    void feed(std::uint64_t seq, double x, double y);
    // Fades the image by age for this frame (shown over the whole area).
    void finish();
    bool full_redraw() const { return full_; }   // the last begin() redrew everything
    const std::uint8_t* rgba() const { return rgba_.data(); }   // w x h, straight alpha
    int width() const { return w_; }
    int height() const { return h_; }

private:
    void segment(PxPoint a, PxPoint b, std::uint32_t stamp);
    bool same_view(const Frame& f) const;
    int x0_ = 0, y0_ = 0, w_ = 0, h_ = 0;
    PlotMapping map_;                       // the mapping the image was drawn with
    PackedColor color_ = 0;
    float thickness_ = 0;
    std::uint64_t generation_ = ~std::uint64_t{0};
    std::uint64_t base_ = 0;                // the oldest sample drawn since the last full redraw; stamps
                                            // are seq - base_ + 1 (0 = never covered)
    std::uint64_t next_seq_ = 0;            // the next sample to draw
    std::uint64_t first_ = 0, last_ = 0;    // this frame's window
    bool have_prev_ = false, full_ = false;
    PxPoint prev_{};                        // the last point drawn (image pixels, the image's mapping)
    std::vector<std::uint32_t> stamp_;
    std::vector<std::uint8_t> cover_;
    std::vector<std::uint8_t> rgba_;
};

}  // namespace impactlab::gui
