#include "impactlab/scan.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <istream>
#include <limits>
#include <mutex>
#include <ostream>
#include <sstream>
#include <thread>

#include "impactlab/analysis.hpp"
#include "impactlab/params_json.hpp"

namespace impactlab {

const char* ScanAxis::name() const { return sweep_param_name(param); }

namespace {

double number(const std::string& what, const std::string& s) {
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(v))
        throw ScanError(what + ": '" + s + "' is not a finite number");
    return v;
}

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::string item;
    std::stringstream ss(s);
    while (std::getline(ss, item, sep)) out.push_back(item);
    if (!s.empty() && s.back() == sep) out.emplace_back();
    return out;
}

// The measures of one CF level, taken in its record window (after `transient` sections).
class ScanObserver : public LevelObserver {
public:
    ScanObserver(const ScanSpec& spec, const Tolerances& tol, std::vector<ScanPoint>& out, std::size_t first_index)
        : spec_(spec), tol_(tol), out_(out), first_(first_index) {}
    void begin_level(std::size_t, const CfLevel& lv) override {
        level_ = lv;
        sections_ = 0;
        impacts_ = 0;
        rec_.clear();
        xmin_ = std::numeric_limits<double>::infinity();
        xmax_ = -xmin_;
        inside_ = false;
        inside_known_ = false;
    }
    void on_section(const SectionPoint& sp) override {
        ++sections_;
        if (sections_ > spec_.transient) rec_.push_back(sp);   // sections transient+1 .. transient+record
    }
    void on_impact(const ImpactEvent&) override {
        if (recording()) ++impacts_;
    }
    void on_piece(const Piece& piece) override {
        if (!recording()) return;
        for (int k = 0; k <= 4; ++k) {   // the ends and three interior points of the dense output
            const double x = piece.at(piece.t0 + (piece.t1 - piece.t0) * k / 4)[0];
            xmin_ = std::min(xmin_, x);
            xmax_ = std::max(xmax_, x);
        }
        // A compliant bumper's contacts: the cart crosses into x > xI (rigid impacts come through on_impact).
        const bool inside = piece.at(piece.t1)[0] > level_.xI;
        if (compliant_ && inside_known_ && inside && !inside_) ++impacts_;
        inside_ = inside;
        inside_known_ = true;
    }
    void end_level(std::size_t j, const Params& p, const State& s) override {
        ScanPoint pt;
        pt.period = settled_period(p, s);
        pt.impacts = static_cast<double>(impacts_) / spec_.record;
        pt.xmin = xmin_;
        pt.xmax = xmax_;
        pt.lyapunov = std::numeric_limits<double>::quiet_NaN();
        if (spec_.measures.lyapunov) {
            State copy = s;   // the continuation goes on from s, untouched
            pt.lyapunov = analysis::lyapunov(p, level_.omega, copy, 0, spec_.record, tol_).lambda_max;
        }
        out_[first_ + j] = pt;
    }
    void set_compliant(bool c) { compliant_ = c; }

private:
    // The period of the record window, only once it has settled by the map's own test (settle_level: 1..16
    // values recurring in order, not still shrinking), running on from its end state (a copy: the row continues
    // from where the level ended) up to kSettleBudget windows more, then kNotSettled. More than 16 values is
    // chaos (or a long period).
    double settled_period(const Params& p, const State& s) const {
        std::vector<SectionPoint> rec = rec_;
        const int k = settle_level(p, level_.omega, s, rec, 16, kSettleBudget, tol_);
        return k == kLevelNotSettled ? kNotSettled : static_cast<double>(k);
    }
    static constexpr int kSettleBudget = 10;      // record windows run on before a cell reads "not settled"

    // The record window's dynamics: from the transient's last section to the end (record whole periods).
    bool recording() const { return sections_ >= spec_.transient; }
    const ScanSpec& spec_;
    const Tolerances& tol_;
    std::vector<ScanPoint>& out_;
    std::size_t first_;
    CfLevel level_{};
    int sections_ = 0;
    long impacts_ = 0;
    std::vector<SectionPoint> rec_;
    double xmin_ = 0, xmax_ = 0;
    bool inside_ = false, inside_known_ = false, compliant_ = false;
};

CfLevel level_at(const Params& p, const ScanSpec& spec, int i, int row) {
    CfLevel lv{spec.omega, p.xI, p.m0e};
    level_value(lv, spec.y.param) = spec.y.at(row);
    level_value(lv, spec.x.param) = spec.x.at(i);
    return lv;
}

}  // namespace

