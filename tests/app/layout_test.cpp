// The visualiser's layout (app/gui/layout): at 1024x768 and 1280x800 with UI scale
// 1, 1.5 and 2, every tile lies inside the viewport, none overlaps another, each keeps its minimum size, and
// every visible panel is shown exactly once; hidden panels give their space away, a maximised one fills the
// plot area; presentation mode shows the rig and the chosen plot under a slim bar. The rig's labels never
// overprint each other, and the magnified rig still shows a contact as a contact.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "../../app/gui/window/layout.hpp"

using namespace impactlab::gui;

namespace {

// The viewport below the menu bar and above the status bar, as App::layout_and_draw passes it.
LayoutRequest request(float w, float h, float scale) {
    LayoutRequest r;
    const float frame_h = std::round((14.5f + 6.0f) * scale);
    r.area = {0.0f, frame_h, w, h - frame_h - std::round(frame_h + 6.0f * scale)};
    r.scale = scale;
    r.frame_h = frame_h;
    return r;
}

int count_of(const Layout& l, PanelId p) {
    int n = 0;
    for (const Tile& t : l.tiles) n += static_cast<int>(std::count(t.panels.begin(), t.panels.end(), p));
    return n;
}

// Inside the area, no overlaps (the controls and the bar included), minimum sizes, each visible panel once.
void check_sound(const LayoutRequest& r, const Layout& l) {
    std::vector<Rect> all;
    if (!l.controls.empty()) all.push_back(l.controls);
    if (!l.bar.empty()) all.push_back(l.bar);
    for (const Tile& t : l.tiles) {
        CHECK_FALSE(t.panels.empty());
        all.push_back(t.rect);
        // Maximised and presentation tiles are as large as the area allows; the others keep their minimum.
        if (!r.maximised && r.mode == LayoutMode::Normal) {
            const bool strip = t.panels.size() == 1 && t.panels[0] == PanelId::Strip;
            CHECK(t.rect.w >= min_tile_w(r.scale) - 0.5f);
            CHECK(t.rect.h >= (strip ? min_strip_h(r.scale) : min_tile_h(r.scale)) - 0.5f);
        }
    }
    for (std::size_t i = 0; i < all.size(); ++i) {
        CHECK(contains(r.area, all[i]));
        CHECK_FALSE(all[i].empty());
        for (std::size_t j = i + 1; j < all.size(); ++j) CHECK_FALSE(overlaps(all[i], all[j]));
    }
    if (r.mode == LayoutMode::Normal && !r.maximised)
        for (int p = 0; p < kPanelCount; ++p)
            CHECK(count_of(l, static_cast<PanelId>(p)) == (r.visible[static_cast<std::size_t>(p)] ? 1 : 0));
}

float covered(const Layout& l) {
    float a = l.controls.w * l.controls.h + l.bar.w * l.bar.h;
    for (const Tile& t : l.tiles) a += t.rect.w * t.rect.h;
    return a;
}

}  // namespace

TEST_CASE("layout: every size and scale is sound, and the tiles cover the viewport") {
    for (auto [w, h] : {std::pair{1024.0f, 768.0f}, std::pair{1280.0f, 800.0f}, std::pair{1920.0f, 1080.0f}}) {
        for (float scale : {1.0f, 1.25f, 1.5f, 2.0f}) {
            CAPTURE(w);
            CAPTURE(h);
            CAPTURE(scale);
            const LayoutRequest r = request(w, h, scale);
            const Layout l = compute_layout(r);
            check_sound(r, l);
            CHECK(covered(l) == doctest::Approx(r.area.w * r.area.h));   // no gaps either
            // The controls never take more than about a third of the width.
            CHECK(l.controls.w <= 0.34f * w + 1);
        }
    }
}

TEST_CASE("layout: the wide layout at scale 1 keeps today's tiles; scale 2 stacks the extra plots as tabs") {
    const Layout one = compute_layout(request(1280, 800, 1.0f));
    CHECK(one.tiles.size() == 6);   // rig, diagram / phase, map, potential / strip: no tabs
    CHECK_FALSE(one.controls_narrow);
    LayoutRequest r2 = request(1280, 800, 2.0f);
    r2.controls_need_h = 36.0f * (r2.frame_h + 10.0f);   // about what every section stacked measures at scale 2
    const Layout two = compute_layout(r2);
    CHECK(two.tiles.size() < 6);
    bool tabbed = false;
    for (const Tile& t : two.tiles) tabbed = tabbed || t.panels.size() > 1;
    CHECK(tabbed);
    CHECK(two.controls_narrow);     // short labels
    CHECK(two.controls_tabbed);     // Run / State / View tabs instead of scrolling
    // The rig keeps a tile of its own, first.
    CHECK(two.tiles[0].panels == std::vector<PanelId>{PanelId::Rig});
}

