#include "plot2d.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <unordered_map>

#include <imgui_internal.h>   // SetItemUsingMouseWheel: the wheel zooms the plot, not the window

#include "render/gl_util.hpp"
#include "impactlab/plot.hpp"
#include "render/opaque_image.hpp"
#include "render/theme.hpp"
#include "views/view_fit.hpp"

namespace impactlab::gui {

namespace {
std::size_t g_vertices = 0;

// The user's view of each plot that has been zoomed or panned (by ImGui id); absent: the caller's ranges.
struct UserView {
    Range x, y;
    std::string name{};   // the plot's id string (session files)
};
std::unordered_map<ImGuiID, UserView> g_user_views;
std::unordered_map<std::string, UserView> g_restored_views;   // from a session, until each plot begins

// Digits after the point for tick labels at this step.
int decimals_for(double step) {
    const int d = static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
    return std::clamp(d, 0, 6);
}

void format_tick(char* buf, std::size_t n, double v, int decimals) {
    if (std::abs(v) < 1e-12) v = 0;   // no "-0"
    std::snprintf(buf, n, "%.*f", decimals, v);
}

// Text rotated 90 degrees counter-clockwise, centred on `center` (the y-axis label).
void add_text_vertical(ImDrawList* dl, ImVec2 center, ImU32 col, const char* text) {
    const ImVec2 ts = ImGui::CalcTextSize(text);
    const int v0 = dl->VtxBuffer.Size;
    // AddText drops glyphs outside the clip rect before we rotate them: lay the text out unclipped.
    dl->PushClipRectFullScreen();
    dl->AddText(ImVec2(center.x - ts.x * 0.5f, center.y - ts.y * 0.5f), col, text);
    dl->PopClipRect();
    for (int i = v0; i < dl->VtxBuffer.Size; ++i) {
        ImVec2& p = dl->VtxBuffer[i].pos;
        const float dx = p.x - center.x, dy = p.y - center.y;
        p = ImVec2(center.x + dy, center.y - dx);
    }
}
}  // namespace

void AutoRange::snap(Range target, double pad, double min_span) {
    init = false;
    track(target, pad, min_span, 0.0);
}

void AutoRange::track(Range t, double pad, double min_span, double dt_s) {
    if (!t.valid()) {
        const double c = 0.5 * (t.lo + t.hi);
        t = {c - 0.5 * min_span, c + 0.5 * min_span};
    }
    double span = std::max(t.span(), min_span);
    const double c = 0.5 * (t.lo + t.hi);
    span *= 1.0 + 2.0 * pad;
    const Range want{c - 0.5 * span, c + 0.5 * span};
    if (!init || !std::isfinite(cur.lo) || !std::isfinite(cur.hi)) {
        cur = want;
        init = true;
        return;
    }
    // Grow at once to include the data. Shrink towards the target over about a second, but only once it is
    // 4% of the span away, and stop dead within 0.2%: an axis that keeps creeping would make every plot
    // that keeps its pixels between frames (TrailCanvas) redraw all of them every frame.
    const double k = 1.0 - std::exp(-dt_s / 0.6);
    const double span_now = cur.span();
    const auto shrink = [&](double& edge, double target, bool& active) {
        if (std::abs(target - edge) > 0.04 * span_now) active = true;
        if (!active) return;
        edge += (target - edge) * k;
        if (std::abs(target - edge) < 0.002 * span_now) {
            edge = target;
            active = false;
        }
    };
    if (want.lo < cur.lo) {
        cur.lo = want.lo;
        shrinking_lo = false;
    } else {
        shrink(cur.lo, want.lo, shrinking_lo);
    }
    if (want.hi > cur.hi) {
        cur.hi = want.hi;
        shrinking_hi = false;
    } else {
        shrink(cur.hi, want.hi, shrinking_hi);
    }
}

std::size_t& g_stat_points() { return g_vertices; }

namespace {
PlotBackend g_backend = PlotBackend::Raster;
bool g_backdrops_by_clear = false;
std::vector<PlotBackdrop> g_backdrops;
// One canvas of each kind per plot (by ImGui id), kept between frames with its texture.
std::unordered_map<ImGuiID, std::unique_ptr<Plot::CanvasSlot>>& canvases() {
    static std::unordered_map<ImGuiID, std::unique_ptr<Plot::CanvasSlot>> map;
    return map;
}
std::unordered_map<ImGuiID, std::unique_ptr<Plot::TrailSlot>>& trail_canvases() {
    static std::unordered_map<ImGuiID, std::unique_ptr<Plot::TrailSlot>> map;
    return map;
}
ImTextureID as_texture_id(GLuint tex) { return reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(tex)); }
}  // namespace

