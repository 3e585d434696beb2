#include "plane_data.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <string_view>

#include "impactlab/input_file.hpp"

namespace impactlab::gui {

namespace {

bool is_axis(const std::string& s) { return s == "omega" || s == "xI" || s == "m0e"; }

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> out;
    std::size_t start = 0;
    for (;;) {
        const std::size_t c = line.find(',', start);
        std::string f = line.substr(start, c == std::string::npos ? std::string::npos : c - start);
        // Trim blanks (a hand-edited file): the scan writes none.
        const auto b = f.find_first_not_of(" \t"), e = f.find_last_not_of(" \t");
        out.push_back(b == std::string::npos ? std::string() : f.substr(b, e - b + 1));
        if (c == std::string::npos) break;
        start = c + 1;
    }
    return out;
}

[[noreturn]] void fail(const std::string& path, std::size_t line, const std::string& what) {
    throw PlaneError(path + ":" + std::to_string(line) + ": " + what);
}

// Two axis values are the same grid value: the scan prints them to round-trip, a hand-made file may not.
bool same(double a, double b, double span) { return std::abs(a - b) <= 1e-9 * std::max(span, 1e-300) + 1e-15; }

}  // namespace

int PlaneData::measure_index(const std::string& name) const {
    for (std::size_t m = 0; m < measures.size(); ++m)
        if (measures[m] == name) return static_cast<int>(m);
    return -1;
}

PlaneData load_plane_csv(const std::string& path) {
    std::istringstream in;
    try {
        in.str(read_input_file(path));
    } catch (const InputFileError& e) {
        throw PlaneError(e.what());
    }
    std::string line;
    std::size_t lineno = 0;
    // Header.
    while (std::getline(in, line)) {
        ++lineno;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (!line.empty()) break;
    }
    if (line.empty()) fail(path, lineno, "empty file (a scan CSV starts with a header such as omega,xI,period)");
    const std::vector<std::string> head = split(line);
    if (head.size() < 3 || !is_axis(head[0]) || !is_axis(head[1]) || head[0] == head[1])
        fail(path, lineno, "the header '" + line + "' does not start with two different axes (omega, xI, m0e) and a measure");
    PlaneData p;
    p.source = path;
    p.x_name = head[0];
    p.y_name = head[1];
    p.measures.assign(head.begin() + 2, head.end());
    p.values.resize(p.measures.size());

    // Rows: x fastest. The first row's x values are the grid's columns; every row must repeat them.
    std::size_t row_line = 0;   // the line where the current row of the grid started
    std::size_t i = 0;          // position in the current row
    std::vector<double> fields(head.size());
    while (std::getline(in, line)) {
        ++lineno;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty()) continue;
        const std::vector<std::string> f = split(line);
        if (f.size() != head.size())
            fail(path, lineno, "expected " + std::to_string(head.size()) + " fields (" + std::to_string(head.size()) +
                                   " columns in the header), got " + std::to_string(f.size()));
        for (std::size_t k = 0; k < f.size(); ++k) {
            char* end = nullptr;
            fields[k] = std::strtod(f[k].c_str(), &end);
            if (f[k].empty() || *end != '\0')
                fail(path, lineno, "'" + f[k] + "' in column " + head[k] + " is not a number");
            if (k < 2 && !std::isfinite(fields[k])) fail(path, lineno, "the axis value " + head[k] + " = " + f[k] + " is not finite");
        }
        const double x = fields[0], y = fields[1];
        if (p.ys.empty()) {   // the first point
            p.ys.push_back(y);
            row_line = lineno;
        }
        if (p.ys.size() == 1 && same(y, p.ys[0], std::abs(y))) {   // still the first row: it defines the columns
            if (!p.xs.empty() && !(x > p.xs.back()))
                fail(path, lineno, p.x_name + " = " + f[0] + " does not increase along the row (the first axis must be the fastest)");
            p.xs.push_back(x);
            i = p.xs.size();
        } else {
            if (i == p.xs.size()) {   // a new row
                if (!(y > p.ys.back()))
                    fail(path, lineno, p.y_name + " = " + f[1] + " does not increase from row to row (the row before began on line " +
                                           std::to_string(row_line) + ")");
                p.ys.push_back(y);
                row_line = lineno;
                i = 0;
            }
            const double span = p.xs.back() - p.xs.front();
            if (!same(x, p.xs[i], span) || !same(y, p.ys.back(), std::abs(p.ys.back())))
                fail(path, lineno, "(" + f[0] + ", " + f[1] + ") is not on the grid: expected " + p.x_name + " = " +
                                       std::to_string(p.xs[i]) + " in the row " + p.y_name + " = " + std::to_string(p.ys.back()) +
                                       " begun on line " + std::to_string(row_line));
            ++i;
        }
        for (std::size_t m = 0; m < p.measures.size(); ++m) p.values[m].push_back(fields[m + 2]);
    }
    if (p.xs.empty()) fail(path, lineno, "no data rows after the header");
    if (i != p.xs.size())
        fail(path, lineno, "the last row (" + p.y_name + " = " + std::to_string(p.ys.back()) + ", begun on line " +
                               std::to_string(row_line) + ") has " + std::to_string(i) + " of " + std::to_string(p.xs.size()) +
                               " points (a scan cut short?)");
    return p;
}

