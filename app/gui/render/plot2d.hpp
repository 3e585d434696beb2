// A small 2-D plotting layer on ImDrawList (ImPlot is not in Debian): a frame with axes, nice ticks and
// labels, a clipped data area, and four primitives that bound their draw cost by the pixels they cover,
// not by the number of points:
//   series  - y(x) with x increasing: per-pixel-column decimation (first, min, max, last in each column);
//   path    - a general curve (phase portraits): points closer than ~0.7 px to the last one are skipped,
//             with an optional fade from old (transparent) to new (opaque);
//   trail   - a fading path over a sliding window of a History, kept between frames (draws only the new);
//   scatter - dots: one per covered pixel (a bitmap of the area, cleared per call).
// Every plot zooms and pans with the mouse (wheel: zoom about the pointer, Shift + wheel: x only, Ctrl +
// wheel: y only; drag: pan; double-click: back to the caller's auto-fit); the view is kept per plot id.
// By default the decimated curves and dots are rasterized on the CPU into one texture per plot
// (plot_raster); the other backends send them to the GPU (plot_gpu: one instanced draw per call) or to
// ImDrawList polylines and rectangles.
// UI thread only.
#pragma once

#include <imgui.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "render/gl_util.hpp"
#include "render/plot_gpu.hpp"
#include "render/plot_raster.hpp"

namespace impactlab::gui {

struct Range {
    double lo = 0, hi = 1;
    double span() const { return hi - lo; }
    bool valid() const { return hi > lo; }
};

// An axis range that follows its data smoothly (grows fast, shrinks slowly), so auto-fit never jitters.
struct AutoRange {
    Range cur;
    bool init = false;
    bool shrinking_lo = false, shrinking_hi = false;
    // target: the data's extent; pad: fraction of span added either side; min_span: the smallest span.
    void track(Range target, double pad, double min_span, double dt_s);
    void snap(Range target, double pad, double min_span);
};

// How dense curves and markers are drawn (the axes, text and overlays always use ImDrawList):
//   Raster   - on the CPU into one texture per plot (default: cheapest on software OpenGL);
//   Gpu      - instanced antialiased quads from plot_gpu's shaders (cheapest on a real GPU);
//   DrawList - ImGui's own polylines (the reference).
enum class PlotBackend { Raster, Gpu, DrawList };
void set_plot_backend(PlotBackend b);
PlotBackend plot_backend();
// Frees the raster canvases' textures (before the GL context goes).
void release_plot_canvases();

// Plot backgrounds as scissored clears instead of blended rectangles (a clear is nearly free under Mesa's
// llvmpipe, a blended rectangle is not). Only for plots that nothing is drawn under and that no window
// covers from below: the app turns it on while it draws its tiles. UI thread only.
struct PlotBackdrop {
    ImVec2 min, max;
    ImU32 color;
};
void set_plot_backdrops_by_clear(bool on);
// The backdrops recorded since the last call; the caller clears them before ImGui renders the frame.
std::vector<PlotBackdrop> take_plot_backdrops();

struct Axes {
    const char* x_label = "";
    const char* y_label = "";
    const char* y_label_short = nullptr;   // drawn instead where y_label is longer than the plot is high
    double x_scale = 1, y_scale = 1;   // data units -> tick label units (e.g. 1e3 for m -> mm)
};

class Plot {
public:
    // Sets the user's view of plot `id` in the current window, as a zoom with the mouse would (scripted
    // views: --bif-zoom). UI thread, inside the plot's window, before its begin().
    static void set_user_view(const char* id, Range x, Range y);
    // Gives plot `id` back to the caller's ranges, as a double-click does (a plot that follows another's
    // zoom hands the user's change over and drops its own). Same thread and window as set_user_view.
    static void clear_user_view(const char* id);
    // Session files: the views the user zoomed or panned, by plot id ("##phase"); and views to put back,
    // each applied when its plot next begins (all others go back to the caller's ranges). UI thread.
    struct NamedView {
        std::string id;
        Range x, y;
    };
    static std::vector<NamedView> user_views();
    static void restore_user_views(const std::vector<NamedView>& views);
    // Lays the plot out at the cursor (an InvisibleButton of `size` takes the mouse). Returns false if the
    // plot is too small to draw (nothing to end() then).
    bool begin(const char* id, ImVec2 size, Range x, Range y, const Axes& axes);
    void end();   // pops the clip rect

