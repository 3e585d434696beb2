// Headless PNG plots: layout, mapping, ticks, text and robustness.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>

#include "impactlab/plot.hpp"

namespace plot = impactlab::plot;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Luminance-ish darkness of a pixel: 0 for white, 255 for black.
int darkness(const plot::Image& img, int x, int y) {
    const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(img.width) + static_cast<std::size_t>(x)) * 4;
    return 255 - (img.rgba[i] + img.rgba[i + 1] + img.rgba[i + 2]) / 3;
}

int dark_pixels(const plot::Image& img, int x0, int y0, int x1, int y1, int threshold = 100) {
    int n = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
            if (darkness(img, x, y) > threshold) ++n;
    return n;
}

plot::Figure one_panel(plot::Series s) {
    plot::Figure fig;
    fig.width = 600;
    fig.panel_height = 300;
    fig.panels.resize(1);
    fig.panels[0].series.push_back(std::move(s));
    return fig;
}

plot::Series make(plot::Series::Kind kind, std::vector<double> x, std::vector<double> y) {
    plot::Series s;
    s.kind = kind;
    s.x = std::move(x);
    s.y = std::move(y);
    return s;
}

bool is_nice(double step) {
    const double e = std::floor(std::log10(step));
    const double m = step / std::pow(10.0, e);
    return std::abs(m - 1) < 1e-9 || std::abs(m - 2) < 1e-9 || std::abs(m - 5) < 1e-9;
}

}  // namespace

TEST_CASE("plot: nice_ticks uses 1-2-5 steps that cover the range") {
    const double ranges[][2] = {{0, 1}, {-3.7, 12.2}, {0.0013, 0.0051}, {-1e-7, 3e-7}, {25.0 / 300.0, 25.0},
                                {1e6, 1e6 + 3}, {-250, -3}, {0.999, 1.001}};
    for (const auto& r : ranges) {
        for (int max_count : {2, 5, 8, 12}) {
            CAPTURE(r[0]);
            CAPTURE(r[1]);
            CAPTURE(max_count);
            const auto t = plot::nice_ticks(r[0], r[1], max_count);
            REQUIRE(!t.empty());
            CHECK(static_cast<int>(t.size()) <= max_count);
            const double step = plot::nice_step(r[0], r[1], max_count);
            CHECK(is_nice(step));
            const double tol = 1e-9 * step;
            CHECK(t.front() >= r[0] - tol);
            CHECK(t.back() <= r[1] + tol);
            CHECK(t.front() - r[0] < step);   // covers the range: no gap of a whole step at either end
            CHECK(r[1] - t.back() < step);
            for (std::size_t i = 1; i < t.size(); ++i) CHECK(t[i] - t[i - 1] == doctest::Approx(step).epsilon(1e-9));
        }
    }
    const auto t = plot::nice_ticks(0, 1, 6);
    REQUIRE(t.size() == 6);
    CHECK(t[3] == 0.6);   // exact decimal values, not 0.6000000000000001
    CHECK(plot::nice_ticks(3, 3, 5) == std::vector<double>{3});
    CHECK(plot::nice_ticks(kNaN, 1, 5).empty());
    CHECK(plot::nice_ticks(0, kInf, 5).empty());
    CHECK(plot::nice_ticks(1, 0, 3) == plot::nice_ticks(0, 1, 3));
}

TEST_CASE("plot: nice_step is the GUI's tick rule too: a step in the shown unit, 0 where no ticks are drawn") {
    // The GUI's plots ask in their label unit (here mm over a 26 mm travel) for at most n ticks.
    CHECK(plot::nice_step(-13.0, 13.0, 8) == 5.0);
    CHECK(plot::nice_step(-13.0, 13.0, 3) == 10.0);   // -10, 0, 10
    CHECK(plot::nice_step(0.0, 1.0, 6) == 0.2);
    // The GUI steps through v += step: it must get 0 (and draw no ticks) for an empty or broken range.
    CHECK(plot::nice_step(3, 3, 5) == 0.0);
    CHECK(plot::nice_step(kNaN, 1, 5) == 0.0);
    CHECK(plot::nice_step(0, kInf, 5) == 0.0);
}

