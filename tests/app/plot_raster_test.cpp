// The plots' CPU rasterizer (app/gui/plot_raster): the per-frame canvas, the persistent fading trail, and
// the sliding auto-fit extent of the UI's histories. No GL: the images are checked as bytes.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <vector>

#include "../../app/gui/sim/history.hpp"
#include "../../app/gui/render/plot_raster.hpp"

using namespace impactlab::gui;

namespace {

constexpr PackedColor kRed = 0xFF0000FFu;    // A B G R from the top byte down: opaque red
constexpr PackedColor kBlue = 0xFFFF0000u;   // opaque blue

std::uint8_t alpha_at(const std::uint8_t* rgba, int w, int x, int y) {
    return rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)) * 4 + 3];
}

// A trajectory like the phase portrait's: a slowly precessing ellipse, sampled densely.
struct Orbit {
    double x(std::uint64_t k) const { return 40.0 * std::cos(0.02 * k) + 5.0 * std::cos(0.0031 * k); }
    double y(std::uint64_t k) const { return 30.0 * std::sin(0.02 * k) + 4.0 * std::sin(0.0017 * k); }
};

TrailCanvas::Frame frame_for(std::uint64_t first, std::uint64_t last, double shift_px = 0.0) {
    TrailCanvas::Frame f;
    f.min = {10, 20};
    f.max = {130, 120};   // 120 x 100 px
    f.map = {70.0 + shift_px, 1.0, 70.0, -1.0};   // data (0, 0) at the centre, y up
    f.generation = 1;
    f.first_seq = first;
    f.last_seq = last;
    f.color = kRed;
    f.thickness = 1.6f;
    return f;
}

void feed_range(TrailCanvas& t, const Orbit& o, std::uint64_t first, std::uint64_t last, std::size_t from) {
    for (std::uint64_t k = first + from; k <= last; ++k) t.feed(k, o.x(k), o.y(k));
}

}  // namespace

TEST_CASE("raster canvas: a segment covers its line, antialiased, and the drawn rectangle bounds it") {
    RasterCanvas c;
    c.begin({0, 0}, {64, 32});
    c.layer(kRed);
    c.segment({8, 16.25f}, {56, 16.25f}, 2.0f, 1.0f, 1.0f);   // off the pixel grid: partial rows
    const PixelRect r = c.finish();
    REQUIRE(!r.empty());
    CHECK(r.x0 <= 7);
    CHECK(r.x1 >= 56);
    CHECK(r.y0 >= 12);
    CHECK(r.y1 <= 19);
    // On the line: opaque red; far from it: transparent; at the edge: partial.
    CHECK(alpha_at(c.rgba(), 64, 30, 16) == 255);
    CHECK(c.rgba()[(16 * 64 + 30) * 4 + 0] == 255);
    CHECK(alpha_at(c.rgba(), 64, 30, 5) == 0);
    const int edge = alpha_at(c.rgba(), 64, 30, 17);
    CHECK(edge > 0);
    CHECK(edge < 255);
}

TEST_CASE("raster canvas: the next frame starts clean, and layers composite over each other") {
    RasterCanvas c;
    c.begin({0, 0}, {32, 32});
    c.layer(kRed);
    c.dot({8, 8}, 6.0f);
    c.finish();
    CHECK(alpha_at(c.rgba(), 32, 8, 8) == 255);
    // Frame 2 draws elsewhere: the old dot is gone, blue over red gives blue where both are opaque.
    c.begin({0, 0}, {32, 32});
    c.layer(kRed);
    c.dot({20, 20}, 6.0f);
    c.layer(kBlue);
    c.dot({20, 20}, 6.0f);
    const PixelRect r = c.finish();
    CHECK(alpha_at(c.rgba(), 32, 8, 8) == 0);
    const std::uint8_t* p = c.rgba() + (20 * 32 + 20) * 4;
    CHECK(p[0] == 0);
    CHECK(p[2] == 255);
    CHECK(p[3] == 255);
    CHECK(r.x0 > 8);   // only the new dot's pixels need showing
}