static_assert(IM_COL32_R_SHIFT == kColorRShift && IM_COL32_G_SHIFT == kColorGShift &&
                  IM_COL32_B_SHIFT == kColorBShift && IM_COL32_A_SHIFT == kColorAShift,
              "the raster canvases pack colours as ImU32 does");

void set_plot_backend(PlotBackend b) { g_backend = b; }
PlotBackend plot_backend() { return g_backend; }
void release_plot_canvases() {
    canvases().clear();
    trail_canvases().clear();
}
void set_plot_backdrops_by_clear(bool on) { g_backdrops_by_clear = on; }
std::vector<PlotBackdrop> take_plot_backdrops() {
    std::vector<PlotBackdrop> out;
    out.swap(g_backdrops);
    return out;
}

RasterCanvas* Plot::canvas() { return &canvas_->canvas; }   // begun by begin() (raster backend only)

Plot::TrailSlot* Plot::trail_slot() {
    auto& slot = trail_canvases()[id_];
    if (!slot) slot = std::make_unique<TrailSlot>();
    return slot.get();
}


void Plot::flush_raster(ImU32 color, float thickness) {
    if (gbuf_.size() < 2) return;
    RasterCanvas* cv = canvas();
    cv->layer(color);
    for (std::size_t i = 1; i < gbuf_.size(); ++i) {
        const auto& a = gbuf_[i - 1];
        const auto& b = gbuf_[i];
        cv->segment({a.x, a.y}, {b.x, b.y}, thickness, a.alpha, b.alpha);
    }
    g_vertices += gbuf_.size();
}
std::size_t Plot::emitted_vertices() { return g_vertices; }
void Plot::reset_stats() { g_vertices = 0; }

void Plot::flush_gpu(ImU32 color, float thickness) {
    plot_gpu::add_lines(dl_, gbuf_.data(), gbuf_.size(), color, thickness);
    g_vertices += gbuf_.size();
}