TEST_CASE("plot: tick labels") {
    CHECK(plot::format_ticks({-1, -0.5, 0, 0.5, 1}, 0.5) == std::vector<std::string>{"-1.0", "-0.5", "0.0", "0.5", "1.0"});
    CHECK(plot::format_ticks({0, 0.01, 0.02}, 0.01) == std::vector<std::string>{"0.00", "0.01", "0.02"});
    CHECK(plot::format_ticks({0, 10, 20}, 10) == std::vector<std::string>{"0", "10", "20"});
    CHECK(plot::format_ticks({-0.005, -0.0045, 0, 0.005}, 5e-4) ==
          std::vector<std::string>{"-5e-3", "-4.5e-3", "0", "5e-3"});
    CHECK(plot::format_ticks({0, 5e4, 1e5, 1.5e5}, 5e4) == std::vector<std::string>{"0", "5e4", "1e5", "1.5e5"});
    CHECK(plot::format_ticks({1e-4, 2e-4}, 1e-4) == std::vector<std::string>{"1e-4", "2e-4"});
    CHECK(plot::format_ticks({0.0095, 0.01}, 5e-4) == std::vector<std::string>{"0.0095", "0.0100"});
    // Nothing prints as "-0".
    const auto t = plot::nice_ticks(-1e-17 - 0.2, 0.2, 5);
    for (const auto& s : plot::format_ticks(t, plot::nice_step(-1e-17 - 0.2, 0.2, 5))) {
        CAPTURE(s);
        const bool negative_zero = s.rfind("-0", 0) == 0 && s.find_first_not_of("-0.") == std::string::npos;
        CHECK_FALSE(negative_zero);
    }
    CHECK(plot::format_ticks({-1e-20}, 0.1) == std::vector<std::string>{"0.0"});
}

TEST_CASE("plot: render makes an image of the documented size") {
    plot::Figure fig = one_panel(make(plot::Series::Kind::Line, {0, 1, 2}, {0, 1, 0}));
    fig.panels.push_back(fig.panels[0]);
    fig.panels.push_back(fig.panels[0]);
    fig.width = 800;
    fig.panel_height = 250;
    const plot::Image img = plot::render(fig);
    CHECK(img.width == 800);
    CHECK(img.height == 750);
    CHECK(img.rgba.size() == 800u * 750u * 4u);
    const auto size = plot::image_size(fig);
    CHECK(size.width == 800);
    CHECK(size.height == 750);

    fig.title = "Title";
    const plot::Image titled = plot::render(fig);
    CHECK(titled.height > 750);
    CHECK(titled.height == plot::image_size(fig).height);
    CHECK(darkness(titled, 0, 0) == 0);   // white background
}

TEST_CASE("plot: points land where the mapping says") {
    plot::Series s;
    s.kind = plot::Series::Kind::Points;
    s.x = {0.0, 10.0, 3.0, 7.5};
    s.y = {0.0, 1.0, 0.8, 0.25};
    s.size = 2.5f;
    s.color = {0, 0, 0, 255};
    plot::Figure fig = one_panel(s);
    fig.panels[0].xmin = -1;
    fig.panels[0].xmax = 11;
    fig.panels[0].ymin = -0.1;
    fig.panels[0].ymax = 1.1;
    fig.panels[0].grid = false;
    const auto maps = plot::layout(fig);
    REQUIRE(maps.size() == 1);
    const plot::Mapping& m = maps[0];
    CHECK(m.xmin == -1);
    CHECK(m.xmax == 11);
    CHECK(m.left < m.right);
    CHECK(m.top < m.bottom);
    CHECK(m.px(-1) == doctest::Approx(m.left));
    CHECK(m.px(11) == doctest::Approx(m.right));
    CHECK(m.py(-0.1) == doctest::Approx(m.bottom));
    CHECK(m.py(1.1) == doctest::Approx(m.top));

    const plot::Image img = plot::render(fig);
    for (std::size_t i = 0; i < s.x.size(); ++i) {
        CAPTURE(i);
        CHECK(darkness(img, m.col(s.x[i]), m.row(s.y[i])) > 200);
    }
    // Away from the points (and from frame, grid and text) the plot area stays white.
    CHECK(darkness(img, m.col(5.0), m.row(0.5)) == 0);
    CHECK(dark_pixels(img, m.col(4.0), m.row(0.6), m.col(6.0), m.row(0.4), 1) == 0);
}