TEST_CASE("layout: the controls are tabbed only when their sections do not fit the column") {
    LayoutRequest r = request(1280, 800, 1.0f);
    r.controls_need_h = r.area.h - 10;
    CHECK_FALSE(compute_layout(r).controls_tabbed);
    r.controls_need_h = r.area.h + 10;
    CHECK(compute_layout(r).controls_tabbed);
    r.controls_need_h = 0;   // not measured yet: stacked, so that the next frame measures every section
    CHECK_FALSE(compute_layout(r).controls_tabbed);
}

TEST_CASE("layout: hidden panels give their space to the others; maximise fills the plot area") {
    for (float scale : {1.0f, 1.5f, 2.0f}) {
        CAPTURE(scale);
        LayoutRequest r = request(1280, 800, scale);
        const Layout full = compute_layout(r);
        r.visible[static_cast<std::size_t>(PanelId::Bifurcation)] = false;
        r.visible[static_cast<std::size_t>(PanelId::Strip)] = false;
        const Layout less = compute_layout(r);
        check_sound(r, less);
        CHECK(count_of(less, PanelId::Bifurcation) == 0);
        CHECK(covered(less) == doctest::Approx(covered(full)));   // the space went to the others
        // The rig alone on its row: as wide as the plot area.
        CHECK(less.tiles[0].rect.w == doctest::Approx(r.area.w - less.controls.w));

        r.maximised = PanelId::Poincare;
        const Layout max = compute_layout(r);
        check_sound(r, max);
        REQUIRE(max.tiles.size() == 1);
        CHECK(max.tiles[0].panels == std::vector<PanelId>{PanelId::Poincare});
        CHECK(max.tiles[0].rect.w == doctest::Approx(r.area.w - max.controls.w));
        CHECK(max.tiles[0].rect.h == doctest::Approx(r.area.h));
        // A hidden panel cannot be maximised: the normal layout stays.
        r.maximised = PanelId::Strip;
        CHECK(compute_layout(r).tiles.size() > 1);
    }
    // Without the controls the plots take the whole width.
    LayoutRequest r = request(1024, 768, 1.0f);
    r.controls_visible = false;
    const Layout l = compute_layout(r);
    check_sound(r, l);
    CHECK(l.controls.empty());
    CHECK(covered(l) == doctest::Approx(r.area.w * r.area.h));
}

TEST_CASE("layout: presentation mode is the rig and one plot under a slim bar") {
    for (auto [w, h] : {std::pair{1024.0f, 768.0f}, std::pair{1280.0f, 800.0f}, std::pair{800.0f, 1000.0f}}) {
        for (float scale : {1.0f, 1.5f, 2.0f}) {
            CAPTURE(w);
            CAPTURE(scale);
            LayoutRequest r = request(w, h, scale);
            r.mode = LayoutMode::Presentation;
            r.featured = PanelId::Poincare;
            const Layout l = compute_layout(r);
            check_sound(r, l);
            CHECK(l.controls.empty());
            REQUIRE(l.tiles.size() == 2);
            CHECK(l.tiles[0].panels == std::vector<PanelId>{PanelId::Rig});
            CHECK(l.tiles[1].panels == std::vector<PanelId>{PanelId::Poincare});
            // Slim: the bar takes under a fifth of the height; the rig and the plot share the rest.
            CHECK(l.bar.h < 0.2f * r.area.h);
            CHECK(l.bar.h >= static_cast<float>(l.bar_lines) * r.frame_h);
            CHECK(covered(l) == doctest::Approx(r.area.w * r.area.h));
            CHECK(l.tiles[1].rect.w * l.tiles[1].rect.h > 0.3f * r.area.w * r.area.h);
        }
    }
    LayoutRequest r = request(1280, 800, 2.0f);
    r.mode = LayoutMode::Presentation;
    CHECK(compute_layout(r).bar_lines == 2);   // the bar wraps at scale 2
    r.maximised = PanelId::Rig;
    const Layout m = compute_layout(r);
    REQUIRE(m.tiles.size() == 1);
    CHECK(m.tiles[0].rect.w == doctest::Approx(1280));
}