bool Plot::begin(const char* id, ImVec2 size, Range x, Range y, const Axes& axes) {
    const Palette& pal = palette();
    dl_ = ImGui::GetWindowDrawList();
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    if (size.x < 80 || size.y < 60) {
        ImGui::Dummy(size);
        return false;
    }
    id_ = ImGui::GetID(id);
    name_ = id;
    ImGui::InvisibleButton(id, size);
    canvas_ = nullptr;
    hovered_ = ImGui::IsItemHovered();
    clicked_ = hovered_ && ImGui::IsMouseReleased(ImGuiMouseButton_Left) &&
               ImGui::GetIO().MouseDragMaxDistanceSqr[0] < 16.0f;
    dragging_ = ImGui::IsItemActive();
    const ImVec2 p1(p0.x + size.x, p0.y + size.y);

    const float fs = ImGui::GetFontSize();
    const float left = fs * 3.6f, bottom = fs * 2.35f, top = fs * 0.45f, right = fs * 0.8f;
    min_ = ImVec2(std::floor(p0.x + left), std::floor(p0.y + top));
    max_ = ImVec2(std::floor(p1.x - right), std::floor(p1.y - bottom));
    x_ = x.valid() ? x : Range{x.lo - 0.5, x.lo + 0.5};
    y_ = y.valid() ? y : Range{y.lo - 0.5, y.lo + 0.5};
    zoom_and_pan();
    bx_ = (max_.x - min_.x) / x_.span();
    ax_ = min_.x - bx_ * x_.lo;
    by_ = -(max_.y - min_.y) / y_.span();
    ay_ = max_.y - by_ * y_.lo;

    opaque_ = plot_backend() == PlotBackend::Raster;
    if (opaque_) {
        // One opaque image of the whole data area: the backdrop, the grid and everything drawn with the
        // canvas are composited on the CPU, and ImDrawList's overlays go over it.
        auto& slot = canvases()[id_];
        if (!slot) slot = std::make_unique<CanvasSlot>();
        canvas_ = slot.get();
        canvas_->canvas.begin_opaque({min_.x, min_.y}, {max_.x, max_.y}, pal.plot_bg);
        opaque_image::add(dl_, canvas_->tex.ensure(), min_, max_);
    } else if (g_backdrops_by_clear) {
        g_backdrops.push_back({min_, max_, pal.plot_bg});
    } else {
        dl_->AddRectFilled(min_, max_, pal.plot_bg);
    }
    RasterCanvas* grid = opaque_ ? &canvas_->canvas : nullptr;
    if (grid) grid->layer(pal.grid);

    // Ticks and grid.
    char buf[32];
    const int nx = std::max(2, static_cast<int>((max_.x - min_.x) / (fs * 5.0f)));
    const int ny = std::max(2, static_cast<int>((max_.y - min_.y) / (fs * 2.6f)));
    // The PNG figures' tick rule (at most nx ticks on a 1-2-5 step, in the axis' shown unit); 0 for an
    // empty or non-finite range, which gets no ticks.
    const double sx = plot::nice_step(x_.lo * axes.x_scale, x_.hi * axes.x_scale, nx) / std::abs(axes.x_scale);
    const double sy = plot::nice_step(y_.lo * axes.y_scale, y_.hi * axes.y_scale, ny) / std::abs(axes.y_scale);
    const int dx = decimals_for(sx * axes.x_scale), dy = decimals_for(sy * axes.y_scale);
    for (double v = std::ceil(x_.lo / sx) * sx; sx > 0 && v <= x_.hi + 1e-9 * sx; v += sx) {
        const float px = std::round(to_px(v, 0).x) + 0.5f;
        if (grid) grid->segment({px, min_.y}, {px, max_.y}, 1.0f, 1.0f, 1.0f);
        else dl_->AddLine(ImVec2(px, min_.y), ImVec2(px, max_.y), pal.grid);
        dl_->AddLine(ImVec2(px, max_.y), ImVec2(px, max_.y + fs * 0.3f), pal.plot_frame);
        format_tick(buf, sizeof buf, v * axes.x_scale, dx);
        const ImVec2 ts = ImGui::CalcTextSize(buf);
        if (px - ts.x * 0.5f < p0.x || px + ts.x * 0.5f > p1.x) continue;   // a label would leave the plot
        dl_->AddText(ImVec2(px - ts.x * 0.5f, max_.y + fs * 0.35f), pal.axis_text, buf);
    }
    for (double v = std::ceil(y_.lo / sy) * sy; sy > 0 && v <= y_.hi + 1e-9 * sy; v += sy) {
        const float py = std::round(to_px(0, v).y) + 0.5f;
        if (grid) grid->segment({min_.x, py}, {max_.x, py}, 1.0f, 1.0f, 1.0f);
        else dl_->AddLine(ImVec2(min_.x, py), ImVec2(max_.x, py), pal.grid);
        dl_->AddLine(ImVec2(min_.x - fs * 0.3f, py), ImVec2(min_.x, py), pal.plot_frame);
        format_tick(buf, sizeof buf, v * axes.y_scale, dy);
        const ImVec2 ts = ImGui::CalcTextSize(buf);
        dl_->AddText(ImVec2(min_.x - fs * 0.4f - ts.x, py - ts.y * 0.5f), pal.axis_text, buf);
    }
    dl_->AddRect(ImVec2(min_.x - 0.5f, min_.y - 0.5f), ImVec2(max_.x + 0.5f, max_.y + 0.5f), pal.plot_frame);
    // Labels: x centred below the ticks, y rotated along the left edge.
    if (axes.x_label && *axes.x_label) {
        const ImVec2 ts = ImGui::CalcTextSize(axes.x_label);
        dl_->AddText(ImVec2(0.5f * (min_.x + max_.x) - 0.5f * ts.x, label_row_y()), pal.title_text, axes.x_label);
    }
    // The y label stays inside the plot's own height (centred where it can be): rotated text longer than
    // that would run over whatever sits above the plot. Too long even so: the short label, or none.
    const char* y_label = axes.y_label;
    if (y_label && *y_label && ImGui::CalcTextSize(y_label).x > p1.y - p0.y) y_label = axes.y_label_short;
    if (y_label && *y_label) {
        const float half = 0.5f * ImGui::CalcTextSize(y_label).x;
        if (2.0f * half <= p1.y - p0.y) {
            const float cy = std::clamp(0.5f * (min_.y + max_.y), p0.y + half, p1.y - half);
            add_text_vertical(dl_, ImVec2(p0.x + fs * 0.6f, cy), pal.title_text, y_label);
        }
    }

    dl_->PushClipRect(min_, max_, true);
    return true;
}