TEST_CASE("plot: dense points are alpha-blended, overlaps get darker") {
    plot::Series one, many;
    one.x = {1.0};
    one.y = {1.0};
    many.x.assign(20, 3.0);
    many.y.assign(20, 1.0);
    for (auto* s : {&one, &many}) {
        s->color = {0, 0, 0, 40};
        s->size = 0.5f;
    }
    plot::Figure fig = one_panel(one);
    fig.panels[0].series.push_back(many);
    fig.panels[0].xmin = 0;
    fig.panels[0].xmax = 4;
    fig.panels[0].ymin = 0;
    fig.panels[0].ymax = 2;
    const auto m = plot::layout(fig)[0];
    const plot::Image img = plot::render(fig);
    const int light = darkness(img, m.col(1.0), m.row(1.0));
    const int dark = darkness(img, m.col(3.0), m.row(1.0));
    CHECK(light > 0);
    CHECK(light < 60);
    CHECK(dark > 3 * light);
}

TEST_CASE("plot: lines are drawn, clipped, and broken by NaN") {
    plot::Series s;
    s.kind = plot::Series::Kind::Line;
    s.x = {0, 1, 2, 3, 4, 5, 6};
    s.y = {0.5, 0.5, 0.5, kNaN, 0.5, 0.5, 100};   // the last segment leaves the plot area
    s.color = {0, 0, 0, 255};
    s.size = 1.5f;
    plot::Figure fig = one_panel(s);
    fig.panels[0].xmin = 0;
    fig.panels[0].xmax = 6;
    fig.panels[0].ymin = 0;
    fig.panels[0].ymax = 1;
    fig.panels[0].grid = false;
    const auto m = plot::layout(fig)[0];
    const plot::Image img = plot::render(fig);
    CHECK(darkness(img, m.col(1.5), m.row(0.5)) > 150);
    CHECK(darkness(img, m.col(4.5), m.row(0.5)) > 150);
    CHECK(darkness(img, m.col(3.0), m.row(0.5)) < 30);   // the gap around the NaN
    // Nothing above the frame: the steep last segment is clipped.
    REQUIRE(m.top >= 8);
    CHECK(dark_pixels(img, m.col(5.2), 0, m.col(5.8), m.top - 1, 1) == 0);
}

TEST_CASE("plot: text renders") {
    plot::Figure fig = one_panel(make(plot::Series::Kind::Points, {0, 1}, {0, 1}));
    const plot::Image plain = plot::render(fig);
    const auto m = plot::layout(fig)[0];
    fig.title = "Bifurcation diagram";
    fig.panels[0].title = "panel title";
    fig.panels[0].xlabel = "ω / ω₀";
    fig.panels[0].ylabel = "x (mm)";
    const plot::Image img = plot::render(fig);
    const auto mt = plot::layout(fig)[0];
    const int title_h = img.height - plain.height;   // the figure title band
    REQUIRE(title_h > 10);
    CHECK(dark_pixels(img, 0, 0, img.width, title_h) > 50);
    CHECK(dark_pixels(img, 0, 0, 150, title_h, 1) == 0);   // centred
    CHECK(dark_pixels(img, img.width - 150, 0, img.width, title_h, 1) == 0);
    // Panel title between the figure title band and the plot area; x label below the tick labels;
    // y label left of the tick labels.
    CHECK(dark_pixels(img, mt.left, title_h, mt.right, mt.top - 1) > 30);
    CHECK(dark_pixels(img, mt.left, mt.bottom + 25, mt.right, img.height) > 30);
    CHECK(dark_pixels(img, 0, mt.top, 25, mt.bottom) > 30);
    // Tick labels under the x axis.
    CHECK(dark_pixels(plain, m.left, m.bottom + 6, m.right, m.bottom + 25) > 30);
}