ScanAxis parse_scan_axis(const std::string& spec) {
    const auto parts = split(spec, ':');
    if (parts.size() != 4) throw ScanError("'" + spec + "': expected NAME:LO:HI:N (e.g. omega:0:25:400)");
    ScanAxis a;
    if (const auto which = parse_sweep_param(parts[0])) a.param = *which;
    else throw ScanError("'" + spec + "': '" + parts[0] + "' is not one of omega, xI, m0e");
    a.lo = number(spec, parts[1]);
    a.hi = number(spec, parts[2]);
    const double n = number(spec, parts[3]);
    if (n != std::floor(n) || n < 1 || n > 100000) throw ScanError("'" + spec + "': N must be an integer in [1, 100000]");
    a.n = static_cast<int>(n);
    if (a.n > 1 && !(a.hi > a.lo)) throw ScanError("'" + spec + "': HI must exceed LO");
    // xI and m0e within the parameter files' ranges (param_ranges); omega within the CLI's [1e-3, 1000] rad/s.
    double lo_ok = 1e-3, hi_ok = 1000.0;
    for (const ParamRange& r : param_ranges())
        if (a.param != ScanParam::Omega && parts[0] == r.key) {
            lo_ok = r.lo;
            hi_ok = r.hi;
        }
    if (a.lo < lo_ok || a.hi > hi_ok) {
        std::ostringstream m;
        m << "'" << spec << "': " << parts[0] << " must lie in [" << lo_ok << ", " << hi_ok << "]";
        throw ScanError(m.str());
    }
    return a;
}

ScanMeasures parse_scan_measures(const std::string& list) {
    ScanMeasures m;
    m.period = false;
    for (const auto& name : split(list, ',')) {
        if (name == "period") m.period = true;
        else if (name == "lyapunov") m.lyapunov = true;
        else if (name == "impacts") m.impacts = true;
        else if (name == "xrange") m.xrange = true;
        else throw ScanError("'" + name + "' is not one of period, lyapunov, impacts, xrange");
    }
    if (!(m.period || m.lyapunov || m.impacts || m.xrange)) throw ScanError("no measure given");
    return m;
}

std::vector<ScanPoint> scan_row(const Params& p, const ScanSpec& spec, int row, const Tolerances& tol,
                                const std::atomic<bool>* cancel) {
    const auto nx = static_cast<std::size_t>(spec.x.n);
    std::vector<ScanPoint> out(nx);
    Progress local;   // carries the caller's cancel flag into the sweep
    auto run = [&](const std::vector<CfLevel>& levels, std::size_t first) {
        if (cancel && cancel->load(std::memory_order_relaxed)) local.cancel.store(true);
        ScanObserver obs(spec, tol, out, first);
        obs.set_compliant(p.compliant());
        const Diagram d = run_cf_levels(p, levels, spec.transient, spec.record, cancel ? &local : nullptr, tol, &obs);
        return !d.cancelled;
    };
    if (spec.start == ScanStart::Continue) {
        std::vector<CfLevel> levels(nx);
        for (std::size_t i = 0; i < nx; ++i) levels[i] = level_at(p, spec, static_cast<int>(i), row);
        if (!run(levels, 0)) return {};
    } else {
        for (std::size_t i = 0; i < nx; ++i)
            if (!run({level_at(p, spec, static_cast<int>(i), row)}, i)) return {};
    }
    return out;
}

void scan_rows(const Params& p, const ScanSpec& spec, const std::vector<int>& todo, int threads, Progress* progress,
               const Tolerances& tol, const std::function<void(int, const std::vector<ScanPoint>&)>& on_row) {
    std::atomic<std::size_t> next{0};
    std::atomic<std::size_t> done{0};
    std::mutex hand_over;
    const std::atomic<bool>* cancel = progress ? &progress->cancel : nullptr;
    auto worker = [&] {
        for (;;) {
            const std::size_t k = next.fetch_add(1);
            if (k >= todo.size() || (cancel && cancel->load())) return;
            std::vector<ScanPoint> r = scan_row(p, spec, todo[k], tol, cancel);
            if (r.empty()) return;   // cancelled
            {
                std::lock_guard<std::mutex> lock(hand_over);
                on_row(todo[k], r);
            }
            if (progress)
                progress->fraction.store(static_cast<double>(++done) / static_cast<double>(todo.size()),
                                         std::memory_order_relaxed);
        }
    };
    const int n = std::max(1, std::min(threads, static_cast<int>(todo.size())));
    std::vector<std::thread> pool;
    for (int t = 1; t < n; ++t) pool.emplace_back(worker);
    worker();   // the calling thread works too
    for (auto& t : pool) t.join();
}

