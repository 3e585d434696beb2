// impactlab scan: a parameter plane on every core (a thread pool) and, started by mpirun, across processes
// and machines (Open MPI: rank 0 hands out rows and writes, the other ranks compute). Rows are independent,
// so the file is the same bit for bit whatever the number of threads or ranks. A tile log beside the output
// holds every finished row; --resume reads it back and computes only what is missing.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <thread>

#include "commands.hpp"
#include "common.hpp"
#include "impactlab/analysis.hpp"
#include "impactlab/input_file.hpp"
#include "impactlab/plane_doubling.hpp"
#include "impactlab/scan.hpp"

#ifdef IMPACTLAB_HAVE_MPI
#include "impactlab/scan_cluster.hpp"
#endif

namespace impactlab::cli {

namespace {

const char* kScanHelp =
    "usage: impactlab scan --model A1C --x omega:0:25:400 --y xI:-0.01:0.01:300 --measure period,lyapunov,impacts,xrange\n"
    "                      --out plane.csv [--png plane.png] [--threads N] [--resume] [options]\n"
    "       mpirun -np N impactlab scan ...   (across processes and machines; rank 0 writes)\n\n"
    "A parameter plane: each row (fixed y) a CF-style sweep along x, each point continued from the previous\n"
    "point's final state (--start continue, the CF sweep's physics), or each point from rest (--start fresh).\n"
    "  --x NAME:LO:HI:N    the fast axis (omega, xI or m0e), N points from LO to HI\n"
    "  --y NAME:LO:HI:N    the slow axis\n"
    "  --measure LIST      period (section values once they recur, 0 = chaos, -1 = not settled within ten more\n"
    "                      records), lyapunov (largest exponent [1/s]), impacts (per forcing period), xrange\n"
    "                      (xmin,xmax [m]); default period\n"
    "  --out FILE          CSV: the axes, then one column per measure, x fastest (required)\n"
    "  --png FILE          one map per measure with its legend\n"
    "  --doubling-from W,X,V[,K]  a doubling of the period-K orbit (default 1) at omega W with section point\n"
    "                      (X, V) [m, m/s], as `continue` prints it (an impacting orbit's too): continued in the\n"
    "                      y axis (xI or m0e) and drawn over the maps (x: omega); `auto`: the first period-1\n"
    "                      doubling over the x axis's omega range, found by continuation\n"
    "  --grazing-from W,X,V[,K]  a grazing of the period-K orbit (default 1) at omega W with section point (X, V),\n"
    "                      as `continue` prints it: continued in the y axis (the omega where the orbit without\n"
    "                      the bumper reaches xI) and drawn over the maps, dashed; `auto`: the first period-1\n"
    "                      grazing over the x axis's omega range, found by continuation\n"
    "  --fold-from W,X,V[,K]  a fold of the period-K orbit (default 1) at omega W with section point (X, V), as\n"
    "                      `continue` prints it: continued in the y axis and drawn over the maps, dotted;\n"
    "                      `auto`: the first period-1 fold over the x axis's omega range\n"
    "  --curves-out FILE   the continued curves' points as CSV: curve (doubling, grazing, fold), omega, the y axis\n"
    "  --omega W           forcing frequency [rad/s] when neither axis is omega\n"
    "  --start continue|fresh   (default continue)\n"
    "  --transient N, --record N   periods per point (default 20, 70: the CF sweep's)\n"
    "  --threads N         worker threads of this process (default: all cores)\n"
    "  --resume            go on from FILE.tiles, the log a killed scan left (rows done are not redone)\n";

std::vector<std::vector<ScanPoint>> empty_rows(const ScanSpec& spec) {
    return std::vector<std::vector<ScanPoint>>(static_cast<std::size_t>(spec.y.n));
}

}  // namespace

namespace {
// A curve's start within the model's physical range (omega >= 0.05 rad/s as continue's, the section point on
// the rail at a speed the rig can have): a start beyond it sends the curve's Newton far from any orbit, where
// it wandered without end.
void check_curve_start(const std::string& flag, const double* w) {
    const char* names[3] = {"OMEGA", "X", "V"};
    const double lo[3] = {0.05, -0.1, -10.0}, hi[3] = {1000.0, 0.1, 10.0};
    const char* units[3] = {"rad/s", "m (the rail)", "m/s"};
    for (int i = 0; i < 3; ++i)
        if (!(w[i] >= lo[i] && w[i] <= hi[i])) {
            char buf[200];
            std::snprintf(buf, sizeof buf, "scan: option '%s': %s = %.6g is outside [%g, %g] %s", flag.c_str(), names[i], w[i], lo[i],
                          hi[i], units[i]);
            throw UsageError(buf);
        }
}

// A curve asked for over the maps: its known point (omega, x, v, k), or `auto` (found by curve_over_plane).
struct CurveAsk {
    bool is_auto = false;
    std::vector<double> from;
};

// The command line, read and checked: every rank reads the same.
struct ScanCommand {
    ScanSpec spec;
    Params p;
    Tolerances tol;
    std::string out_path, png, log_path, curves_path;
    bool resume = false;
    int threads = 1;
    CurveAsk doubling, grazing, fold;   // --doubling-from, --grazing-from, --fold-from
};

// The plane: its axes, measures, forcing, start and periods per point, every corner a valid model.
void read_plane(const Args& a, ScanCommand& c) {
    ScanSpec& spec = c.spec;
    try {
        spec.x = parse_scan_axis(a.required("--x"));
    } catch (const ScanError& e) {
        throw UsageError(std::string("scan: --x: ") + e.what());
    }
    try {
        spec.y = parse_scan_axis(a.required("--y"));
    } catch (const ScanError& e) {
        throw UsageError(std::string("scan: --y: ") + e.what());
    }
    if (spec.x.param == spec.y.param) throw UsageError("scan: --x and --y vary the same parameter");
    check_rows("scan", static_cast<double>(spec.x.n) * spec.y.n, "--x N x --y N");
    try {
        spec.measures = parse_scan_measures(a.str("--measure", "period"));
    } catch (const ScanError& e) {
        throw UsageError(std::string("scan: --measure: ") + e.what());
    }
    const bool omega_axis = spec.x.param == ScanParam::Omega || spec.y.param == ScanParam::Omega;
    if (!omega_axis && !a.has("--omega")) throw UsageError("scan: neither axis is omega: give --omega W");
    if (omega_axis && a.has("--omega")) throw UsageError("scan: --omega is an axis already");
    spec.omega = a.num("--omega", 0.0, 1e-3, 1000.0);
    const std::string start = a.str("--start", "continue");
    if (start != "continue" && start != "fresh") throw UsageError("scan: --start: '" + start + "' is not continue or fresh");
    spec.start = start == "continue" ? ScanStart::Continue : ScanStart::Fresh;
    spec.transient = a.integer("--transient", 20, 0, 1000000);
    spec.record = a.integer("--record", 70, 1, 1000000);
    const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
    c.threads = a.integer("--threads", static_cast<int>(hw), 1, 1024);
    // Every parameter of the plane must be one the model accepts: check its corners.
    for (int j : {0, spec.y.n - 1})
        for (int i : {0, spec.x.n - 1}) {
            Params q = c.p;
            for (const ScanAxis* ax : {&spec.x, &spec.y}) {
                const double v = ax->at(ax == &spec.x ? i : j);
                if (ax->param == ScanParam::XI) q.xI = v;
                if (ax->param == ScanParam::M0e) q.m0e = v;
            }
            validate(q, "scan plane corner");
        }
}

// --doubling-from, --grazing-from, --fold-from: each an omega-by-(xI or m0e) plane's curve, on the PNG or in
// --curves-out.
void read_curves(const Args& a, ScanCommand& c) {
    const ScanSpec& spec = c.spec;
    for (const char* flag : {"--doubling-from", "--grazing-from", "--fold-from"}) {
        if (!a.has(flag)) continue;
        const std::string f = flag;
        const std::string what = f == "--fold-from" ? "fold" : f == "--doubling-from" ? "doubling" : "grazing";
        CurveAsk& ask = what == "fold" ? c.fold : what == "doubling" ? c.doubling : c.grazing;
        if (!a.has("--png") && !a.has("--curves-out"))
            throw UsageError("scan: " + f + " draws on the PNG or writes --curves-out: give --png or --curves-out");
        if (spec.x.param != ScanParam::Omega || spec.y.param == ScanParam::Omega)
            throw UsageError("scan: " + f + " needs --x omega:... and --y xI:... or m0e:...");
        if (what == "grazing" && !c.p.has_bumper()) throw UsageError("scan: --grazing-from needs a model with a bumper");
        const std::string v = a.str(flag, "");
        if (v == "auto") {
            ask.is_auto = true;
            continue;
        }
        double w[4] = {0, 0, 0, 1};
        char tail = 0;
        const int n = std::sscanf(v.c_str(), "%lf,%lf,%lf,%lf%c", &w[0], &w[1], &w[2], &w[3], &tail);
        if ((n != 3 && n != 4) || !(w[3] >= 1 && w[3] <= 64) || w[3] != std::floor(w[3]))
            throw UsageError("scan: option '" + f + "': expected OMEGA,X,V[,K] with K in 1..64 (a " + what +
                             " of the period-K orbit, as continue prints it), got '" + v + "'");
        check_curve_start(f, w);
        ask.from = {w[0], w[1], w[2], w[3]};
    }
}

ScanCommand read_command(const Args& a) {
    ScanCommand c;
    c.p = model_from(a);
    c.tol = tolerances_from(a);
    read_plane(a, c);
    read_curves(a, c);
    c.out_path = a.required("--out");
    c.png = a.str("--png", "");
    c.curves_path = a.str("--curves-out", "");
    if (!c.curves_path.empty() && !a.has("--doubling-from") && !a.has("--grazing-from") && !a.has("--fold-from"))
        throw UsageError("scan: --curves-out writes the continued curves: give --doubling-from, --grazing-from or --fold-from");
    c.log_path = c.out_path + ".tiles";
    c.resume = a.has("--resume");
    return c;
}

// Rank 0's files: the CSV, written in row order as rows finish (row_done: computed or resumed; next_row: the
// first not yet written; without --png a written row is freed, so memory holds the rows in flight, not the
// plane), and the tile log beside it, which holds every finished row for --resume.
struct ScanFiles {
    std::vector<std::vector<ScanPoint>> rows;
    std::vector<bool> row_done;
    int next_row = 0;
    std::vector<int> todo;   // the rows to compute
    std::optional<OutputFile> out;
    std::ofstream log;
    int log_errno = 0;   // the tile log's first failed write: the scan stops, as nothing could be resumed

