// Headless PNG plots for the command-line tool: stacked panels of scatter points and polylines,
// rendered on the CPU into an RGBA image (text with stb_truetype, PNG with stb_image_write).
// No GL, no windowing: safe to call from any thread, also concurrently.
//
// Pixel convention (used by Mapping and the tests): image pixel (col, row) covers the square
// [col, col+1) x [row, row+1) of continuous image coordinates; row 0 is the top of the image.
// A data point (x, y) of panel p lands at continuous coordinates (m.px(x), m.py(y)) with
// m = layout(fig)[p], i.e. in pixel (m.col(x), m.row(y)).
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace impactlab::plot {

struct Color { std::uint8_t r, g, b, a = 255; };

struct Series {
    enum class Kind { Line, Points };
    Kind kind = Kind::Points;
    std::vector<double> x, y;        // same length (std::invalid_argument otherwise); non-finite pairs are
                                     // skipped, and a non-finite pair breaks a Line into pieces
    Color color{20, 20, 20, 255};    // for dense scatter plots use a < 255: overlapping points get darker
    float size = 1.0f;               // Line: width in px; Points: dot radius in px (<= 0.5: a one-pixel dot)
    std::string label;               // shown in a legend if any series of the panel has a label
};

enum class LegendPlace { Auto, UpperRight, UpperLeft, LowerRight, LowerLeft };  // Auto: least covered corner

struct Panel {
    std::string title, xlabel, ylabel;   // UTF-8 (Latin-1, Greek and a few math symbols are available)
    std::vector<Series> series;
    // NaN (or infinite) = automatic from the finite data, with a 3 % margin; each limit independently.
    double xmin = std::numeric_limits<double>::quiet_NaN(), xmax = std::numeric_limits<double>::quiet_NaN();
    double ymin = std::numeric_limits<double>::quiet_NaN(), ymax = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> vlines;                      // vertical marker lines (e.g. the current omega)
    std::vector<std::pair<double, double>> shade_x;  // shaded x-intervals
    Color vline_color{214, 39, 40, 220};
    Color shade_color{31, 119, 180, 40};
    bool grid = true;                                // light grid lines at the ticks
    LegendPlace legend = LegendPlace::Auto;
};

// Panels are stacked vertically below the optional figure title; each has its own ranges and ticks,
// but all plot areas share the same left edge so that stacked panels line up.
struct Figure {
    int width = 1200;
    int panel_height = 300;
    std::string title;
    std::vector<Panel> panels;
    float font_scale = 1.0f;   // multiplies every font size and the text margins (not line widths or dots)
};

struct Image {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;   // row-major, top row first, 4 bytes per pixel
};

// Where the data of one panel goes. The plot area is columns [left, right) and rows [top, bottom);
// xmin maps to the left edge of column `left`, xmax to the right edge of column right-1, ymin to the
// bottom edge of row bottom-1 and ymax to the top edge of row `top`. The ranges are the final ones
// (automatic limits resolved, degenerate ranges padded): xmin < xmax and ymin < ymax always.
struct Mapping {
    int left = 0, top = 0, right = 0, bottom = 0;
    double xmin = 0, xmax = 1, ymin = 0, ymax = 1;

    double px(double x) const { return left + (x - xmin) / (xmax - xmin) * (right - left); }
    double py(double y) const { return bottom - (y - ymin) / (ymax - ymin) * (bottom - top); }
    int col(double x) const { return static_cast<int>(std::floor(px(x))); }
    int row(double y) const { return static_cast<int>(std::floor(py(y))); }
};

// Size of the image render(fig) makes: fig.width x (title height + panels * panel_height).
struct Size { int width = 0, height = 0; };
Size image_size(const Figure& fig);

// One Mapping per panel, exactly as render() uses them. Needs the font (it measures tick labels).
// Throws std::invalid_argument when the figure has no panels, a series has x/y of different lengths,
// a panel has xmin > xmax (or ymin > ymax) given explicitly, or the figure is too small for a plot area.
std::vector<Mapping> layout(const Figure& fig);

// Tick positions: multiples of a "nice" step (1, 2 or 5 times a power of ten) inside [lo, hi]
// (with a relative tolerance of 1e-9 of the step at both ends), at most max(max_count, 1) of them,
// using the smallest such step. The first tick is less than one step above lo and the last less than
// one step below hi. lo > hi are swapped; lo == hi gives {lo}; non-finite input, or hi - lo below 1e-300
// or overflowing, gives {}.
std::vector<double> nice_ticks(double lo, double hi, int max_count);
// The step nice_ticks(lo, hi, max_count) uses (0 when it returns {} or {lo}).
double nice_step(double lo, double hi, int max_count);
// Labels for ticks spaced by `step`: fixed notation with the decimals the step needs ("0.05", "-1.5",
// "20"), or, when the largest |tick| is >= 1e5 or < 1e-2, short scientific notation ("-5e-3", "2.5e5").
// Never "-0": a tick within 1e-9 step of zero is written as zero.
std::vector<std::string> format_ticks(const std::vector<double>& ticks, double step);

Image render(const Figure& fig);
// Throws std::runtime_error("PATH: cannot write it (REASON)" or "PATH: write failed (REASON)") when the file cannot
// be written whole (a missing folder, a full disk); an old file at PATH is then left as it was.
void save_png(const Figure& fig, const std::string& path);
void save_png(const Image& image, const std::string& path);

// The TrueType font the text is drawn with. Core knows no path of its own: the program finds its font
// (beside itself when installed, the source tree's assets/ in a build) and hands the files to try here, in
// order, before the first text is drawn. The first that loads is kept for the process; a call after that
// changes nothing.
void set_font_files(std::vector<std::string> candidates);
// Path of the font in use. Throws std::runtime_error naming every path tried when none of the files handed
// in can be read (or that none was handed in).
const std::string& font_path();
// The first of `candidates` that loads as a TrueType font; throws as font_path() does. Loads nothing for
// the process.
std::string first_usable_font(const std::vector<std::string>& candidates);

}  // namespace impactlab::plot