std::vector<double> ScanRowMessage::pack() const {
    std::vector<double> buf;
    buf.reserve(size(points.size()));
    buf.push_back(row);
    for (const ScanPoint& pt : points) buf.insert(buf.end(), {pt.period, pt.lyapunov, pt.impacts, pt.xmin, pt.xmax});
    return buf;
}

ScanRowMessage ScanRowMessage::unpack(const std::vector<double>& buf, std::size_t nx) {
    if (buf.size() < size(nx))
        throw ScanError("a row message of " + std::to_string(buf.size()) + " values, not " + std::to_string(size(nx)));
    ScanRowMessage m;
    m.row = static_cast<int>(buf[0]);
    m.points.resize(nx);
    for (std::size_t i = 0; i < nx; ++i) {
        const double* v = &buf[1 + kPointValues * i];
        m.points[i] = {v[0], v[1], v[2], v[3], v[4]};
    }
    return m;
}

void write_scan_csv_header(const ScanSpec& spec, std::ostream& out) {
    const ScanMeasures& m = spec.measures;
    out << spec.x.name() << ',' << spec.y.name();
    if (m.period) out << ",period";
    if (m.lyapunov) out << ",lyapunov";
    if (m.impacts) out << ",impacts";
    if (m.xrange) out << ",xmin,xmax";
    out << '\n';
}

void write_scan_csv_row(const ScanSpec& spec, int j, const std::vector<ScanPoint>& row, std::ostream& out) {
    const ScanMeasures& m = spec.measures;
    char buf[64];
    auto put = [&](double v) {
        std::snprintf(buf, sizeof buf, ",%.17g", v);
        out << buf;
    };
    for (int i = 0; i < spec.x.n; ++i) {
        const ScanPoint& pt = row[static_cast<std::size_t>(i)];
        std::snprintf(buf, sizeof buf, "%.10g,%.10g", spec.x.at(i), spec.y.at(j));
        out << buf;
        if (m.period) put(pt.period);
        if (m.lyapunov) put(pt.lyapunov);
        if (m.impacts) put(pt.impacts);
        if (m.xrange) {
            put(pt.xmin);
            put(pt.xmax);
        }
        out << '\n';
    }
}

void write_scan_csv(const ScanSpec& spec, const std::vector<std::vector<ScanPoint>>& rows, std::ostream& out) {
    write_scan_csv_header(spec, out);
    for (int j = 0; j < spec.y.n; ++j) write_scan_csv_row(spec, j, rows[static_cast<std::size_t>(j)], out);
}

namespace {

// FNV-1a, 64 bits: a fingerprint of the model's parameters in the log header (not a defence against forgery).
std::uint64_t fnv1a(const std::string& text) {
    std::uint64_t h = 14695981039346656037ull;
    for (const unsigned char c : text) {
        h ^= c;
        h *= 1099511628211ull;
    }
    return h;
}

// A log token as scan_log_line writes it: a hexadecimal float, or inf / nan; nothing else (no "1e999", no word).
bool log_number(const std::string& tok, double& v) {
    const std::string body = !tok.empty() && tok[0] == '-' ? tok.substr(1) : tok;
    if (body == "inf" || body == "nan") {
        v = std::strtod(tok.c_str(), nullptr);
        return true;
    }
    if (body.size() < 3 || body[0] != '0' || body[1] != 'x') return false;
    errno = 0;
    char* end = nullptr;
    v = std::strtod(tok.c_str(), &end);
    return end == tok.c_str() + tok.size() && errno == 0 && std::isfinite(v);
}

}  // namespace

std::string scan_log_header(const Params& p, const ScanSpec& spec, const Tolerances& tol) {
    std::string name = p.name.substr(0, 64);   // for the reader; the fingerprint is what is compared
    for (char& c : name)
        if (static_cast<unsigned char>(c) <= ' ' || c == 127) c = '_';
    char fp[32];
    std::snprintf(fp, sizeof fp, "%016llx", static_cast<unsigned long long>(fnv1a(params_to_json_text(p))));
    std::ostringstream h;
    h.precision(17);
    h << "# impactlab scan log v2 model=" << name << " params=" << fp << " x=" << spec.x.name() << ':' << spec.x.lo << ':'
      << spec.x.hi << ':' << spec.x.n << " y=" << spec.y.name() << ':' << spec.y.lo << ':' << spec.y.hi << ':' << spec.y.n
      << " omega=" << spec.omega << " xI=" << p.xI << " m0e=" << p.m0e << " transient=" << spec.transient
      << " record=" << spec.record << " start=" << (spec.start == ScanStart::Continue ? "continue" : "fresh")
      << " lyapunov=" << spec.measures.lyapunov << " rtol=" << tol.rtol << " x_scale=" << tol.x_scale
      << " v_scale=" << tol.v_scale << " h_max=" << tol.h_max << " h_min=" << tol.h_min
      << " max_step_rate=" << tol.max_step_rate << " max_wall_s=" << tol.max_wall_s;
    return h.str();
}

