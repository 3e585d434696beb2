// The one capsule rasteriser (impactlab/raster.hpp) that the figures (double) and the visualiser (float)
// both draw with: coverage by distance, round ends, each pixel once, and the two precisions agree.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "impactlab/raster.hpp"

namespace raster = impactlab::raster;

namespace {

template <class T>
std::map<std::pair<int, int>, double> covered(T ax, T ay, T bx, T by, T hw, int w, int h, int* visits_twice = nullptr) {
    std::map<std::pair<int, int>, double> out;
    raster::capsule(ax, ay, bx, by, hw, 0, 0, w, h, [&](int x, int y, T cov, T) {
        CHECK(x >= 0);
        CHECK(x < w);
        CHECK(y >= 0);
        CHECK(y < h);
        if (out.count({x, y}) && visits_twice) ++*visits_twice;
        if (cov > 0) out[{x, y}] = static_cast<double>(cov);
    });
    return out;
}

}  // namespace

TEST_CASE("raster::capsule: a 1-px line through pixel centres covers one pixel per column, fully") {
    const auto c = covered(2.5, 5.5, 12.5, 5.5, 0.5, 20, 12);
    for (int x = 2; x <= 12; ++x) CHECK(c.at({x, 5}) == doctest::Approx(1.0).epsilon(1e-12));
    for (const auto& [p, cov] : c)
        if (p.second != 5) CHECK(cov < 1e-12);   // nothing beside the line but round-off
    // Round ends: one pixel beyond either end is half a pixel further than the width reaches.
    CHECK(c.count({1, 5}) == 0);
    CHECK(c.count({13, 5}) == 0);
}

TEST_CASE("raster::capsule: coverage is the distance rule, each pixel once, float and double agree") {
    struct Seg { double ax, ay, bx, by, hw; };
    for (const Seg s : {Seg{3.2, 4.1, 27.9, 19.3, 1.0}, Seg{10.0, 2.0, 11.0, 28.0, 0.75}, Seg{15.3, 15.7, 15.3, 15.7, 2.5},
                        Seg{-5.0, 3.0, 40.0, 8.0, 1.5}}) {
        int twice = 0;
        const auto d = covered(s.ax, s.ay, s.bx, s.by, s.hw, 32, 30, &twice);
        CHECK(twice == 0);
        REQUIRE(!d.empty());
        for (const auto& [p, cov] : d) {
            // Distance from the pixel centre to the segment, by projection.
            const double px = p.first + 0.5, py = p.second + 0.5, dx = s.bx - s.ax, dy = s.by - s.ay;
            const double l2 = dx * dx + dy * dy;
            const double t = l2 > 0 ? std::clamp(((px - s.ax) * dx + (py - s.ay) * dy) / l2, 0.0, 1.0) : 0.0;
            const double dist = std::hypot(px - s.ax - t * dx, py - s.ay - t * dy);
            CHECK(cov == doctest::Approx(std::clamp(s.hw + 0.5 - dist, 0.0, 1.0)).epsilon(1e-9));
        }
        // Every pixel the rule covers is visited (a scan of the whole image finds no other).
        for (int y = 0; y < 30; ++y)
            for (int x = 0; x < 32; ++x) {
                const double px = x + 0.5, py = y + 0.5, dx = s.bx - s.ax, dy = s.by - s.ay;
                const double l2 = dx * dx + dy * dy;
                const double t = l2 > 0 ? std::clamp(((px - s.ax) * dx + (py - s.ay) * dy) / l2, 0.0, 1.0) : 0.0;
                if (s.hw + 0.5 - std::hypot(px - s.ax - t * dx, py - s.ay - t * dy) > 1e-6) CHECK(d.count({x, y}) == 1);
            }
        const auto f = covered(static_cast<float>(s.ax), static_cast<float>(s.ay), static_cast<float>(s.bx),
                               static_cast<float>(s.by), static_cast<float>(s.hw), 32, 30);
        for (const auto& [p, cov] : d)
            if (cov > 1e-4) CHECK(std::abs(f.count(p) ? f.at(p) - cov : cov) < 1e-4);
    }
}

TEST_CASE("raster::capsule: a segment out of the clip visits nothing") {
    int n = 0;
    const raster::PixelBox b = raster::capsule(100.0, 100.0, 120.0, 130.0, 1.0, 0, 0, 32, 30, [&](int, int, double, double) { ++n; });
    CHECK(b.empty());
    CHECK(n == 0);
}