TEST_CASE("raster canvas: a vertical bar has full coverage inside and its width in total across a row") {
    RasterCanvas c;
    c.begin({0, 0}, {16, 40});
    c.layer(kRed);
    c.vspan(8.5f, 10.0f, 30.0f, 2.0f);   // centred on column 8, 2 px wide: columns 7.5 .. 9.5
    c.finish();
    CHECK(alpha_at(c.rgba(), 16, 8, 20) == 255);
    CHECK(alpha_at(c.rgba(), 16, 5, 20) == 0);
    int sum = 0;
    for (int x = 0; x < 16; ++x) sum += alpha_at(c.rgba(), 16, x, 20);
    CHECK(sum == doctest::Approx(2 * 255).epsilon(0.01));
    CHECK(alpha_at(c.rgba(), 16, 8, 2) == 0);   // nothing far above the span
}

namespace {
const std::uint8_t* pixel(const RasterCanvas& c, int x, int y) {
    return c.rgba() + (static_cast<std::size_t>(y) * static_cast<std::size_t>(c.width()) + static_cast<std::size_t>(x)) * 4;
}
constexpr PackedColor kGrey = 0xFF404040u;   // the opaque backdrop
}  // namespace

TEST_CASE("opaque canvas: the backdrop fills every pixel, and the whole area is what the frame shows") {
    RasterCanvas c;
    c.begin_opaque({10.0f, 20.0f}, {50.0f, 45.0f}, kGrey & 0x00FFFFFFu);   // a backdrop's alpha is ignored
    CHECK(c.opaque());
    const PixelRect r = c.finish();
    CHECK(r.x0 == 0);
    CHECK(r.y0 == 0);
    CHECK(r.x1 == 39);
    CHECK(r.y1 == 24);
    for (int y = 0; y < c.height(); ++y)
        for (int x = 0; x < c.width(); ++x) {
            const std::uint8_t* p = pixel(c, x, y);
            REQUIRE(p[0] == 0x40);
            REQUIRE(p[3] == 255);
        }
    // A transparent frame after an opaque one starts from nothing.
    c.begin({10.0f, 20.0f}, {50.0f, 45.0f});
    CHECK(!c.opaque());
    c.finish();
    CHECK(pixel(c, 5, 5)[3] == 0);
}

TEST_CASE("opaque canvas: layers mix into the backdrop by their opacity and every pixel stays opaque") {
    RasterCanvas c;
    c.begin_opaque({0, 0}, {32, 32}, kGrey);
    c.layer(kRed);
    c.fill_rect({4, 4}, {12, 12});                   // opaque red over grey: red
    c.layer(0x80FF0000u);                            // blue at alpha 128
    c.fill_rect({20, 20}, {28, 28});
    c.finish();
    const std::uint8_t* red = pixel(c, 8, 8);
    CHECK(red[0] == 255);
    CHECK(red[1] == 0);
    CHECK(red[3] == 255);
    const std::uint8_t* mix = pixel(c, 24, 24);      // (255 * 128 + 64 * 127) / 255 = 160, grey elsewhere
    CHECK(mix[2] == doctest::Approx(160).epsilon(0.01));
    CHECK(mix[0] == doctest::Approx(32).epsilon(0.05));
    CHECK(mix[3] == 255);
    // fill_rect covers exactly the whole pixels of [min, max).
    CHECK(pixel(c, 3, 8)[0] == 0x40);
    CHECK(pixel(c, 4, 8)[0] == 255);
    CHECK(pixel(c, 11, 8)[0] == 255);
    CHECK(pixel(c, 12, 8)[0] == 0x40);
}