    // Opens the outputs, reads back what --resume finds in the log and rewrites the log whole with it.
    void open(const ScanCommand& c) {
        const ScanSpec& spec = c.spec;
        out.emplace(c.out_path, "--out");
        if (!c.png.empty()) check_writable(c.png, "--png");
        if (!c.curves_path.empty()) check_writable(c.curves_path, "--curves-out");
        row_done.assign(static_cast<std::size_t>(spec.y.n), false);
        const std::string header = scan_log_header(c.p, spec, c.tol);
        std::size_t resumed = 0;
        if (c.resume && std::filesystem::exists(c.log_path)) {
            std::istringstream in;
            try {
                in.str(read_input_file(c.log_path));
            } catch (const InputFileError& e) {
                throw UsageError(std::string("scan: --resume: ") + e.what());
            }
            try {
                for (auto& [row, pts] : read_scan_log(in, header, spec)) {
                    if (!row_done[static_cast<std::size_t>(row)]) ++resumed;
                    row_done[static_cast<std::size_t>(row)] = true;
                    rows[static_cast<std::size_t>(row)] = std::move(pts);
                }
            } catch (const ScanError& e) {
                throw UsageError("scan: --resume: " + c.log_path + ": " + e.what());
            }
        }
        for (int j = 0; j < spec.y.n; ++j)
            if (!row_done[static_cast<std::size_t>(j)]) todo.push_back(j);
        log.open(c.log_path, std::ios::trunc);
        if (!log) throw UsageError("scan: cannot write the tile log " + c.log_path);
        log << header << '\n';
        for (int j = 0; j < spec.y.n; ++j)
            if (row_done[static_cast<std::size_t>(j)]) log << scan_log_line(j, rows[static_cast<std::size_t>(j)]) << '\n';
        log.flush();
        if (!log) throw std::runtime_error(c.log_path + ": write failed (" + std::strerror(errno) + ")");
        if (c.resume) std::fprintf(stderr, "scan: resumed %zu of %d rows from %s\n", resumed, spec.y.n, c.log_path.c_str());
    }

