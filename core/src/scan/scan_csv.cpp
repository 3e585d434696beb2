// The scan CSV read back (write_scan_csv's reader): the visualiser's plane and any tool share its rules.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <istream>
#include <string>
#include <vector>

#include "impactlab/scan.hpp"

namespace impactlab {

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
    throw ScanCsvError(path + ":" + std::to_string(line) + ": " + what);
}

// Two axis values are the same grid value: the scan prints them to round-trip, a hand-made file may not.
bool same(double a, double b, double span) { return std::abs(a - b) <= 1e-9 * std::max(span, 1e-300) + 1e-15; }

}  // namespace

ScanGrid read_scan_csv(std::istream& in, const std::string& path) {
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
    ScanGrid p;
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

}  // namespace impactlab