    ImVec2 to_px(double x, double y) const {
        return ImVec2(static_cast<float>(ax_ + bx_ * x), static_cast<float>(ay_ + by_ * y));
    }
    double x_at(float px) const { return (px - ax_) / bx_; }
    double y_at(float py) const { return (py - ay_) / by_; }
    ImDrawList* draw() const { return dl_; }
    ImVec2 area_min() const { return min_; }
    ImVec2 area_max() const { return max_; }
    // The top of the x label's row, below the tick labels (a note beside the label goes there too).
    float label_row_y() const { return max_.y + ImGui::GetFontSize() * 1.25f; }
    bool hovered() const { return hovered_; }
    bool clicked() const { return clicked_; }   // left click released on the data area
    bool dragging() const { return dragging_; }
    bool zoomed() const { return zoomed_; }       // the user's zoom or pan replaces the caller's ranges
    Range x_range() const { return x_; }
    Range y_range() const { return y_; }

    // Points are fetched by get(i) -> ImPlotPoint-like {double x, y} for i in [0, n).
    template <class Get>
    void series(std::size_t n, Get&& get, ImU32 color, float thickness = 1.5f);
    template <class Get>
    void path(std::size_t n, Get&& get, ImU32 color, float thickness = 1.5f, bool fade = false);
    template <class Get>
    void scatter(std::size_t n, Get&& get, ImU32 color, float size = 2.0f);
    // While on, scatter() calls share one covered-pixel bitmap: a pixel drawn by an earlier call is not
    // drawn again by a later one (draw the newest layer first). Layers of one point set then cost what
    // one call costs, not one each.
    void share_dots(bool on);
    // A fading trail of the history samples [0, n) whose sequence numbers start at seq0 (History::seq_of)
    // in history `generation`: like path(..., fade = true), but kept between frames (TrailCanvas), so a
    // frame only draws what is new. Raster backend only; the others fall back to path().
    template <class Get>
    void trail(std::size_t n, std::uint64_t seq0, std::uint64_t generation, Get&& get, ImU32 color,
               float thickness = 1.5f);

    // An image of the data area's size (w x h pixels, rows top-down, straight alpha) over what is drawn,
    // at `alpha` times its opacity: composited into the plot's image (raster backend), else texture `tex`.
    void image(const std::uint8_t* rgba, int w, int h, GLuint tex, float alpha = 1.0f);
    // Dots of `diameter` at display-pixel positions, all of them (no per-pixel thinning: for a few markers).
    void dots(const ImVec2* at, std::size_t n, ImU32 color, float diameter);
    void vline(double x, ImU32 color, float thickness = 1.0f, bool dashed = false);
    void hline(double y, ImU32 color, float thickness = 1.0f, bool dashed = false);
    void text(double x, double y, const char* s, ImU32 color, ImVec2 align = ImVec2(0, 0));
    // Fills the part of the area with x > x0 (a forbidden region), hatched.
    void shade_right_of(double x0, ImU32 color);

    // Up to this many markers, scatter() draws them with ImDrawList (not with the raster backend, whose
    // plots are one opaque image that dots cost nothing to join).
    static constexpr std::size_t kFewDots = 256;