    void write_ready_rows(const ScanCommand& c, Progress& progress) {
        while (next_row < c.spec.y.n && row_done[static_cast<std::size_t>(next_row)]) {
            auto& r = rows[static_cast<std::size_t>(next_row)];
            write_scan_csv_row(c.spec, next_row, r, *out);
            if (c.png.empty()) std::vector<ScanPoint>().swap(r);
            ++next_row;
        }
        out->flush();   // each finished row reaches the (partial) file now
        if (out->error() != 0) progress.cancel.store(true);   // a full disk: stop computing what cannot be written
    }

    // One call at a time.
    void record_row(const ScanCommand& c, int row, const std::vector<ScanPoint>& pts, Progress& progress) {
        rows[static_cast<std::size_t>(row)] = pts;
        row_done[static_cast<std::size_t>(row)] = true;
        write_ready_rows(c, progress);
        errno = 0;
        log << scan_log_line(row, pts) << '\n';
        log.flush();   // a kill loses at most the rows in flight
        if (!log && log_errno == 0) {
            log_errno = errno != 0 ? errno : EIO;
            progress.cancel.store(true);
        }
    }
};

// The curves asked for, each continued along the y axis at half its grid step: printed, drawn over the maps
// and, with --curves-out, written.
std::vector<ScanCurve> follow_curves(const ScanCommand& c) {
    const ScanSpec& spec = c.spec;
    std::vector<ScanCurve> curves;
    std::vector<std::pair<const char*, analysis::BifCurve>> followed;   // for --curves-out
    const analysis::ContParam second = spec.y.param;   // xI or m0e (checked with the curves' flags)
    const double step = 0.5 * (spec.y.hi - spec.y.lo) / std::max(1, spec.y.n - 1);
    auto add_curve = [&](const char* what, const char* label, analysis::BifCurve bc, bool dashed, bool dotted) {
        ScanCurve sc;
        sc.label = label;
        sc.dashed = dashed;
        sc.dotted = dotted;
        for (const auto& q : bc.points) {
            sc.x.push_back(q.omega);
            sc.y.push_back(q.q);
        }
        std::fprintf(stderr, "%s curve: %zu points, ends: %s\n", what, bc.points.size(), bc.end.c_str());
        curves.push_back(std::move(sc));
        followed.emplace_back(what, std::move(bc));
    };
    // `auto`: the first period-1 point of the kind over the x axis's omega range, found by continuation.
    auto found = [&](analysis::BifKind kind, const char* what) {
        const analysis::PlaneCurve d =
            analysis::curve_over_plane(c.p, {second, spec.x.lo, spec.x.hi, spec.y.lo, spec.y.hi, step, kind});
        if (!d.found) std::fprintf(stderr, "%s curve: %s\n", what, d.note.c_str());
        else std::fprintf(stderr, "%s curve: started at the period-1 %s at omega = %.7f, (x, v) = (%.7f, %.7f)\n", what, what,
                          d.omega0, d.y0[0], d.y0[1]);
        return d.curve;
    };
    struct Asked {
        analysis::BifKind kind;
        const char *what, *label;
        bool dashed, dotted;
        const CurveAsk& ask;
    };
    const Asked asked[] = {
        {analysis::BifKind::PeriodDoubling, "doubling", "period doubling, continued", false, false, c.doubling},
        {analysis::BifKind::Grazing, "grazing", "grazing, continued (dashed)", true, false, c.grazing},
        {analysis::BifKind::Fold, "fold", "fold, continued (dotted)", false, true, c.fold}};
    for (const Asked& k : asked) {
        const std::vector<double>& from = k.ask.from;
        if (k.ask.is_auto)
            add_curve(k.what, k.label, found(k.kind, k.what), k.dashed, k.dotted);
        else if (!from.empty())
            add_curve(k.what, k.label,
                      analysis::continue_curve(k.kind, c.p, second, from[0], Vec2(from[1], from[2]), static_cast<int>(from[3]),
                                               spec.y.lo, spec.y.hi, step),
                      k.dashed, k.dotted);
    }
    if (!c.curves_path.empty()) {
        // Full precision: the visualiser's test compares its own curves with these.
        OutputFile cf(c.curves_path, "--curves-out");
        cf << "curve,omega," << spec.y.name() << "\n";
        char line[96];
        for (const auto& [what, bc] : followed)
            for (const auto& q : bc.points) {
                std::snprintf(line, sizeof line, "%s,%.17g,%.17g\n", what, q.omega, q.q);
                cf << line;
            }
        cf.commit();
    }
    return curves;
}

}  // namespace

int cmd_scan(const std::vector<std::string>& argv) {
    if (show_help_if_asked(argv, kScanHelp, kModelHelp)) return 0;
#ifdef IMPACTLAB_HAVE_MPI
    const ScanCluster cluster;
    const int rank = cluster.rank(), ranks = cluster.ranks();
#else
    const int rank = 0, ranks = 1;
#endif
    // Every rank parses the same argv; only rank 0 touches files, and it tells the others whether to go on.
    ScanCommand c;
    ScanFiles files;
    try {
        const Args a("scan", argv,
                     with_model_flags({"--x", "--y", "--measure", "--out", "--png", "--threads", "--transient", "--record",
                                       "--start", "--omega", "--doubling-from", "--grazing-from", "--fold-from",
                                       "--curves-out"}),
                     {"--resume"});
        c = read_command(a);
        files.rows = empty_rows(c.spec);
        if (rank == 0) files.open(c);
    } catch (...) {
#ifdef IMPACTLAB_HAVE_MPI
        cluster.agree(false);
        if (rank != 0) return 2;   // rank 0 says what was wrong
#endif
        throw;
    }
#ifdef IMPACTLAB_HAVE_MPI
    if (!cluster.agree(true)) return 2;
#endif

    Progress progress;
    if (rank == 0) {
        write_scan_csv_header(c.spec, *files.out);
        files.write_ready_rows(c, progress);   // what --resume read back
    }
    auto record_row = [&](int row, const std::vector<ScanPoint>& pts) { files.record_row(c, row, pts, progress); };
    if (ranks == 1) {
        ProgressBar bar("scan " + c.p.name, progress);
        scan_rows(c.p, c.spec, files.todo, c.threads, &progress, c.tol, record_row);
    }
#ifdef IMPACTLAB_HAVE_MPI
    else if (rank == 0) {
        ProgressBar bar("scan " + c.p.name + " (" + std::to_string(ranks - 1) + " MPI workers)", progress);
        cluster.hand_out(c.spec, files.todo, &progress, record_row);
    } else {
        cluster.work(c.p, c.spec, c.tol);
        return 0;
    }
#endif
    if (files.log_errno != 0)
        throw std::runtime_error(c.log_path + ": write failed (" + std::strerror(files.log_errno) + "); the scan stopped");
    files.out->check();
    if (files.next_row != c.spec.y.n)
        throw std::runtime_error("scan: " + std::to_string(c.spec.y.n - files.next_row) + " rows were not computed");
    const std::vector<ScanCurve> curves = follow_curves(c);
    if (!c.png.empty()) save_scan_png(c.spec, files.rows, c.p.name, c.png, curves);   // first: a PNG that fails leaves the old CSV
    files.out->commit();
    files.log.close();
    std::filesystem::remove(c.log_path);   // complete: nothing to resume
    std::fprintf(stderr, "scan %s: %d x %d points (%zu rows computed, %d %s) -> %s%s%s\n", printable(c.p.name).c_str(), c.spec.x.n,
                 c.spec.y.n, files.todo.size(), ranks > 1 ? ranks - 1 : c.threads, ranks > 1 ? "MPI workers" : "threads",
                 printable(c.out_path).c_str(), c.png.empty() ? "" : ", ", printable(c.png).c_str());
    return 0;
}

}  // namespace impactlab::cli