void Plot::share_dots(bool on) {
    shared_dots_ = on;
    if (!on) return;
    const int w = static_cast<int>(max_.x - min_.x) + 1, h = static_cast<int>(max_.y - min_.y) + 1;
    if (w <= 0 || h <= 0) return;
    const std::size_t bits = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    bitmap_.assign((bits + 63) / 64, 0);
}

void Plot::set_user_view(const char* id, Range x, Range y) {
    if (x.valid() && y.valid()) g_user_views[ImGui::GetID(id)] = UserView{x, y, id};
}

void Plot::clear_user_view(const char* id) { g_user_views.erase(ImGui::GetID(id)); }

std::vector<Plot::NamedView> Plot::user_views() {
    std::vector<NamedView> out;
    for (const auto& [key, v] : g_user_views) out.push_back({v.name, v.x, v.y});
    for (const auto& [name, v] : g_restored_views) out.push_back({name, v.x, v.y});   // not drawn since
    std::sort(out.begin(), out.end(), [](const NamedView& a, const NamedView& b) { return a.id < b.id; });
    return out;
}

void Plot::restore_user_views(const std::vector<NamedView>& views) {
    g_user_views.clear();
    g_restored_views.clear();
    for (const NamedView& v : views)
        if (v.x.valid() && v.y.valid()) g_restored_views[v.id] = UserView{v.x, v.y, v.id};
}