TEST_CASE("opaque canvas: an image composites over it by its alpha, scaled by the call's opacity") {
    RasterCanvas c;
    c.begin_opaque({0, 0}, {16, 8}, kGrey);
    std::vector<std::uint8_t> img(16 * 8 * 4, 0);   // transparent but for two pixels
    auto put = [&](int x, int y, std::uint8_t r, std::uint8_t a) {
        std::uint8_t* p = &img[(static_cast<std::size_t>(y) * 16 + static_cast<std::size_t>(x)) * 4];
        p[0] = r, p[3] = a;
    };
    put(3, 2, 255, 255);
    put(9, 5, 255, 255);
    c.blend_image(img.data(), 16, 8, 1.0f);
    CHECK(pixel(c, 3, 2)[0] == 255);
    CHECK(pixel(c, 4, 2)[0] == 0x40);   // its neighbour (read two at a time) untouched
    CHECK(pixel(c, 9, 5)[0] == 255);
    c.blend_image(img.data(), 16, 8, 0.0f);   // nothing
    c.finish();
    RasterCanvas half;
    half.begin_opaque({0, 0}, {16, 8}, kGrey);
    half.blend_image(img.data(), 16, 8, 0.5f);
    half.finish();
    CHECK(pixel(half, 3, 2)[0] == doctest::Approx((255 * 128 + 64 * 127) / 255).epsilon(0.02));
    CHECK(pixel(half, 8, 5)[0] == 0x40);
    // A smaller image lands at the top left and leaves the rest as it was.
    RasterCanvas wide;
    wide.begin_opaque({0, 0}, {20, 10}, kGrey);
    wide.blend_image(img.data(), 16, 8);
    wide.finish();
    CHECK(pixel(wide, 9, 5)[0] == 255);
    CHECK(pixel(wide, 18, 9)[0] == 0x40);
}

TEST_CASE("raster canvas: axis-aligned lines (grid, dashes) cover their pixels like the general segment") {
    RasterCanvas c;
    c.begin({0, 0}, {40, 40});
    c.layer(kRed);
    c.segment({10.5f, 5.0f}, {10.5f, 35.0f}, 1.0f, 1.0f, 1.0f);   // a grid line on the pixel centres
    c.segment({5.0f, 20.5f}, {35.0f, 20.5f}, 1.0f, 1.0f, 1.0f);
    c.finish();
    CHECK(alpha_at(c.rgba(), 40, 10, 15) == 255);
    CHECK(alpha_at(c.rgba(), 40, 9, 15) == 0);
    CHECK(alpha_at(c.rgba(), 40, 11, 15) == 0);
    CHECK(alpha_at(c.rgba(), 40, 25, 20) == 255);
    CHECK(alpha_at(c.rgba(), 40, 25, 19) == 0);
    CHECK(alpha_at(c.rgba(), 40, 25, 21) == 0);
    CHECK(alpha_at(c.rgba(), 40, 10, 38) == 0);   // not past its ends
    CHECK(alpha_at(c.rgba(), 40, 38, 20) == 0);
    // Off the grid and 2 px wide: the same total coverage across as the general (distance) rasterizer.
    RasterCanvas a, b;
    a.begin({0, 0}, {40, 40});
    a.layer(kRed);
    a.segment({5.0f, 20.3f}, {35.0f, 20.3f}, 2.0f, 1.0f, 1.0f);   // the bar
    a.finish();
    b.begin({0, 0}, {40, 40});
    b.layer(kRed);
    b.segment({5.0f, 20.3f}, {35.0f, 20.3f}, 2.0f, 1.0f, 0.999f);   // not one opacity: the general path
    b.finish();
    int sa = 0, sb = 0;
    for (int y = 0; y < 40; ++y) {
        sa += alpha_at(a.rgba(), 40, 20, y);
        sb += alpha_at(b.rgba(), 40, 20, y);
    }
    CHECK(sa == doctest::Approx(sb).epsilon(0.03));
    CHECK(sa == doctest::Approx(2 * 255).epsilon(0.03));
}

TEST_CASE("trail canvas: drawn frame by frame, it matches one full redraw of the same window") {
    const Orbit o;
    constexpr std::uint64_t kWindow = 3000, kPerFrame = 170, kFrames = 60;
    TrailCanvas live;
    std::uint64_t last = kWindow - 1;
    int full_redraws = 0;
    for (std::uint64_t f = 0; f < kFrames; ++f, last += kPerFrame) {
        const std::uint64_t first = last + 1 - kWindow;
        const auto fr = frame_for(first, last);
        const std::size_t from = live.begin(fr);
        full_redraws += live.full_redraw();
        feed_range(live, o, first, last, from);
        live.finish();
    }
    CHECK(full_redraws == 1);   // only the first frame
    last -= kPerFrame;
    TrailCanvas once;
    const auto fr = frame_for(last + 1 - kWindow, last);
    REQUIRE(once.begin(fr) == 0);
    feed_range(once, o, last + 1 - kWindow, last, 0);
    once.finish();
    REQUIRE(once.width() == live.width());
    REQUIRE(once.height() == live.height());
    // The same picture up to antialiasing fringes where old and new lines cross: a pixel keeps the sample
    // that covered it more strongly, and once that one leaves the window, the incremental image forgets a
    // weaker newer one that a redraw would show. This orbit recrosses itself ten times in the window.
    const int w = live.width(), h = live.height();
    long diff = 0, total = 0, big = 0, covered = 0;
    int worst = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const int a = alpha_at(live.rgba(), w, x, y), b = alpha_at(once.rgba(), w, x, y);
            diff += std::abs(a - b);
            total += b;
            big += std::abs(a - b) > 128;
            worst = std::max(worst, std::abs(a - b));
            covered += b > 0;
        }
    CHECK(total > 0);
    CHECK(static_cast<double>(diff) < 0.10 * static_cast<double>(total));
    CHECK(static_cast<double>(big) < 0.01 * static_cast<double>(covered));
    CHECK(worst < 240);   // never a whole line missing or extra
}

