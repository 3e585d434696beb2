// A parameter plane as the visualiser shows it: a scan CSV (`impactlab scan`: the two axis names,
// then one column per measure, the first axis fastest) or a plane computed by the core's scan_rows, as a
// regular grid; where a click lands on it; where the bifurcation diagram cuts it. GL-free, UI thread
// (loading runs on whatever thread calls it).
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "impactlab/scan.hpp"

namespace impactlab::gui {

// A CSV that is not a plane: the message starts with "FILE:LINE: " (LINE 0 when the file cannot be read).
struct PlaneError : std::runtime_error { using std::runtime_error::runtime_error; };

struct PlaneData {
    std::string source;                        // the file, or "computed: A1C" for a plane from the worker
    std::string x_name, y_name;                // "omega", "xI" or "m0e"
    std::vector<double> xs, ys;                // the axes' values (the grid's columns and rows), increasing
    std::vector<std::string> measures;         // the columns after the axes ("period", "impacts", ...)
    std::vector<std::vector<double>> values;   // values[m][j * nx + i] at (xs[i], ys[j]); NaN: not computed
    int nx() const { return static_cast<int>(xs.size()); }
    int ny() const { return static_cast<int>(ys.size()); }
    int measure_index(const std::string& name) const;   // -1 when absent
};

// Reads a scan CSV. Throws PlaneError naming the file and line: an unreadable file, a header without two
// axes (omega, xI, m0e) and a measure, a row with the wrong number of fields or a field that is no number,
// rows that do not form a grid with the first axis fastest.
PlaneData load_plane_csv(const std::string& path);

// The rows of a scan as a plane (rows not computed, e.g. after a cancel, stay NaN).
PlaneData plane_from_scan(const ScanSpec& spec, const std::vector<std::vector<ScanPoint>>& rows, const std::string& source);

// The cell under a point of the plot, given as fractions of the plot area (fx from left to right, fy from
// bottom to top, both in [0, 1]); none outside. The cells are centred on the grid values.
struct PlaneCell {
    int i = 0, j = 0;
    double x = 0, y = 0;   // the axes' values at the cell (xs[i], ys[j])
};
std::optional<PlaneCell> plane_pick(const PlaneData& plane, double fx, double fy);

// What a click on a cell asks of the live simulation: omega and the bumper xI where they are axes (m0e is no
// live parameter: `ignored` names it).
struct PlaneClick {
    std::optional<double> omega, xI;
    std::string ignored;   // "m0e" when an axis could not be applied, else ""
};
PlaneClick plane_click(const PlaneData& plane, const PlaneCell& cell);

// Where the bifurcation diagram (omega from omega_lo to omega_hi at fixed xI and m0e) lies on the plane, in
// the plane's (x, y) data coordinates: a segment when omega is an axis, a point when it is not, none when
// it misses the plane's ranges.
struct PlaneSegment {
    double x0, y0, x1, y1;
};
std::optional<PlaneSegment> diagram_cut(const PlaneData& plane, double omega_lo, double omega_hi, double xI, double m0e);

// Cell extent of the plot: from half a cell before the first value to half a cell after the last.
struct PlaneExtent {
    double x_lo, x_hi, y_lo, y_hi;
};
PlaneExtent plane_extent(const PlaneData& plane);

}  // namespace impactlab::gui