void Plot::zoom_and_pan() {
    // The mouse over this plot: wheel zooms about the pointer, a drag pans, a double-click gives the view
    // back to the caller's auto-fit. The user's view then replaces the caller's ranges until that reset.
    const ImGuiIO& io = ImGui::GetIO();
    if (!g_restored_views.empty()) {
        if (const auto r = g_restored_views.find(name_); r != g_restored_views.end()) {
            g_user_views[id_] = r->second;
            g_restored_views.erase(r);
        }
    }
    auto it = g_user_views.find(id_);
    if (hovered_ && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left) && it != g_user_views.end()) {
        g_user_views.erase(it);
        it = g_user_views.end();
    }
    UserView v = it != g_user_views.end() ? it->second : UserView{x_, y_};
    bool changed = false;
    const double w = std::max(1.0f, max_.x - min_.x), h = std::max(1.0f, max_.y - min_.y);
    if (hovered_) ImGui::SetItemUsingMouseWheel();
    if (hovered_ && io.MouseWheel != 0.0f) {
        const double f = std::pow(0.85, static_cast<double>(io.MouseWheel));
        const double mx = v.x.lo + (io.MousePos.x - min_.x) / w * v.x.span();
        const double my = v.y.hi - (io.MousePos.y - min_.y) / h * v.y.span();
        if (!io.KeyCtrl) {
            const AxisFit r = zoom_axis({v.x.lo, v.x.hi}, mx, f);
            v.x = {r.lo, r.hi};
        }
        if (!io.KeyShift) {
            const AxisFit r = zoom_axis({v.y.lo, v.y.hi}, my, f);
            v.y = {r.lo, r.hi};
        }
        changed = true;
    }
    if (dragging_ && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 4.0f) &&
        (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f)) {
        const AxisFit rx = pan_axis({v.x.lo, v.x.hi}, io.MouseDelta.x, w);
        const AxisFit ry = pan_axis({v.y.lo, v.y.hi}, -io.MouseDelta.y, h);   // screen y grows downwards
        v.x = {rx.lo, rx.hi};
        v.y = {ry.lo, ry.hi};
        changed = true;
    }
    if (changed && v.x.valid() && v.y.valid() && std::isfinite(v.x.span()) && std::isfinite(v.y.span()) &&
        v.x.span() > 1e-12 && v.y.span() > 1e-12)
        g_user_views[id_] = UserView{v.x, v.y, name_};
    it = g_user_views.find(id_);
    zoomed_ = it != g_user_views.end();
    if (zoomed_) {
        x_ = it->second.x;
        y_ = it->second.y;
    }
}

void Plot::end() {
    if (canvas_ && canvas_->canvas.active()) {   // shown whole by the opaque image begin() placed
        const RasterCanvas& cv = canvas_->canvas;
        const PixelRect r = canvas_->canvas.finish();
        canvas_->tex.upload(cv.rgba(), cv.width(), cv.height(), r.x0, r.y0, r.x1, r.y1);
    }
    canvas_ = nullptr;
    if (zoomed_) {   // over the data: the user should know this view is theirs, and how to leave it
        const char* note = "zoomed: double-click resets";
        const ImVec2 ts = ImGui::CalcTextSize(note);
        const ImVec2 q(max_.x - ts.x - 6, max_.y - 2 * ts.y - 10);   // a line above the plots' own notes
        dl_->AddRectFilled(ImVec2(q.x - 3, q.y - 1), ImVec2(q.x + ts.x + 3, q.y + ts.y + 1),
                           palette().dark ? IM_COL32(10, 12, 16, 170) : IM_COL32(255, 255, 255, 190), 3.0f);
        dl_->AddText(q, palette().axis_text, note);
    }
    dl_->PopClipRect();
}

void Plot::flush(std::vector<ImVec2>& pts, ImU32 color, float thickness) {
    // ImDrawList indexes with 16 bits: keep each polyline well under 64k vertices (AA lines emit up to
    // 4 per point), overlapping chunks by one point.
    constexpr std::size_t kChunk = 4000;
    const std::size_t n = pts.size();
    if (n < 2) return;
    for (std::size_t s = 0; s + 1 < n; s += kChunk) {
        const std::size_t len = std::min(kChunk + 1, n - s);
        dl_->AddPolyline(pts.data() + s, static_cast<int>(len), color, ImDrawFlags_None, thickness);
        g_vertices += len;
    }
}

void Plot::vline(double x, ImU32 color, float thickness, bool dashed) {
    const float px = to_px(x, 0).x;
    RasterCanvas* cv = opaque_ ? canvas() : nullptr;
    if (cv) cv->layer(color);
    auto line = [&](ImVec2 a, ImVec2 b) {
        if (cv) cv->segment({a.x, a.y}, {b.x, b.y}, thickness, 1.0f, 1.0f);
        else dl_->AddLine(a, b, color, thickness);
    };
    if (!dashed) {
        line(ImVec2(px, min_.y), ImVec2(px, max_.y));
        return;
    }
    const float dash = ImGui::GetFontSize() * 0.35f;
    for (float y = min_.y; y < max_.y; y += 2 * dash) line(ImVec2(px, y), ImVec2(px, std::min(y + dash, max_.y)));
}