std::string scan_log_line(int row, const std::vector<ScanPoint>& points) {
    std::string line = "row " + std::to_string(row);
    char buf[40];
    for (const ScanPoint& pt : points)
        for (const double v : {pt.period, pt.lyapunov, pt.impacts, pt.xmin, pt.xmax}) {
            std::snprintf(buf, sizeof buf, " %a", v);
            line += buf;
        }
    return line + " end";
}

std::vector<std::pair<int, std::vector<ScanPoint>>> read_scan_log(std::istream& in, const std::string& header,
                                                                  const ScanSpec& spec) {
    std::string line;
    if (!std::getline(in, line)) return {};
    if (line != header)
        throw ScanError("the tile log belongs to another scan (its header: '" + line.substr(0, 400) +
                        "'); remove it or drop --resume");
    std::vector<std::pair<int, std::vector<ScanPoint>>> rows;
    std::vector<long> seen_at(static_cast<std::size_t>(spec.y.n), 0);   // the line each row was read from
    const std::size_t nx = static_cast<std::size_t>(spec.x.n);
    long lineno = 1;
    std::string next;
    bool more = static_cast<bool>(std::getline(in, next));
    while (more) {
        line = std::move(next);
        ++lineno;
        more = static_cast<bool>(std::getline(in, next));
        const auto bad = [&](const std::string& what) {
            return ScanError("line " + std::to_string(lineno) + ": " + what);
        };
        std::istringstream ls(line);
        std::vector<std::string> tok;
        for (std::string t; ls >> t;) tok.push_back(t);
        const std::size_t want = 3 + 5 * nx;   // "row", N, the values, "end"
        if (tok.size() < want || tok.back() != "end") {
            if (!more) break;   // a row killed while being written: computed again
            throw bad("not a complete row (expected 'row N', " + std::to_string(5 * nx) + " values and 'end')");
        }
        if (tok.size() != want) throw bad("more fields than a row of " + std::to_string(nx) + " points has");
        char* end = nullptr;
        errno = 0;
        const long row = std::strtol(tok[1].c_str(), &end, 10);
        if (tok[0] != "row" || end != tok[1].c_str() + tok[1].size() || errno != 0 || row < 0 || row >= spec.y.n)
            throw bad("'" + tok[0].substr(0, 40) + " " + tok[1].substr(0, 40) + "' is not 'row N' with N in [0, " +
                      std::to_string(spec.y.n - 1) + "]");
        std::vector<ScanPoint> pts(nx);
        for (std::size_t i = 0; i < nx; ++i) {
            double v[5];
            for (int k = 0; k < 5; ++k) {
                const std::string& t = tok[2 + 5 * i + static_cast<std::size_t>(k)];
                if (!log_number(t, v[k]))
                    throw bad("'" + t.substr(0, 40) + "' is not a number as the log writes them (hexadecimal)");
            }
            // What no scan gives: a period that is no whole number of sections in [0, 16] (0 = chaos) nor
            // kNotSettled, a negative
            // or unbounded impact rate.
            if (!((v[0] >= 0 || v[0] == kNotSettled) && v[0] <= 16 && v[0] == std::floor(v[0])))
                throw bad("point " + std::to_string(i) + ": period " + tok[2 + 5 * i] + " is not one a scan gives");
            if (!(v[2] >= 0 && std::isfinite(v[2])))
                throw bad("point " + std::to_string(i) + ": impacts " + tok[4 + 5 * i] + " is not one a scan gives");
            pts[i] = {v[0], v[1], v[2], v[3], v[4]};
        }
        long& first = seen_at[static_cast<std::size_t>(row)];
        if (first > 0) {
            const auto same = [&](const std::vector<ScanPoint>& a) {
                for (std::size_t i = 0; i < nx; ++i)
                    if (std::memcmp(&a[i], &pts[i], sizeof(ScanPoint)) != 0) return false;
                return true;
            };
            for (const auto& [r, old] : rows)
                if (r == row && !same(old))
                    throw bad("row " + std::to_string(row) + " appears again with other values (first on line " +
                              std::to_string(first) + ")");
            continue;
        }
        first = lineno;
        rows.emplace_back(static_cast<int>(row), std::move(pts));
    }
    return rows;
}

}  // namespace impactlab