TEST_CASE("plot: legend appears when a series has a label") {
    plot::Series s = make(plot::Series::Kind::Line, {0, 1}, {0, 0});
    s.color = {0, 0, 255, 255};
    s.size = 2.0f;
    plot::Figure fig = one_panel(s);
    fig.panels[0].legend = plot::LegendPlace::UpperRight;
    const auto m = plot::layout(fig)[0];
    const plot::Image without = plot::render(fig);
    fig.panels[0].series[0].label = "sin(t)";
    const plot::Image with = plot::render(fig);
    const int x0 = m.right - 150, y0 = m.top + 2, x1 = m.right - 2, y1 = m.top + 40;
    CHECK(dark_pixels(with, x0, y0, x1, y1) > dark_pixels(without, x0, y0, x1, y1) + 20);
}

TEST_CASE("plot: automatic ranges from degenerate data") {
    SUBCASE("a single point") {
        plot::Figure fig = one_panel(make(plot::Series::Kind::Points, {2.0}, {-3.0}));
        const auto m = plot::layout(fig)[0];
        CHECK(m.xmin < 2.0);
        CHECK(m.xmax > 2.0);
        CHECK(m.ymin < -3.0);
        CHECK(m.ymax > -3.0);
        const auto img = plot::render(fig);
        CHECK(darkness(img, m.col(2.0), m.row(-3.0)) > 100);
    }
    SUBCASE("zero") {
        plot::Figure fig = one_panel(make(plot::Series::Kind::Points, {0.0, 0.0}, {0.0, 0.0}));
        const auto m = plot::layout(fig)[0];
        CHECK(m.xmin < 0.0);
        CHECK(m.xmax > 0.0);
    }
    SUBCASE("NaN and infinite values are ignored") {
        plot::Figure fig = one_panel(make(plot::Series::Kind::Points, {kNaN, 1.0, kInf, 3.0, 2.0}, {5.0, 1.0, 7.0, -kInf, 2.0}));
        const auto m = plot::layout(fig)[0];
        CHECK(m.xmin < 1.0);
        CHECK(m.xmin > 0.8);
        CHECK(m.xmax > 2.0);
        CHECK(m.xmax < 2.2);
        CHECK(m.ymin > 0.8);
        CHECK(m.ymax < 2.2);
        CHECK_NOTHROW(plot::render(fig));
    }
    SUBCASE("all NaN, empty series, no series") {
        plot::Figure fig = one_panel(make(plot::Series::Kind::Line, {kNaN, kNaN}, {kNaN, 1.0}));
        fig.panels[0].series.push_back({});
        fig.panels.push_back({});
        const auto maps = plot::layout(fig);
        for (const auto& m : maps) {
            CHECK(std::isfinite(m.xmin));
            CHECK(m.xmin < m.xmax);
            CHECK(m.ymin < m.ymax);
        }
        CHECK_NOTHROW(plot::render(fig));
    }
    SUBCASE("one fixed limit beyond the data") {
        plot::Figure fig = one_panel(make(plot::Series::Kind::Points, {1.0, 2.0}, {1.0, 2.0}));
        fig.panels[0].xmin = 5.0;
        const auto m = plot::layout(fig)[0];
        CHECK(m.xmin == 5.0);
        CHECK(m.xmax > 5.0);
        CHECK_NOTHROW(plot::render(fig));
    }
    SUBCASE("huge values, markers and shading outside the range") {
        plot::Figure fig = one_panel(make(plot::Series::Kind::Line, {0, 1e308, -1e308, 1}, {0, 1, 1e308, 1}));
        fig.panels[0].series.push_back(make(plot::Series::Kind::Points, {0, 1e300}, {1e-300, -1e300}));
        fig.panels[0].vlines = {kNaN, -1e300, 0.5};
        fig.panels[0].shade_x = {{kNaN, 1}, {-kInf, kInf}};
        CHECK_NOTHROW(plot::render(fig));
    }
}