void Plot::hline(double y, ImU32 color, float thickness, bool dashed) {
    const float py = to_px(0, y).y;
    RasterCanvas* cv = opaque_ ? canvas() : nullptr;
    if (cv) cv->layer(color);
    auto line = [&](ImVec2 a, ImVec2 b) {
        if (cv) cv->segment({a.x, a.y}, {b.x, b.y}, thickness, 1.0f, 1.0f);
        else dl_->AddLine(a, b, color, thickness);
    };
    if (!dashed) {
        line(ImVec2(min_.x, py), ImVec2(max_.x, py));
        return;
    }
    const float dash = ImGui::GetFontSize() * 0.35f;
    for (float x = min_.x; x < max_.x; x += 2 * dash) line(ImVec2(x, py), ImVec2(std::min(x + dash, max_.x), py));
}

void Plot::dots(const ImVec2* at, std::size_t n, ImU32 color, float diameter) {
    if (n == 0) return;
    if (opaque_) {
        RasterCanvas* cv = canvas();
        cv->layer(color);
        for (std::size_t i = 0; i < n; ++i) cv->dot({at[i].x, at[i].y}, diameter);
        return;
    }
    for (std::size_t i = 0; i < n; ++i) dl_->AddCircleFilled(at[i], 0.5f * diameter, color, 10);
}

void Plot::image(const std::uint8_t* rgba, int w, int h, GLuint tex, float alpha) {
    if (opaque_) {
        canvas()->blend_image(rgba, w, h, alpha);
        return;
    }
    if (tex)
        dl_->AddImage(as_texture_id(tex), min_, max_, ImVec2(0, 0), ImVec2(1, 1),
                      IM_COL32(255, 255, 255, static_cast<int>(std::clamp(alpha, 0.0f, 1.0f) * 255.0f + 0.5f)));
}

void Plot::text(double x, double y, const char* s, ImU32 color, ImVec2 align) {
    const ImVec2 ts = ImGui::CalcTextSize(s);
    const ImVec2 p = to_px(x, y);
    dl_->AddText(ImVec2(p.x - ts.x * align.x, p.y - ts.y * align.y), color, s);
}

void Plot::shade_right_of(double x0, ImU32 color) {
    const float px = std::max(to_px(x0, 0).x, min_.x);
    if (px >= max_.x) return;
    ImVec4 c = ImGui::ColorConvertU32ToFloat4(color);
    c.w *= 0.12f;
    const ImU32 fill = ImGui::ColorConvertFloat4ToU32(c);
    c.w = ImGui::ColorConvertU32ToFloat4(color).w * 0.35f;
    const ImU32 hatch = ImGui::ColorConvertFloat4ToU32(c);
    const float step = ImGui::GetFontSize() * 0.6f;
    const float h = max_.y - min_.y;
    if (opaque_) {
        RasterCanvas* cv = canvas();
        cv->layer(fill);
        cv->fill_rect({px, min_.y}, {max_.x, max_.y});
        cv->layer(hatch);
        // Lines up and to the right at 45 degrees, each cut where it enters the region x >= px.
        for (float x = px - h; x < max_.x; x += step) {
            const float t0 = std::max(0.0f, (px - x) / h);
            if (t0 >= 1.0f) continue;
            cv->segment({x + t0 * h, max_.y - t0 * h}, {x + h, min_.y}, 1.0f, 1.0f, 1.0f);
        }
        return;
    }
    dl_->AddRectFilled(ImVec2(px, min_.y), max_, fill);
    dl_->PushClipRect(ImVec2(px, min_.y), max_, true);
    for (float x = px - h; x < max_.x; x += step) dl_->AddLine(ImVec2(x, max_.y), ImVec2(x + h, min_.y), hatch);
    dl_->PopClipRect();
}

}  // namespace impactlab::gui