    // Statistics of the last frame (benchmark)
    static std::size_t emitted_vertices();
    static void reset_stats();

private:
    void zoom_and_pan();   // the mouse's zoom and pan; replaces x_, y_ with the user's view
    void flush(std::vector<ImVec2>& pts, ImU32 color, float thickness);
    void flush_gpu(ImU32 color, float thickness);
    void flush_raster(ImU32 color, float thickness);
public:
    // A canvas and its texture, kept per plot between frames (plot2d.cpp).
    struct CanvasSlot {
        RasterCanvas canvas;
        CanvasTexture tex;
    };
    struct TrailSlot {
        TrailCanvas trail;
    };

private:
    RasterCanvas* canvas();   // the plot's canvas (raster backend: begun by begin())
    TrailSlot* trail_slot();
    // The raster backend's plots are one opaque image (backdrop, grid and data composited on the CPU,
    // drawn without blending: opaque_image.hpp), begun by begin(); ImDrawList draws over it.
    bool opaque_ = false;
    PlotMapping mapping() const { return {ax_, bx_, ay_, by_}; }
    CanvasSlot* canvas_ = nullptr;
    ImGuiID id_ = 0;
    const char* name_ = "";   // the id as given to begin() (session files)
    ImDrawList* dl_ = nullptr;
    ImVec2 min_, max_;
    Range x_, y_;
    double ax_ = 0, bx_ = 1, ay_ = 0, by_ = 1;
    bool hovered_ = false, clicked_ = false, dragging_ = false, zoomed_ = false;
    std::vector<ImVec2> buf_;
    struct ColumnSpan {
        float x, lo, hi, last;   // the column's centre, the screen y of its top (lo), bottom (hi) and last point
    };
    std::vector<ColumnSpan> spans_;
    std::vector<plot_gpu::Vtx> gbuf_;
    std::vector<std::uint64_t> bitmap_;
    bool shared_dots_ = false;
};

// Points handed to the renderer this frame (benchmark statistics).
std::size_t& g_stat_points();

// ---- templates -------------------------------------------------------------------------------------

template <class Get>
void Plot::series(std::size_t n, Get&& get, ImU32 color, float thickness) {
    if (n == 0) return;
    buf_.clear();
    // Per pixel column: keep first, min, max, last (M4 decimation): exact extremes, O(columns) vertices.
    constexpr int kNone = std::numeric_limits<int>::min();
    int col = kNone;
    ImVec2 first{}, lo{}, hi{}, last{};
    spans_.clear();
    auto emit = [&] {
        spans_.push_back({std::floor(first.x) + 0.5f, lo.y, hi.y, last.y});
        buf_.push_back(first);
        if (lo.y != first.y && lo.y != last.y) buf_.push_back(lo);
        if (hi.y != first.y && hi.y != last.y) buf_.push_back(hi);
        if (last.x != first.x || last.y != first.y) buf_.push_back(last);
    };
    for (std::size_t i = 0; i < n; ++i) {
        const auto p = get(i);
        const ImVec2 q = to_px(p.x, p.y);
        const int c = static_cast<int>(q.x);
        if (c != col) {
            if (col != kNone) emit();
            col = c;
            first = lo = hi = last = q;
        } else {
            if (q.y < lo.y) lo = q;
            if (q.y > hi.y) hi = q;
            last = q;
        }
    }
    emit();
    if (plot_backend() == PlotBackend::DrawList || (plot_backend() == PlotBackend::Gpu && !plot_gpu::ready())) {
        flush(buf_, color, thickness);
        return;
    }
    if (plot_backend() == PlotBackend::Raster && n >= 16 * spans_.size()) {
        // Dense (16+ samples per pixel column, where a slope is no longer seen as one): the curve is a
        // vertical bar per column from its lowest to its highest point (joined to the column before),
        // drawn as such rather than as the segments.
        RasterCanvas* cv = canvas();
        cv->layer(color);
        float prev_last = 0.0f;
        bool have_prev = false;
        for (const ColumnSpan& c : spans_) {
            const float lo_y = have_prev ? std::min(c.lo, prev_last) : c.lo;
            const float hi_y = have_prev ? std::max(c.hi, prev_last) : c.hi;
            cv->vspan(c.x, lo_y, hi_y, thickness);
            prev_last = c.last;
            have_prev = true;
        }
        g_stat_points() += spans_.size();
        return;
    }
    gbuf_.clear();
    for (const ImVec2& q : buf_) gbuf_.push_back({q.x, q.y, 1.0f, 0.0f});
    if (plot_backend() == PlotBackend::Gpu) flush_gpu(color, thickness);
    else flush_raster(color, thickness);
}

template <class Get>
void Plot::path(std::size_t n, Get&& get, ImU32 color, float thickness, bool fade) {
    if (n < 2) return;
    if (plot_backend() == PlotBackend::Raster || (plot_backend() == PlotBackend::Gpu && plot_gpu::ready())) {
        // One instanced draw (or one raster layer); the fade is a per-point opacity, old to new.
        // Steps under 1.5 px add nothing visible to a 1.6 px line: the raster skips them.
        const float min_step2 = plot_backend() == PlotBackend::Raster ? 2.25f : 0.5f;
        gbuf_.clear();
        const float inv = 1.0f / static_cast<float>(n);
        ImVec2 prev = to_px(get(0).x, get(0).y);
        gbuf_.push_back({prev.x, prev.y, fade ? inv * inv : 1.0f, 0.0f});
        for (std::size_t i = 1; i < n; ++i) {
            const auto p = get(i);
            const ImVec2 q = to_px(p.x, p.y);
            const float dx = q.x - prev.x, dy = q.y - prev.y;
            if (dx * dx + dy * dy < min_step2 && i + 1 != n) continue;
            const float f = static_cast<float>(i + 1) * inv;
            gbuf_.push_back({q.x, q.y, fade ? f * f : 1.0f, 0.0f});
            prev = q;
        }
        if (plot_backend() == PlotBackend::Gpu) flush_gpu(color, thickness);
        else flush_raster(color, thickness);
        return;
    }
    // Fading: the curve is split into kBands runs of rising opacity (one AddPolyline each).
    constexpr int kBands = 24;
    const int bands = fade ? kBands : 1;
    const ImVec4 base = ImGui::ColorConvertU32ToFloat4(color);
    std::size_t start = 0;
    for (int b = 0; b < bands; ++b) {
        const std::size_t stop = (b + 1 == bands) ? n : n * static_cast<std::size_t>(b + 1) / static_cast<std::size_t>(bands);
        if (stop <= start) continue;
        buf_.clear();
        ImVec2 prev = to_px(get(start).x, get(start).y);
        buf_.push_back(prev);
        for (std::size_t i = start + 1; i < stop; ++i) {
            const auto p = get(i);
            const ImVec2 q = to_px(p.x, p.y);
            const float dx = q.x - prev.x, dy = q.y - prev.y;
            if (dx * dx + dy * dy < 0.5f && i + 1 != stop) continue;
            buf_.push_back(q);
            prev = q;
        }
        ImVec4 c = base;
        if (fade) {
            const float f = static_cast<float>(b + 1) / static_cast<float>(bands);
            c.w *= f * f;
        }
        flush(buf_, ImGui::ColorConvertFloat4ToU32(c), thickness);
        start = stop - 1;   // bands share their end point: no gaps
    }
}

template <class Get>
void Plot::trail(std::size_t n, std::uint64_t seq0, std::uint64_t generation, Get&& get, ImU32 color,
                 float thickness) {
    if (n < 2) return;
    if (plot_backend() != PlotBackend::Raster) {
        path(n, get, color, thickness, true);
        return;
    }
    TrailSlot* slot = trail_slot();
    TrailCanvas* tc = &slot->trail;
    TrailCanvas::Frame f;
    f.min = {min_.x, min_.y};
    f.max = {max_.x, max_.y};
    f.map = mapping();
    f.generation = generation;
    f.first_seq = seq0;
    f.last_seq = seq0 + n - 1;
    f.color = color;
    f.thickness = thickness;
    const std::size_t from = tc->begin(f);
    for (std::size_t i = from; i < n; ++i) {
        const auto p = get(i);
        tc->feed(seq0 + i, p.x, p.y);
    }
    g_stat_points() += n - from;
    tc->finish();
    canvas()->blend_image(tc->rgba(), tc->width(), tc->height());
}

template <class Get>
void Plot::scatter(std::size_t n, Get&& get, ImU32 color, float size) {
    if (n == 0) return;
    if (n <= kFewDots && !opaque_) {
        // A few markers: ImDrawList circles cost less than a canvas the size of the plot.
        for (std::size_t i = 0; i < n; ++i) {
            const auto p = get(i);
            dl_->AddCircleFilled(to_px(p.x, p.y), 0.5f * size, color, 10);
        }
        return;
    }
    const int w = static_cast<int>(max_.x - min_.x) + 1, h = static_cast<int>(max_.y - min_.y) + 1;
    if (w <= 0 || h <= 0) return;
    const std::size_t bits = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    if (!shared_dots_ || bitmap_.size() != (bits + 63) / 64) bitmap_.assign((bits + 63) / 64, 0);
    const float r = 0.5f * size;
    const bool gpu = plot_backend() == PlotBackend::Gpu && plot_gpu::ready();
    RasterCanvas* cv = plot_backend() == PlotBackend::Raster ? canvas() : nullptr;
    if (cv) cv->layer(color);
    gbuf_.clear();
    for (std::size_t i = 0; i < n; ++i) {
        const auto p = get(i);
        const ImVec2 q = to_px(p.x, p.y);
        const int ix = static_cast<int>(q.x - min_.x), iy = static_cast<int>(q.y - min_.y);
        if (ix < 0 || iy < 0 || ix >= w || iy >= h) continue;
        const std::size_t k = static_cast<std::size_t>(iy) * static_cast<std::size_t>(w) + static_cast<std::size_t>(ix);
        std::uint64_t& word = bitmap_[k >> 6];
        const std::uint64_t bit = std::uint64_t{1} << (k & 63);
        if (word & bit) continue;
        word |= bit;
        if (cv) cv->dot({q.x, q.y}, size);
        else if (gpu) gbuf_.push_back({q.x, q.y, 1.0f, 0.0f});
        else dl_->AddRectFilled(ImVec2(q.x - r, q.y - r), ImVec2(q.x + r, q.y + r), color);
    }
    if (gpu) {
        plot_gpu::add_points(dl_, gbuf_.data(), gbuf_.size(), color, size);
        g_stat_points() += gbuf_.size();
    }
    if (cv) g_stat_points() += n;
}

}  // namespace impactlab::gui