TEST_CASE("plot: invalid figures throw std::invalid_argument") {
    plot::Figure fig = one_panel(make(plot::Series::Kind::Points, {0, 1}, {0, 1}));
    SUBCASE("too narrow") {
        fig.width = 40;
        CHECK_THROWS_AS(plot::render(fig), std::invalid_argument);
        try {
            plot::render(fig);
        } catch (const std::invalid_argument& e) {
            CHECK(std::string(e.what()).find("too small") != std::string::npos);
        }
    }
    SUBCASE("too flat") {
        fig.panel_height = 30;
        CHECK_THROWS_AS(plot::render(fig), std::invalid_argument);
    }
    SUBCASE("zero size") {
        fig.width = 0;
        CHECK_THROWS_AS(plot::render(fig), std::invalid_argument);
    }
    SUBCASE("no panels") {
        fig.panels.clear();
        CHECK_THROWS_AS(plot::render(fig), std::invalid_argument);
    }
    SUBCASE("x and y of different lengths") {
        fig.panels[0].series[0].y.pop_back();
        CHECK_THROWS_AS(plot::render(fig), std::invalid_argument);
    }
    SUBCASE("xmin > xmax") {
        fig.panels[0].xmin = 2;
        fig.panels[0].xmax = 1;
        CHECK_THROWS_AS(plot::render(fig), std::invalid_argument);
    }
}

TEST_CASE("plot: save_png writes a PNG and reports unwritable paths") {
    plot::Figure fig = one_panel(make(plot::Series::Kind::Line, {0, 1, 2}, {1, 0, 1}));
    fig.width = 300;
    fig.panel_height = 150;
    const std::string bad = "/nonexistent-directory/impactlab/plot.png";
    try {
        plot::save_png(fig, bad);
        FAIL("save_png to an unwritable path did not throw");
    } catch (const std::runtime_error& e) {
        CHECK(std::string(e.what()) == bad + ": cannot write it (No such file or directory)");
    }
    const std::string good = (std::filesystem::temp_directory_path() / "impactlab_plot_test.png").string();
    plot::save_png(fig, good);
    std::ifstream in(good, std::ios::binary);
    REQUIRE(in.good());
    char magic[8] = {};
    in.read(magic, 8);
    CHECK(std::string(magic + 1, 3) == "PNG");
    in.close();
    std::remove(good.c_str());
}

TEST_CASE("plot: a million points render quickly") {
    plot::Series s;
    s.color = {0, 0, 80, 30};
    s.size = 0.5f;
    const std::size_t n = 1000000;
    s.x.resize(n);
    s.y.resize(n);
    double x = 0.3;
    for (std::size_t i = 0; i < n; ++i) {
        const double r = 2.8 + 1.2 * static_cast<double>(i % 1000) / 1000.0;
        x = r * x * (1 - x);
        s.x[i] = r;
        s.y[i] = x;
    }
    plot::Figure fig = one_panel(std::move(s));
    fig.width = 1200;
    const auto t0 = std::chrono::steady_clock::now();
    const plot::Image img = plot::render(fig);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    MESSAGE("1e6 points rendered in " << seconds << " s");
    CHECK(img.width == 1200);
    CHECK(seconds < 2.0);   // ~0.05 s optimised; generous for sanitizer and debug builds
}
