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
#include <mpi.h>
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
    "  --doubling-from W,X,V  a period-1 doubling at omega W with section point (X, V) [m, m/s], as `continue`\n"
    "                      prints it: continued in the y axis (xI or m0e) and drawn over the maps (x: omega);\n"
    "                      `auto`: the first one over the x axis's omega range, found by continuation\n"
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

#ifdef IMPACTLAB_HAVE_MPI
// Launched by mpirun (Open MPI sets these): only then is MPI started, so a plain run never needs a daemon.
bool launched_by_mpirun() {
    return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMIX_RANK") || std::getenv("PMI_SIZE");
}
struct MpiSession {
    int rank = 0, size = 1;
    bool active = false;
    MpiSession() {
        if (!launched_by_mpirun()) return;
        MPI_Init(nullptr, nullptr);
        MPI_Comm_rank(MPI_COMM_WORLD, &rank);
        MPI_Comm_size(MPI_COMM_WORLD, &size);
        active = true;
    }
    ~MpiSession() {
        if (active) MPI_Finalize();
    }
};
constexpr int kTagRequest = 1, kTagRow = 2, kTagResult = 3;
#endif

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
}  // namespace

int cmd_scan(const std::vector<std::string>& argv) {
    if (show_help_if_asked(argv, kScanHelp, kModelHelp)) return 0;
#ifdef IMPACTLAB_HAVE_MPI
    MpiSession mpi;
    const int rank = mpi.rank, ranks = mpi.size;
#else
    const int rank = 0, ranks = 1;
#endif
    // Every rank parses the same argv; only rank 0 touches files, and it tells the others whether to go on.
    [[maybe_unused]] int ok = 1;   // told to the MPI workers (unread without MPI)
    ScanSpec spec;
    Params p;
    std::string out_path, png, log_path, curves_path;
    std::vector<double> doubling_from;   // omega, x, v, 1 of a period-1 doubling (--doubling-from)
    std::vector<double> grazing_from;    // omega, x, v, k of a grazing (--grazing-from)
    std::vector<double> fold_from;       // omega, x, v, k of a fold (--fold-from)
    // --doubling-from auto (--grazing-from, --fold-from): found by curve_over_plane
    bool doubling_auto = false, grazing_auto = false, fold_auto = false;
    std::vector<std::vector<ScanPoint>> rows;
    // Rows are written to --out in order as they finish (row_done: computed or resumed; next_row: the first
    // not yet written); without --png a written row is freed, so memory holds the rows in flight, not the plane.
    std::vector<bool> row_done;
    int next_row = 0;
    std::vector<int> todo;
    int threads = 1;
    Tolerances tol;
    std::optional<OutputFile> out;
    std::ofstream log;
    try {
        const Args a("scan", argv,
                     with_model_flags({"--x", "--y", "--measure", "--out", "--png", "--threads", "--transient", "--record",
                                       "--start", "--omega", "--doubling-from", "--grazing-from", "--fold-from",
                                       "--curves-out"}),
                     {"--resume"});
        p = model_from(a);
        tol = tolerances_from(a);
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
        threads = a.integer("--threads", static_cast<int>(hw), 1, 1024);
        // Every parameter of the plane must be one the model accepts: check its corners.
        for (int j : {0, spec.y.n - 1})
            for (int i : {0, spec.x.n - 1}) {
                Params q = p;
                for (const ScanAxis* ax : {&spec.x, &spec.y}) {
                    const double v = ax->at(ax == &spec.x ? i : j);
                    if (ax->param == ScanParam::XI) q.xI = v;
                    if (ax->param == ScanParam::M0e) q.m0e = v;
                }
                validate(q, "scan plane corner");
            }
        if (a.has("--doubling-from")) {
            if (!a.has("--png") && !a.has("--curves-out"))
                throw UsageError("scan: --doubling-from draws on the PNG or writes --curves-out: give --png or --curves-out");
            if (spec.x.param != ScanParam::Omega || spec.y.param == ScanParam::Omega)
                throw UsageError("scan: --doubling-from needs --x omega:... and --y xI:... or m0e:...");
            const std::string v = a.str("--doubling-from", "");
            double w[3];
            if (v == "auto") {   // the first period-1 doubling over the x axis's omega range, found by continuation
                doubling_auto = true;
            } else {
                char tail = 0;
                if (std::sscanf(v.c_str(), "%lf,%lf,%lf%c", &w[0], &w[1], &w[2], &tail) != 3)
                    throw UsageError("scan: option '--doubling-from': expected OMEGA,X,V (a period-1 doubling, as continue prints it), got '" +
                                     v + "'");
                check_curve_start("--doubling-from", w);
                doubling_from = {w[0], w[1], w[2], 1};
            }
        }
        for (const char* flag : {"--grazing-from", "--fold-from"}) {
            if (!a.has(flag)) continue;
            const std::string f = flag;
            const std::string what = f == "--fold-from" ? "fold" : "grazing";
            if (!a.has("--png") && !a.has("--curves-out"))
                throw UsageError("scan: " + f + " draws on the PNG or writes --curves-out: give --png or --curves-out");
            if (spec.x.param != ScanParam::Omega || spec.y.param == ScanParam::Omega)
                throw UsageError("scan: " + f + " needs --x omega:... and --y xI:... or m0e:...");
            if (what == "grazing" && !p.has_bumper()) throw UsageError("scan: --grazing-from needs a model with a bumper");
            const std::string v = a.str(flag, "");
            if (v == "auto") {
                (what == "fold" ? fold_auto : grazing_auto) = true;
                continue;
            }
            double w[4] = {0, 0, 0, 1};
            char tail = 0;
            const int n = std::sscanf(v.c_str(), "%lf,%lf,%lf,%lf%c", &w[0], &w[1], &w[2], &w[3], &tail);
            if ((n != 3 && n != 4) || !(w[3] >= 1 && w[3] <= 64) || w[3] != std::floor(w[3]))
                throw UsageError("scan: option '" + f + "': expected OMEGA,X,V[,K] with K in 1..64 (a " + what +
                                 " of the period-K orbit, as continue prints it), got '" + v + "'");
            check_curve_start(f, w);
            (what == "fold" ? fold_from : grazing_from) = {w[0], w[1], w[2], w[3]};
        }
        out_path = a.required("--out");
        png = a.str("--png", "");
        curves_path = a.str("--curves-out", "");
        if (!curves_path.empty() && !a.has("--doubling-from") && !a.has("--grazing-from") && !a.has("--fold-from"))
            throw UsageError("scan: --curves-out writes the continued curves: give --doubling-from, --grazing-from or --fold-from");
        log_path = out_path + ".tiles";
        rows = empty_rows(spec);
        if (rank == 0) {
            out.emplace(out_path, "--out");
            if (!png.empty()) check_writable(png, "--png");
            if (!curves_path.empty()) check_writable(curves_path, "--curves-out");
            row_done.assign(static_cast<std::size_t>(spec.y.n), false);
            std::vector<bool>& done = row_done;
            const std::string header = scan_log_header(p, spec, tol);
            std::size_t resumed = 0;
            if (a.has("--resume") && std::filesystem::exists(log_path)) {
                std::istringstream in;
                try {
                    in.str(read_input_file(log_path));
                } catch (const InputFileError& e) {
                    throw UsageError(std::string("scan: --resume: ") + e.what());
                }
                try {
                    for (auto& [row, pts] : read_scan_log(in, header, spec)) {
                        if (!done[static_cast<std::size_t>(row)]) ++resumed;
                        done[static_cast<std::size_t>(row)] = true;
                        rows[static_cast<std::size_t>(row)] = std::move(pts);
                    }
                } catch (const ScanError& e) {
                    throw UsageError("scan: --resume: " + log_path + ": " + e.what());
                }
            }
            for (int j = 0; j < spec.y.n; ++j)
                if (!done[static_cast<std::size_t>(j)]) todo.push_back(j);
            // The log is rewritten whole (the rows read back, then the new ones as they finish).
            log.open(log_path, std::ios::trunc);
            if (!log) throw UsageError("scan: cannot write the tile log " + log_path);
            log << header << '\n';
            for (int j = 0; j < spec.y.n; ++j)
                if (done[static_cast<std::size_t>(j)]) log << scan_log_line(j, rows[static_cast<std::size_t>(j)]) << '\n';
            log.flush();
            if (!log) throw std::runtime_error(log_path + ": write failed (" + std::strerror(errno) + ")");
            if (a.has("--resume"))
                std::fprintf(stderr, "scan: resumed %zu of %d rows from %s\n", resumed, spec.y.n, log_path.c_str());
        }
    } catch (...) {
        ok = 0;
#ifdef IMPACTLAB_HAVE_MPI
        if (mpi.active) {
            MPI_Bcast(&ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
            if (rank != 0) return 2;   // rank 0 says what was wrong
        }
#endif
        throw;
    }
#ifdef IMPACTLAB_HAVE_MPI
    if (mpi.active) {
        MPI_Bcast(&ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
        if (!ok) return 2;
    }
#endif

    [[maybe_unused]] const std::size_t nx = static_cast<std::size_t>(spec.x.n);   // a row's points, as MPI messages carry them
    Progress progress;
    int log_errno = 0;   // the tile log's first failed write: the scan stops, as nothing could be resumed
    auto write_ready_rows = [&] {
        while (next_row < spec.y.n && row_done[static_cast<std::size_t>(next_row)]) {
            auto& r = rows[static_cast<std::size_t>(next_row)];
            write_scan_csv_row(spec, next_row, r, *out);
            if (png.empty()) std::vector<ScanPoint>().swap(r);
            ++next_row;
        }
        out->flush();   // each finished row reaches the (partial) file now
        if (out->error() != 0) progress.cancel.store(true);   // a full disk: stop computing what cannot be written
    };
    if (rank == 0) {
        write_scan_csv_header(spec, *out);
        write_ready_rows();   // what --resume read back
    }
    auto record_row = [&](int row, const std::vector<ScanPoint>& pts) {   // rank 0, one call at a time
        rows[static_cast<std::size_t>(row)] = pts;
        row_done[static_cast<std::size_t>(row)] = true;
        write_ready_rows();
        errno = 0;
        log << scan_log_line(row, pts) << '\n';
        log.flush();   // a kill loses at most the rows in flight
        if (!log && log_errno == 0) {
            log_errno = errno != 0 ? errno : EIO;
            progress.cancel.store(true);
        }
    };
    if (ranks == 1) {
        ProgressBar bar("scan " + p.name, progress);
        scan_rows(p, spec, todo, threads, &progress, tol, record_row);
    }
#ifdef IMPACTLAB_HAVE_MPI
    else if (rank == 0) {
        // Dynamic hand-out: a worker asks, gets the next row (or -1: done), and sends the row's values back.
        ProgressBar bar("scan " + p.name + " (" + std::to_string(ranks - 1) + " MPI workers)", progress);
        std::size_t next = 0, finished = 0;
        int stopped = 0;
        std::vector<double> buf(1 + 5 * nx);
        while (stopped < ranks - 1) {
            MPI_Status st;
            MPI_Recv(buf.data(), static_cast<int>(buf.size()), MPI_DOUBLE, MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &st);
            if (st.MPI_TAG == kTagResult) {
                std::vector<ScanPoint> pts(nx);
                for (std::size_t i = 0; i < nx; ++i)
                    pts[i] = {buf[1 + 5 * i], buf[2 + 5 * i], buf[3 + 5 * i], buf[4 + 5 * i], buf[5 + 5 * i]};
                record_row(static_cast<int>(buf[0]), pts);
                progress.fraction.store(static_cast<double>(++finished) / std::max<std::size_t>(1, todo.size()));
            }
            int row = -1;
            if (next < todo.size()) row = todo[next++];
            else ++stopped;
            MPI_Send(&row, 1, MPI_INT, st.MPI_SOURCE, kTagRow, MPI_COMM_WORLD);
        }
    } else {
        std::vector<double> buf(1 + 5 * nx);
        double dummy = 0;
        MPI_Send(&dummy, 1, MPI_DOUBLE, 0, kTagRequest, MPI_COMM_WORLD);
        for (;;) {
            int row = -1;
            MPI_Recv(&row, 1, MPI_INT, 0, kTagRow, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
            if (row < 0) break;
            const std::vector<ScanPoint> pts = scan_row(p, spec, row, tol);
            buf[0] = row;
            for (std::size_t i = 0; i < nx; ++i) {
                buf[1 + 5 * i] = pts[i].period;
                buf[2 + 5 * i] = pts[i].lyapunov;
                buf[3 + 5 * i] = pts[i].impacts;
                buf[4 + 5 * i] = pts[i].xmin;
                buf[5 + 5 * i] = pts[i].xmax;
            }
            MPI_Send(buf.data(), static_cast<int>(buf.size()), MPI_DOUBLE, 0, kTagResult, MPI_COMM_WORLD);
        }
        return 0;
    }
#endif
    if (log_errno != 0) throw std::runtime_error(log_path + ": write failed (" + std::strerror(log_errno) + "); the scan stopped");
    out->check();
    if (next_row != spec.y.n) throw std::runtime_error("scan: " + std::to_string(spec.y.n - next_row) + " rows were not computed");
    std::vector<ScanCurve> curves;
    std::vector<std::pair<const char*, analysis::BifCurve>> followed;   // for --curves-out
    // Each curve continued along the y axis at half its grid step, drawn over the maps.
    const analysis::ContParam second = spec.y.param;   // xI or m0e (checked with the curves' flags)
    const double step = 0.5 * (spec.y.hi - spec.y.lo) / std::max(1, spec.y.n - 1);
    auto add_curve = [&](const char* what, const char* label, analysis::BifCurve c, bool dashed, bool dotted) {
        ScanCurve sc;
        sc.label = label;
        sc.dashed = dashed;
        sc.dotted = dotted;
        for (const auto& q : c.points) {
            sc.x.push_back(q.omega);
            sc.y.push_back(q.q);
        }
        std::fprintf(stderr, "%s curve: %zu points, ends: %s\n", what, c.points.size(), c.end.c_str());
        curves.push_back(std::move(sc));
        followed.emplace_back(what, std::move(c));
    };
    // `auto`: the first period-1 point of the kind over the x axis's omega range, found by continuation.
    auto found = [&](analysis::BifKind kind, const char* what) {
        const analysis::PlaneCurve d =
            analysis::curve_over_plane(p, {second, spec.x.lo, spec.x.hi, spec.y.lo, spec.y.hi, step, kind});
        if (!d.found) std::fprintf(stderr, "%s curve: %s\n", what, d.note.c_str());
        else std::fprintf(stderr, "%s curve: started at the period-1 %s at omega = %.7f, (x, v) = (%.7f, %.7f)\n", what, what,
                          d.omega0, d.y0[0], d.y0[1]);
        return d.curve;
    };
    struct Asked {
        analysis::BifKind kind;
        const char *what, *label;
        bool dashed, dotted, is_auto;
        const std::vector<double>& from;   // omega, x, v, k
    };
    const Asked asked[] = {
        {analysis::BifKind::PeriodDoubling, "doubling", "period doubling, continued", false, false, doubling_auto, doubling_from},
        {analysis::BifKind::Grazing, "grazing", "grazing, continued (dashed)", true, false, grazing_auto, grazing_from},
        {analysis::BifKind::Fold, "fold", "fold, continued (dotted)", false, true, fold_auto, fold_from}};
    for (const Asked& k : asked) {
        if (k.is_auto)
            add_curve(k.what, k.label, found(k.kind, k.what), k.dashed, k.dotted);
        else if (!k.from.empty())
            add_curve(k.what, k.label,
                      analysis::continue_curve(k.kind, p, second, k.from[0], Vec2(k.from[1], k.from[2]), static_cast<int>(k.from[3]),
                                               spec.y.lo, spec.y.hi, step),
                      k.dashed, k.dotted);
    }
    if (!curves_path.empty()) {
        // Full precision: the visualiser's test compares its own curves with these.
        OutputFile cf(curves_path, "--curves-out");
        cf << "curve,omega," << spec.y.name() << "\n";
        char line[96];
        for (const auto& [what, c] : followed)
            for (const auto& q : c.points) {
                std::snprintf(line, sizeof line, "%s,%.17g,%.17g\n", what, q.omega, q.q);
                cf << line;
            }
        cf.commit();
    }
    if (!png.empty()) save_scan_png(spec, rows, p.name, png, curves);   // first: a PNG that fails leaves the old CSV
    out->commit();
    log.close();
    std::filesystem::remove(log_path);   // complete: nothing to resume
    std::fprintf(stderr, "scan %s: %d x %d points (%zu rows computed, %d %s) -> %s%s%s\n", printable(p.name).c_str(), spec.x.n,
                 spec.y.n, todo.size(), ranks > 1 ? ranks - 1 : threads,
                 ranks > 1 ? "MPI workers" : "threads", printable(out_path).c_str(), png.empty() ? "" : ", ", printable(png).c_str());
    return 0;
}

}  // namespace impactlab::cli
