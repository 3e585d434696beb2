// impactlab continue: periodic orbits continued along omega, xI or m0e, with their bifurcations.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <numbers>
#include <tuple>
#include <utility>

#include "analysis_common.hpp"
#include "commands.hpp"
#include "impactlab/input_file.hpp"
#include "impactlab/plot.hpp"
#include "impactlab/simulator.hpp"

namespace impactlab::cli {

namespace {

// The --param family: the parameter continued and its range, omega's flags or those of xI and m0e.
void set_range(const Args& a, analysis::ContinuationSpec& spec) {
    const std::string param = a.str("--param", "omega");
    if (param == "omega") {
        for (const char* f : {"--omega", "--min", "--max"})
            if (a.has(f)) throw UsageError(std::string("continue: ") + f + " belongs to --param xI or m0e (for omega: --omega-min, --omega-max)");
        spec.param = analysis::ContParam::Omega;
        spec.lo = a.num("--omega-min", 5.0, 0.05, 1000.0);
        spec.hi = a.num("--omega-max", 25.0, 0.05, 1000.0);
        if (spec.hi <= spec.lo) throw UsageError("continue: --omega-max is not above --omega-min");
        spec.start = a.num("--omega-start", spec.lo, spec.lo, spec.hi);
    } else if (param == "xI" || param == "m0e") {
        for (const char* f : {"--omega-min", "--omega-max", "--omega-start"})
            if (a.has(f)) throw UsageError("continue: " + std::string(f) + " belongs to --param omega (for " + param + ": --min, --max)");
        spec.param = param == "xI" ? analysis::ContParam::XI : analysis::ContParam::M0e;
        if (!a.has("--omega")) throw UsageError("continue: --param " + param + " needs '--omega'");
        spec.omega = a.num("--omega", 10.0, 0.05, 1000.0);
        if (!a.has("--min") || !a.has("--max")) throw UsageError("continue: --param " + param + " needs '--min' and '--max'");
        // The model's physical range, as --xI and --m0e take it: the bumper on the rail, an unbalance >= 0.
        const double lo = param == "xI" ? -0.1 : 0.0, hi = param == "xI" ? 0.1 : 10.0;
        spec.lo = a.num("--min", 0.0, lo, hi);
        spec.hi = a.num("--max", 0.0, lo, hi);
        if (spec.hi <= spec.lo) throw UsageError("continue: --max is not above --min");
        spec.start = spec.lo;
    } else {
        throw UsageError("continue: option '--param': '" + param + "' is not one of omega, xI, m0e");
    }
}

// The continuation's flags: the range, the first orbit's start and period, the periods followed, the
// integrator.
analysis::ContinuationSpec continue_spec(const Args& a, const Params& p) {
    analysis::ContinuationSpec spec;
    set_range(a, spec);
    if (a.has("--from")) {
        spec.guess = to_vec2(a.pair("--from"));
        check_start(p, spec.guess[0], "continue", "--from");
    }
    spec.period = a.integer("--period", 1, 1, 64);
    spec.max_period = a.integer("--max-period", 8, 1, 256);
    spec.sim = analysis_tol(a);
    return spec;
}

// The branches and the bifurcation points, one row per point.
void write_tables(const analysis::ContinuationResult& r, const char* pname, OutputFile& br, OutputFile& pt) {
    br << "branch," << pname << ",x,v,period,stable\n";
    for (const auto& b : r.branches)
        for (const auto& q : b.points)
            br << b.id << ',' << q.param << ',' << q.y[0] << ',' << q.y[1] << ',' << q.period << ',' << (q.stable ? 1 : 0) << '\n';
    pt.precision(12);
    pt << "kind," << pname << ",x,v,period\n";
    for (const auto& q : r.points)
        pt << analysis::bif_kind_name(q.kind) << ',' << q.param << ',' << q.y[0] << ',' << q.y[1] << ',' << q.period << '\n';
    br.check();
    pt.check();
}

// The listing: each branch and how it ends, each point, a cascade's ratios, each grazing crossed.
void print_result(const analysis::ContinuationResult& r, const char* pname) {
    for (const auto& b : r.branches)
        std::printf("branch %d: period %d, %zu points%s, ends: %s\n", b.id, b.period, b.points.size(),
                    b.parent >= 0 ? (" (from branch " + std::to_string(b.parent) + ")").c_str() : "", b.end.c_str());
    for (const auto& q : r.points)
        std::printf("%-16s %s = %.9g (+- %.1g), period %d, x = %.6g m, v = %.6g m/s\n", analysis::bif_kind_name(q.kind), pname,
                    q.param, q.precision, q.period, q.y[0], q.y[1]);
    // A cascade of doublings on switched branches: Feigenbaum's ratios as a check of the points' accuracy.
    if (const analysis::Cascade c = analysis::find_cascade(r); c.doublings.size() >= 3) {
        std::printf("cascade: doublings of period");
        for (const analysis::BifPoint* d : c.doublings) std::printf(" %d at %.9g", d->period, d->param);
        std::printf("\ncascade: ratios (q_k - q_k-1) / (q_k+1 - q_k):");
        for (double x : c.ratios) std::printf(" %.4f", x);
        std::printf(" (Feigenbaum's delta %.4f)\n", analysis::kFeigenbaumDelta);
    }
    for (const auto& q : r.points)
        if (!q.scenario.empty() && std::isfinite(q.mu_exponent)) {
            std::printf("grazing at %s = %.9g crossed onto the impacting branch: %s; |mu| ~ d^%.3f, v- ~ d^%.3f "
                        "(d: distance from the grazing; the square-root map gives -1, 1)\n",
                        pname, q.param, q.scenario.c_str(), q.mu_exponent, q.speed_exponent);
            // A nonsmooth fold is where the free and the impacting branch meet at the touch; the impacting
            // branch's own turn, a smooth fold (a multiplier through +1), is another point: named apart.
            if (q.scenario == "nonsmooth fold")
                for (const auto& f : r.points)
                    if (f.kind == analysis::BifKind::Fold && f.period == q.period && f.branch != q.branch &&
                        std::abs(f.param - q.param) < 0.5)
                        std::printf("  (the free and the impacting branch meet at the grazing, both on one side; the "
                                    "impacting branch then turns at %s = %.9g, a smooth fold: a multiplier through +1)\n",
                                    pname, f.param);
        }
        else if (!q.scenario.empty())
            std::printf("grazing at %s = %.9g: %s\n", pname, q.param, q.scenario.c_str());
}

// The branches over the parameter (stable solid, unstable dotted, points marked).
void save_branches_png(const Params& p, const analysis::ContinuationSpec& spec, const analysis::ContinuationResult& r,
                       const char* pname, const std::string& path) {
    plot::Figure fig;
    fig.width = 1200;
    fig.panel_height = 500;
    fig.title = p.name + ": continued periodic orbits (x at phi = 0)";
    plot::Panel pan;
    pan.xlabel = std::string(pname) + (spec.param == analysis::ContParam::Omega ? " [rad/s]" : "");
    pan.ylabel = "x [mm]";
    const plot::Color colors[] = {{31, 119, 180, 255}, {255, 127, 14, 255}, {44, 160, 44, 255}, {148, 103, 189, 255},
                                  {214, 39, 40, 255}, {140, 86, 75, 255}};
    const std::vector<analysis::BranchCurve> curves = analysis::branch_curves(r);
    for (int per : {1, 2, 4, 8, 16, 32}) {
        plot::Series st{plot::Series::Kind::Line, {}, {}, colors[std::min(5, static_cast<int>(std::log2(per)))], 2.0f,
                        "period " + std::to_string(per) + " stable"};
        plot::Series un{plot::Series::Kind::Points, {}, {}, st.color, 0.8f, "period " + std::to_string(per) + " unstable"};
        // Each of the k section points of an orbit is a point of the diagram, as in a sweep: one curve per
        // section point.
        for (const analysis::BranchCurve& cv : curves) {
            if (cv.period != per) continue;
            for (std::size_t i = 0; i < cv.param.size(); ++i) {
                (cv.stable[i] ? st : un).x.push_back(cv.param[i]);
                (cv.stable[i] ? st : un).y.push_back(1e3 * cv.x[i]);
                (cv.stable[i] ? un : st).x.push_back(NAN);
                (cv.stable[i] ? un : st).y.push_back(NAN);
            }
            st.x.push_back(NAN);
            st.y.push_back(NAN);
        }
        if (!st.x.empty() && std::any_of(st.x.begin(), st.x.end(), [](double v) { return std::isfinite(v); }))
            pan.series.push_back(st);
        if (!un.x.empty() && std::any_of(un.x.begin(), un.x.end(), [](double v) { return std::isfinite(v); }))
            pan.series.push_back(un);
    }
    for (analysis::BifKind k : {analysis::BifKind::PeriodDoubling, analysis::BifKind::Fold, analysis::BifKind::Grazing,
                                analysis::BifKind::NeimarkSacker}) {
        plot::Series s{plot::Series::Kind::Points, {}, {}, {0, 0, 0, 255}, 4.0f, analysis::bif_kind_name(k)};
        if (k == analysis::BifKind::Fold) s.color = {214, 39, 40, 255};
        if (k == analysis::BifKind::Grazing) s.color = {140, 86, 75, 255};
        for (const auto& q : r.points)
            if (q.kind == k) {
                s.x.push_back(q.param);
                s.y.push_back(1e3 * q.y[0]);
            }
        if (!s.x.empty()) pan.series.push_back(s);
    }
    fig.panels.push_back(pan);
    plot::save_png(fig, path);
    std::fprintf(stderr, "plot -> %s\n", printable(path).c_str());
}

}  // namespace

int cmd_continue(const std::vector<std::string>& argv) {
    if (wants_help_tight(argv, "usage: impactlab continue --model A1C --omega-min 5 --omega-max 25 --out DIR [--png FILE]\n\n"
                         "Pseudo-arclength continuation of periodic orbits (stable and unstable) with folds, period doublings\n"
                         "(the period-2k branch switched onto), Neimark-Sacker and grazing located to 1e-7 in the parameter.\n"
                         "A branch of a G version goes on through a grazing onto the impacting branch (from impact to impact\n"
                         "while the impacts are slower than 0.05 m/s); each grazing crossed is printed with its scenario and\n"
                         "the impacting orbit's scaling. A branch back at an earlier orbit ends (\"closed loop\"). A cascade\n"
                         "of doublings is printed with Feigenbaum's ratios (omega_k - omega_k-1) / (omega_k+1 - omega_k).\n"
                         "Writes DIR/branches.csv (branch,omega,x,v,period,stable; x, v at the section phi = 0) and\n"
                         "DIR/points.csv (kind,omega,x,v,period).\n"
                         "  --omega-min W, --omega-max W   the range [rad/s] (default 5, 25)\n"
                         "  --omega-start W  where the first orbit is found (default: omega-min)\n"
                         "  --from X,V       its start (default: 200 periods from the left well's bottom)\n"
                         "  --period K       period of the first branch (default 1)\n"
                         "  --max-period K   follow period doublings up to this period (default 8)\n"
                         "  --param P        omega (default), xI or m0e: continue in the bumper position or the forcing\n"
                         "                   amplitude at fixed --omega, between --min and --max\n"
                         "  --omega W        fixed omega for --param xI|m0e [rad/s]\n"
                         "  --min V, --max V the range of xI [m] or m0e [kg m]\n"
                         "  --out DIR        output directory (required)\n"
                         "  --png FILE       the branches over the parameter (stable solid, unstable dotted, points marked)\n"))
        return 0;
    const Args a("continue", argv,
                 with_model_flags({"--omega-min", "--omega-max", "--omega-start", "--from", "--period", "--max-period",
                                   "--param", "--omega", "--min", "--max", "--out", "--png"}));
    const Params p = model_from(a, "A1C");
    const analysis::ContinuationSpec spec = continue_spec(a, p);
    const std::string dir = a.required("--out");
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw UsageError("continue: option '--out': cannot create directory '" + dir + "'");
    auto br = open_out(dir + "/branches.csv");
    auto pt = open_out(dir + "/points.csv");
    Progress progress;
    analysis::ContinuationResult r;
    {
        ProgressBar bar("continue " + p.name, progress);
        r = analysis::continue_orbits(p, spec, &progress);
    }
    const char* pname = sweep_param_name(spec.param);
    write_tables(r, pname, br, pt);
    // No orbit at all: say so, and print no branch listing that looks like a result.
    if (r.branches.size() == 1 && r.branches[0].points.empty()) {
        std::fprintf(stderr, "continue: no period-%d orbit to continue: %s\n", spec.period, r.branches[0].end.c_str());
        return 1;
    }
    std::fprintf(stderr, "%s: %zu branches, %zu bifurcation points, %llu map evaluations, %.2f s -> %s\n", printable(p.name).c_str(),
                 r.branches.size(), r.points.size(), static_cast<unsigned long long>(r.map_evaluations), r.seconds, printable(dir).c_str());
    print_result(r, pname);
    if (a.has("--png")) save_branches_png(p, spec, r, pname, a.str("--png", ""));
    return 0;
}

}  // namespace impactlab::cli