TEST_CASE("trail canvas: the newest samples are opaque, samples that left the window vanish") {
    const Orbit o;
    TrailCanvas t;
    // A short window over a quarter turn, then the window moves on by a full quarter turn.
    auto fr = frame_for(0, 80);
    feed_range(t, o, 0, 80, t.begin(fr));
    t.finish();
    const auto pixel = [&](std::uint64_t k) {
        const PxPoint p = fr.map.to_px(o.x(k), o.y(k));
        return alpha_at(t.rgba(), t.width(), static_cast<int>(p.x - fr.min.x), static_cast<int>(p.y - fr.min.y));
    };
    CHECK(pixel(80) > 200);
    CHECK(pixel(0) < 10);   // the oldest end has faded out
    CHECK(pixel(40) > 20);
    fr = frame_for(81, 161);
    const std::size_t from = t.begin(fr);
    CHECK_FALSE(t.full_redraw());
    CHECK(from == 0);   // sample 81 is the first of the new window and the next to draw
    feed_range(t, o, 81, 161, from);
    t.finish();
    CHECK(pixel(40) == 0);   // sample 40 left the window (and the orbit has moved on)
    CHECK(pixel(161) > 200);
}

TEST_CASE("trail canvas: a redraw happens on a view change of half a pixel, a clear, or a longer trail") {
    const Orbit o;
    TrailCanvas t;
    auto draw = [&](const TrailCanvas::Frame& f) {
        feed_range(t, o, f.first_seq, f.last_seq, t.begin(f));
        t.finish();
        return t.full_redraw();
    };
    CHECK(draw(frame_for(0, 500)));
    CHECK_FALSE(draw(frame_for(10, 520)));
    CHECK_FALSE(draw(frame_for(20, 540, 0.3)));   // the axes moved by 0.3 px: keep the image
    CHECK(draw(frame_for(30, 560, 0.8)));         // 0.8 px: redraw
    CHECK(draw(frame_for(5, 580, 0.8)));          // the trail grew backwards: redraw
    auto f = frame_for(40, 600, 0.8);
    f.generation = 2;                              // the history was cleared
    CHECK(draw(f));
    f = frame_for(50, 620, 0.8);
    f.generation = 2;
    f.color = kBlue;
    CHECK(draw(f));
}

TEST_CASE("window extent: sliding minimum and maximum match a full scan, across clears") {
    History<double> h(256);
    WindowExtent e;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> val(-1.0, 1.0);
    std::size_t window = 40;
    for (int step = 0; step < 3000; ++step) {
        const int pushes = static_cast<int>(rng() % 5);
        for (int i = 0; i < pushes; ++i) h.push(val(rng));
        if (step % 500 == 499) h.clear();
        if (step % 97 == 0) window = 10 + rng() % 100;   // also grows: the extent rebuilds
        const std::size_t first = h.size() > window ? h.size() - window : 0;
        const auto r = e.update(h, first, [](double v) { return v; });
        if (first >= h.size()) {
            CHECK(r.empty);
            continue;
        }
        double lo = 1e9, hi = -1e9;
        for (std::size_t i = first; i < h.size(); ++i) lo = std::min(lo, h[i]), hi = std::max(hi, h[i]);
        REQUIRE_FALSE(r.empty);
        CHECK(r.lo == lo);
        CHECK(r.hi == hi);
    }
}