TEST_CASE("layout: degenerate requests lay out nothing or something sound, never crash") {
    for (float scale : {0.0f, -1.0f, 0.5f, 3.0f, std::nanf("")}) {
        for (float w : {0.0f, 1.0f, 50.0f, 300.0f, 1280.0f}) {
            for (float h : {0.0f, 1.0f, 50.0f, 800.0f}) {
                for (LayoutMode mode : {LayoutMode::Normal, LayoutMode::Presentation}) {
                    LayoutRequest r;
                    r.area = {0, 20, w, h};
                    r.scale = scale;
                    r.mode = mode;
                    const Layout l = compute_layout(r);
                    for (const Tile& t : l.tiles) {
                        CHECK_FALSE(t.panels.empty());
                        CHECK(contains(r.area, t.rect));
                    }
                }
            }
        }
    }
    LayoutRequest r;
    r.area = {0, 0, std::numeric_limits<float>::infinity(), 800};
    CHECK(compute_layout(r).tiles.empty());
}

TEST_CASE("layout: panel keys round-trip, unknown keys are refused") {
    for (int p = 0; p < kPanelCount; ++p) CHECK(panel_from_key(panel_key(static_cast<PanelId>(p))) == static_cast<PanelId>(p));
    CHECK_FALSE(panel_from_key("controls").has_value());
    CHECK_FALSE(panel_from_key("").has_value());
    CHECK(panel_keys().find("poincare") != std::string::npos);
}

TEST_CASE("label placer: no label overprints another or leaves the drawing") {
    LabelPlacer lp({0, 0, 400, 200});
    CHECK(lp.place({10, 10, 100, 20}));
    CHECK_FALSE(lp.place({60, 15, 100, 20}));    // over the first
    CHECK_FALSE(lp.place({350, 10, 100, 20}));   // past the right edge (it was once clipped at xI = 20 mm)
    CHECK(lp.place_first({{60, 15, 100, 20}, {60, 40, 100, 20}}) == 1);   // the second candidate
    CHECK(lp.place_first({{-5, 0, 10, 10}}) == -1);
    for (std::size_t i = 0; i < lp.placed().size(); ++i)
        for (std::size_t j = i + 1; j < lp.placed().size(); ++j) CHECK_FALSE(overlaps(lp.placed()[i], lp.placed()[j]));
    // Touching edges are no overlap.
    CHECK_FALSE(overlaps({0, 0, 10, 10}, {10, 0, 10, 10}));
    // A reserved box (the rig's end wall, reaching past the right edge) takes its room without a label.
    lp.reserve({380, 0, 40, 200});
    CHECK_FALSE(lp.place({300, 150, 90, 20}));   // would cover the wall
    CHECK(lp.place({280, 150, 90, 20}));         // clear of it
}

TEST_CASE("rig magnification: a contact stays a contact, the walls make room for the travel") {
    for (double g : {1.0, 2.0, 4.0, 10.0}) {
        CAPTURE(g);
        const RigMagnify m{g};
        // The cart's right face at x = xI meets the bumper's face, both drawn magnified about the same origin.
        for (double xI : {-0.02, 0.0, 0.005, 0.02}) {
            CHECK(m.cart_face(xI) == doctest::Approx(m.bumper_face(xI)));
            // A cart 1 mm short of the bumper is drawn g mm short of it.
            CHECK(m.bumper_face(xI) - m.cart_face(xI - 0.001) == doctest::Approx(0.001 * g));
        }
        // Displacements are magnified about x = 0.
        CHECK(m.draw_x(0.0) == 0.0);
        CHECK(m.draw_x(-0.011) == doctest::Approx(-0.011 * g));
        // At the usual reach the cart stays clear of the walls with room for the springs, and far beyond it
        // it is held off them.
        CHECK(m.wall_x() - m.cart_face(RigMagnify::kTravel) >= RigMagnify::kSpringRoom - 1e-12);
        CHECK(m.wall_x() - m.cart_face(0.09) > 0);
        CHECK(m.draw_x(-0.09) - RigMagnify::kCartHalfW > -m.wall_x());
        CHECK(m.wall_x() >= RigMagnify::kWallX);
    }
    CHECK(RigMagnify{1.0}.wall_x() == doctest::Approx(RigMagnify::kWallX));   // x1: the rig as built
}