PlaneData plane_from_scan(const ScanSpec& spec, const std::vector<std::vector<ScanPoint>>& rows, const std::string& source) {
    PlaneData p;
    p.source = source;
    p.x_name = spec.x.name();
    p.y_name = spec.y.name();
    for (int i = 0; i < spec.x.n; ++i) p.xs.push_back(spec.x.at(i));
    for (int j = 0; j < spec.y.n; ++j) p.ys.push_back(spec.y.at(j));
    struct Col {
        const char* name;
        bool on;
        double ScanPoint::*field;
    };
    const Col cols[] = {{"period", spec.measures.period, &ScanPoint::period},
                        {"lyapunov", spec.measures.lyapunov, &ScanPoint::lyapunov},
                        {"impacts", spec.measures.impacts, &ScanPoint::impacts},
                        {"xmin", spec.measures.xrange, &ScanPoint::xmin},
                        {"xmax", spec.measures.xrange, &ScanPoint::xmax}};
    const std::size_t cells = p.xs.size() * p.ys.size();
    for (const Col& c : cols) {
        if (!c.on) continue;
        p.measures.push_back(c.name);
        std::vector<double> v(cells, std::numeric_limits<double>::quiet_NaN());
        for (std::size_t j = 0; j < rows.size() && j < p.ys.size(); ++j)
            for (std::size_t i = 0; i < rows[j].size() && i < p.xs.size(); ++i) v[j * p.xs.size() + i] = rows[j][i].*c.field;
        p.values.push_back(std::move(v));
    }
    return p;
}

PlaneExtent plane_extent(const PlaneData& p) {
    auto ext = [](const std::vector<double>& v, double& lo, double& hi) {
        if (v.size() < 2) {   // one value: a cell of 1 % around it (or of 1 unit of the last digit for 0)
            const double h = std::max(0.01 * std::abs(v.empty() ? 0.0 : v[0]), 1e-6);
            lo = (v.empty() ? 0.0 : v[0]) - h;
            hi = (v.empty() ? 0.0 : v[0]) + h;
            return;
        }
        const double d = (v.back() - v.front()) / static_cast<double>(v.size() - 1);
        lo = v.front() - 0.5 * d;
        hi = v.back() + 0.5 * d;
    };
    PlaneExtent e{};
    ext(p.xs, e.x_lo, e.x_hi);
    ext(p.ys, e.y_lo, e.y_hi);
    return e;
}

std::optional<PlaneCell> plane_pick(const PlaneData& p, double fx, double fy) {
    if (p.xs.empty() || p.ys.empty() || !(fx >= 0.0 && fx <= 1.0 && fy >= 0.0 && fy <= 1.0)) return std::nullopt;
    // The cells are equal slices of the extent (the scan's axes are uniform).
    const int i = std::min(static_cast<int>(fx * p.nx()), p.nx() - 1);
    const int j = std::min(static_cast<int>(fy * p.ny()), p.ny() - 1);
    return PlaneCell{i, j, p.xs[static_cast<std::size_t>(i)], p.ys[static_cast<std::size_t>(j)]};
}

PlaneClick plane_click(const PlaneData& p, const PlaneCell& c) {
    PlaneClick out;
    auto apply = [&](const std::string& name, double v) {
        if (name == "omega") out.omega = v;
        else if (name == "xI") out.xI = v;
        else out.ignored = name;
    };
    apply(p.x_name, c.x);
    apply(p.y_name, c.y);
    return out;
}

std::optional<PlaneSegment> diagram_cut(const PlaneData& p, double omega_lo, double omega_hi, double xI, double m0e) {
    if (p.xs.empty() || p.ys.empty()) return std::nullopt;
    const PlaneExtent e = plane_extent(p);
    auto fixed = [&](const std::string& name) { return name == "xI" ? xI : m0e; };
    auto inside = [](double v, double lo, double hi) { return v >= lo && v <= hi; };
    if (p.x_name == "omega" || p.y_name == "omega") {
        const bool omega_x = p.x_name == "omega";
        const double w_lo = omega_x ? e.x_lo : e.y_lo, w_hi = omega_x ? e.x_hi : e.y_hi;
        const double o_lo = omega_x ? e.y_lo : e.x_lo, o_hi = omega_x ? e.y_hi : e.x_hi;
        const double other = fixed(omega_x ? p.y_name : p.x_name);
        const double a = std::max(omega_lo, w_lo), b = std::min(omega_hi, w_hi);
        if (!(a <= b) || !inside(other, o_lo, o_hi)) return std::nullopt;
        if (omega_x) return PlaneSegment{a, other, b, other};
        return PlaneSegment{other, a, other, b};
    }
    const double x = fixed(p.x_name), y = fixed(p.y_name);
    if (!inside(x, e.x_lo, e.x_hi) || !inside(y, e.y_lo, e.y_hi)) return std::nullopt;
    return PlaneSegment{x, y, x, y};
}

}  // namespace impactlab::gui
