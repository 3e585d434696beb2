// Parameter planes: a grid over two of (omega, xI, m0e), each row a CF-style sweep along the first axis
// (continued from the previous point's final state) or each point from rest (fresh), with measures per
// point: the period of the section points, the largest Lyapunov exponent, impacts per period, the x range.
// Rows are the unit of work: independent of one another, so a result never depends on how many threads,
// processes or machines computed it, or in which order (the CLI spreads rows over threads and MPI ranks).
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

#include "impactlab/params.hpp"
#include "impactlab/rosenbrock.hpp"
#include "impactlab/sweep.hpp"

namespace impactlab {

struct ScanError : std::runtime_error { using std::runtime_error::runtime_error; };

using ScanParam = SweepParam;   // an axis is one of the parameters a CF sweep can move
struct ScanAxis {
    ScanParam param = ScanParam::Omega;
    double lo = 0, hi = 0;   // [rad/s], [m] or [kg m]
    int n = 1;               // points, lo and hi included
    // The last value is HI itself: lo + (hi - lo) may round past it, out of the range the axis was checked in.
    double at(int i) const { return n == 1 ? lo : i == n - 1 ? hi : lo + (hi - lo) * i / (n - 1); }
    const char* name() const;
};
// "omega:0:25:400", "xI:-0.01:0.01:300", "m0e:0.01:0.05:50"; throws ScanError naming the problem.
ScanAxis parse_scan_axis(const std::string& spec);

struct ScanMeasures {
    bool period = true, lyapunov = false, impacts = false, xrange = false;
};
// "period,lyapunov,impacts,xrange"; throws ScanError for an unknown name.
ScanMeasures parse_scan_measures(const std::string& list);

enum class ScanStart { Continue, Fresh };
struct ScanSpec {
    ScanAxis x, y;              // x: the fast axis, along which a row continues
    ScanMeasures measures;
    ScanStart start = ScanStart::Continue;
    double omega = 0;           // [rad/s] when neither axis is omega
    int transient = 20, record = 70;   // periods per point, as the CF sweep
};

// What one point shows. period: 1..16 distinct section values (as the CF sweep counts them) once they recur
// in order, 0 for more (chaos or a long period), kNotSettled when the point had not settled within its
// record and ten more records; impacts per forcing period (rigid impacts, or contacts of a compliant bumper);
// x range over the recorded periods [m]; lyapunov [1/s] (NaN when not measured).
inline constexpr double kNotSettled = -1;   // ScanPoint::period of a point still in its transient
struct ScanPoint {
    double period = 0, lyapunov = 0, impacts = 0, xmin = 0, xmax = 0;
};

// One row (y = spec.y.at(row)) of the plane; any thread. Cancelled rows return empty.
std::vector<ScanPoint> scan_row(const Params& p, const ScanSpec& spec, int row, const Tolerances& tol = {},
                                const std::atomic<bool>* cancel = nullptr);

// The rows `todo` on `threads` workers, handing rows out one at a time (a chaotic row costs several
// periodic ones). on_row is called once per finished row, serialised (one call at a time), on a worker
// thread. Progress counts the rows of `todo`.
void scan_rows(const Params& p, const ScanSpec& spec, const std::vector<int>& todo, int threads, Progress* progress,
               const Tolerances& tol, const std::function<void(int row, const std::vector<ScanPoint>&)>& on_row);

// A finished row as it travels between processes (the MPI hand-out, scan_cluster.hpp): one flat array of
// doubles, the row's index first, then each point's five values in ScanPoint's order. Exact: a row sent is
// the row received, bit for bit.
struct ScanRowMessage {
    static constexpr std::size_t kPointValues = 5;
    int row = -1;
    std::vector<ScanPoint> points;

    static std::size_t size(std::size_t nx) { return 1 + kPointValues * nx; }
    std::vector<double> pack() const;
    // The first size(nx) values of buf; throws ScanError if buf is shorter.
    static ScanRowMessage unpack(const std::vector<double>& buf, std::size_t nx);
};

// The CSV: the two axis names, then one column per measure (period, lyapunov, impacts, xmin, xmax), rows
// with the first axis fastest; numbers printed to round-trip exactly.
void write_scan_csv(const ScanSpec& spec, const std::vector<std::vector<ScanPoint>>& rows, std::ostream& out);
// The same CSV in pieces, for a scan that writes its rows as they finish: the header, then row j (y =
// spec.y.at(j)) once rows 0 .. j-1 are written.
void write_scan_csv_header(const ScanSpec& spec, std::ostream& out);
void write_scan_csv_row(const ScanSpec& spec, int j, const std::vector<ScanPoint>& row, std::ostream& out);
// The same CSV read back as a regular grid: values[m][j * nx + i] at (xs[i], ys[j]), axes increasing. Throws
// ScanCsvError "SOURCE:LINE: why": a header without two different axes (omega, xI, m0e) and a measure, a row
// with the wrong number of fields or a field that is no number, rows that do not form a grid with the first
// axis fastest.
struct ScanCsvError : std::runtime_error { using std::runtime_error::runtime_error; };
struct ScanGrid {
    std::string x_name, y_name;
    std::vector<double> xs, ys;
    std::vector<std::string> measures;
    std::vector<std::vector<double>> values;
};
ScanGrid read_scan_csv(std::istream& in, const std::string& source);

// The tile log of a scan: a header with everything that shapes the result (the spec, the integrator's
// tolerances and a fingerprint of every model parameter, effects included), then one line per finished row
// with its values in hexadecimal floating point (exact). A resumed scan reads it back.
std::string scan_log_header(const Params& p, const ScanSpec& spec, const Tolerances& tol);
std::string scan_log_line(int row, const std::vector<ScanPoint>& points);
// Rows read from a log, each once. Throws ScanError if the header belongs to another scan, or naming the line
// if a row is malformed (a token that is no number as the log writes them, a value no scan gives) or appears
// twice with different values; only a torn last line (a killed write) is dropped.
std::vector<std::pair<int, std::vector<ScanPoint>>> read_scan_log(std::istream& in, const std::string& header,
                                                                  const ScanSpec& spec);

// A curve in the plane's coordinates (x along spec.x, y along spec.y), e.g. a continued bifurcation.
struct ScanCurve {
    std::string label;
    std::vector<double> x, y;
    bool dashed = false;   // drawn in dashes (a second kind of curve over the same maps)
    bool dotted = false;   // drawn in dots (a third)
};
// A PNG with one map per measure (period classes, impacts, lambda, x range) and a legend for each; the curves,
// if any, drawn in black over every map, so that the brute-force regions and the continued boundaries can be
// compared by eye.
void save_scan_png(const ScanSpec& spec, const std::vector<std::vector<ScanPoint>>& rows, const std::string& model,
                   const std::string& path, const std::vector<ScanCurve>& curves = {});

}  // namespace impactlab
