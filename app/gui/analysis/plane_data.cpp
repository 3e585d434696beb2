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
    ScanGrid g;
    try {
        g = read_scan_csv(in, path);
    } catch (const ScanCsvError& e) {
        throw PlaneError(e.what());
    }
    PlaneData p;
    p.source = path;
    p.x_name = std::move(g.x_name);
    p.y_name = std::move(g.y_name);
    p.xs = std::move(g.xs);
    p.ys = std::move(g.ys);
    p.measures = std::move(g.measures);
    p.values = std::move(g.values);
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
