// Commands beyond the sweep: orbit, continue, lyapunov, basins. Thin over core/analysis.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <numbers>
#include <tuple>
#include <utility>

#include "commands.hpp"
#include "common.hpp"
#include "impactlab/analysis.hpp"
#include "impactlab/plot.hpp"
#include "impactlab/simulator.hpp"

namespace impactlab::cli {

namespace {

// Every analysis command takes the model flags: its help ends with them.
bool wants_help(const std::vector<std::string>& args, const char* text) { return show_help_if_asked(args, text, kModelHelp); }
// orbit and continue default to analysis_tol's 1e-10, not the shared help's 1e-8: their help says so.
bool wants_help_tight(const std::vector<std::string>& args, const char* text) {
    if (!show_help_if_asked(args, text, kModelHelp)) return false;
    std::printf("  (--rtol: default 1e-10 here: Newton and the monodromy need the map smooth far below the orbit tolerance)\n");
    return true;
}

// The analysis needs a tighter integrator than a sweep: --rtol given wins, else 1e-10.
Tolerances analysis_tol(const Args& a) {
    return a.has("--rtol") ? tolerances_from(a) : analysis::analysis_tolerances(1e-10);
}

Vec2 parse_pair(const Args& a, const std::string& flag, const std::string& cmd) {
    const auto parts = split_list(a.str(flag, ""));
    if (parts.size() != 2) throw UsageError(cmd + ": option '" + flag + "': expected X,V (two numbers)");
    Vec2 y;
    for (int i = 0; i < 2; ++i) {
        char* end = nullptr;
        y[i] = std::strtod(parts[static_cast<std::size_t>(i)].c_str(), &end);
        if (end == parts[static_cast<std::size_t>(i)].c_str() || *end || !std::isfinite(y[i]))
            throw UsageError(cmd + ": option '" + flag + "': '" + parts[static_cast<std::size_t>(i)] + "' is not a finite number");
    }
    return y;
}

// "A:B" with A < B, both finite, inside [lo, hi].
std::pair<double, double> parse_range(const Args& a, const std::string& flag, const std::string& cmd, double lo, double hi,
                                      std::pair<double, double> fallback) {
    if (!a.has(flag)) return fallback;
    const std::string s = a.str(flag, "");
    const auto colon = s.find(':');
    if (colon == std::string::npos) throw UsageError(cmd + ": option '" + flag + "': expected A:B, got '" + s + "'");
    double r[2];
    const std::string parts[2] = {s.substr(0, colon), s.substr(colon + 1)};
    for (int i = 0; i < 2; ++i) {
        char* end = nullptr;
        r[i] = std::strtod(parts[i].c_str(), &end);
        if (parts[i].empty() || *end || !std::isfinite(r[i]) || r[i] < lo || r[i] > hi)
            throw UsageError(cmd + ": option '" + flag + "': '" + parts[i] + "' is not a number in [" + std::to_string(lo) +
                             ", " + std::to_string(hi) + "]");
    }
    if (!(r[1] > r[0])) throw UsageError(cmd + ": option '" + flag + "': the end is not above the start");
    return {r[0], r[1]};
}

std::string fmt_mu(const std::complex<double>& m) {
    char buf[96];
    if (std::abs(m.imag()) < 1e-12) std::snprintf(buf, sizeof buf, "%.8g", m.real());
    else std::snprintf(buf, sizeof buf, "%.8g%+.8gi (|mu| = %.8g)", m.real(), m.imag(), std::abs(m));
    return buf;
}

}  // namespace

int cmd_orbit(const std::vector<std::string>& argv) {
    if (wants_help_tight(argv, "usage: impactlab orbit --model A1C --omega 10 --period 1 [--from x,v] --out orbit.csv [--png orbit.png]\n\n"
                         "Finds a period-k orbit as a fixed point of the k-th Poincare map (phi = 2 pi i) by Newton, with the\n"
                         "monodromy from the variational equations and the impact law's saltation matrices. Writes the orbit\n"
                         "t,x,v,phi over k periods; prints its section point, period, Floquet multipliers and stability.\n"
                         "  --omega W        forcing frequency [rad/s] (required)\n"
                         "  --period K       forcing periods per repetition (default 1)\n"
                         "  --from X,V       Newton's start at phi = 0 [m],[m/s] (default: 200 periods from the left well)\n"
                         "  --out FILE       CSV output t,x,v,phi (required)\n"
                         "  --dt DT          output sample step [s] (default 1e-3)\n"
                         "  --png FILE       phase portrait of the orbit with its section points\n"))
        return 0;
    const Args a("orbit", argv, with_model_flags({"--omega", "--period", "--from", "--out", "--dt", "--png"}));
    const Params p = model_from(a, "A1C");
    if (!a.has("--omega")) throw UsageError("orbit: missing required option '--omega'");
    const double omega = a.num("--omega", 0, 1e-2, 1000.0);
    const int k = a.integer("--period", 1, 1, 64);
    const double dt = a.num("--dt", 1e-3, 1e-7, 1.0);
    check_rows("orbit", kTwoPi * k / omega / dt, "--period x 2 pi / --omega / --dt");
    const std::string out_path = a.required("--out");
    auto out = open_out(out_path);
    const Tolerances tol = analysis_tol(a);
    analysis::OrbitOptions opt;
    opt.period = k;
    opt.sim = tol;
    Vec2 guess = a.has("--from") ? parse_pair(a, "--from", "orbit")
                                 : analysis::settle(p, omega, Vec2(analysis::left_well(p), 0.0), 200, tol);
    if (a.has("--from")) check_start(p, guess[0], "orbit", "--from");
    const analysis::Orbit o = analysis::find_orbit(p, omega, guess, opt);
    if (!o.converged) {
        std::fprintf(stderr, "orbit: no period-%d orbit found from (%g, %g): %s (residual %.3g)\n", k, guess[0], guess[1],
                     o.message.c_str(), o.residual);
        return 1;
    }
    // The orbit itself, sampled by the simulator from the section point.
    Simulator sim(tol);
    const Drive d(omega);
    State s;
    s.x = o.y[0];
    s.v = o.y[1];
    Simulator::make_consistent(p, d, s);
    out << "t,x,v,phi\n";
    std::vector<double> px, pv;
    UniformSampler sampler(d, dt, 0.0, [&](const Sample& smp) {
        out << smp.t << ',' << smp.x << ',' << smp.v << ',' << smp.phi << '\n';
        px.push_back(smp.x);
        pv.push_back(smp.v);
    });
    sim.advance(p, d, s, d.time_of_phase(kTwoPi * k), &sampler);
    if (!out) throw std::runtime_error(out_path + ": write failed");
    std::printf("%s omega = %.10g rad/s, period %d (%.10g s)\n", p.name.c_str(), omega, k, kTwoPi * k / omega);
    std::printf("section point: x = %.12g m, v = %.12g m/s (residual %.2g, %d Newton iterations)\n", o.y[0], o.y[1],
                o.residual, o.iterations);
    std::printf("Floquet multipliers: %s, %s\n", fmt_mu(o.floquet.mu[0]).c_str(), fmt_mu(o.floquet.mu[1]).c_str());
    std::printf("stable: %s; impacts per period-%d: %d; largest x: %.6g m\n", o.floquet.stable ? "yes" : "no", k, o.impacts,
                o.max_x);
    if (a.has("--png")) {
        plot::Figure fig;
        fig.width = 800;
        fig.panel_height = 600;
        fig.title = p.name + " period-" + std::to_string(k) + " orbit, omega = " + std::to_string(omega) + " rad/s";
        plot::Panel pan;
        pan.xlabel = "x [m]";
        pan.ylabel = "v [m/s]";
        pan.series.push_back({plot::Series::Kind::Line, px, pv, {31, 119, 180, 255}, 1.5f, "orbit"});
        std::vector<double> sx{o.y[0]}, sv{o.y[1]};
        for (const auto& y : o.sections) {
            sx.push_back(y[0]);
            sv.push_back(y[1]);
        }
        pan.series.push_back({plot::Series::Kind::Points, sx, sv, {214, 39, 40, 255}, 4.0f, "section points"});
        if (p.has_bumper()) pan.vlines.push_back(p.xI);
        fig.panels.push_back(pan);
        plot::save_png(fig, a.str("--png", ""));
    }
    return 0;
}

int cmd_continue(const std::vector<std::string>& argv) {
    if (wants_help_tight(argv, "usage: impactlab continue --model A1C --omega-min 5 --omega-max 25 --out DIR [--png FILE]\n\n"
                         "Pseudo-arclength continuation of periodic orbits (stable and unstable) with folds, period doublings\n"
                         "(the period-2k branch switched onto), Neimark-Sacker and grazing located to 1e-7 in the parameter.\n"
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
    analysis::ContinuationSpec spec;
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
        spec.omega = a.num("--omega", 10.0, 1e-2, 1000.0);
        if (!a.has("--min") || !a.has("--max")) throw UsageError("continue: --param " + param + " needs '--min' and '--max'");
        spec.lo = a.num("--min", 0.0, -0.1, 1.0);
        spec.hi = a.num("--max", 0.0, -0.1, 1.0);
        if (spec.hi <= spec.lo) throw UsageError("continue: --max is not above --min");
        spec.start = spec.lo;
    } else {
        throw UsageError("continue: option '--param': '" + param + "' is not one of omega, xI, m0e");
    }
    if (a.has("--from")) {
        spec.guess = parse_pair(a, "--from", "continue");
        check_start(p, spec.guess[0], "continue", "--from");
    }
    spec.period = a.integer("--period", 1, 1, 64);
    spec.max_period = a.integer("--max-period", 8, 1, 256);
    spec.sim = analysis_tol(a);
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
    const char* pname = analysis::cont_param_name(spec.param);
    br << "branch," << pname << ",x,v,period,stable\n";
    for (const auto& b : r.branches)
        for (const auto& q : b.points)
            br << b.id << ',' << q.param << ',' << q.y[0] << ',' << q.y[1] << ',' << q.period << ',' << (q.stable ? 1 : 0) << '\n';
    pt.precision(12);
    pt << "kind," << pname << ",x,v,period\n";
    for (const auto& q : r.points)
        pt << analysis::bif_kind_name(q.kind) << ',' << q.param << ',' << q.y[0] << ',' << q.y[1] << ',' << q.period << '\n';
    if (!br || !pt) throw std::runtime_error(dir + ": write failed");
    // No orbit at all: say so, and print no branch listing that looks like a result.
    if (r.branches.size() == 1 && r.branches[0].points.empty()) {
        std::fprintf(stderr, "continue: no period-%d orbit to continue: %s\n", spec.period, r.branches[0].end.c_str());
        return 1;
    }
    std::fprintf(stderr, "%s: %zu branches, %zu bifurcation points, %llu map evaluations, %.2f s -> %s\n", p.name.c_str(),
                 r.branches.size(), r.points.size(), static_cast<unsigned long long>(r.map_evaluations), r.seconds, dir.c_str());
    for (const auto& b : r.branches)
        std::printf("branch %d: period %d, %zu points%s, ends: %s\n", b.id, b.period, b.points.size(),
                    b.parent >= 0 ? (" (from branch " + std::to_string(b.parent) + ")").c_str() : "", b.end.c_str());
    for (const auto& q : r.points)
        std::printf("%-16s %s = %.9g (+- %.1g), period %d, x = %.6g m, v = %.6g m/s\n", analysis::bif_kind_name(q.kind), pname,
                    q.param, q.precision, q.period, q.y[0], q.y[1]);
    if (a.has("--png")) {
        plot::Figure fig;
        fig.width = 1200;
        fig.panel_height = 500;
        fig.title = p.name + ": continued periodic orbits (x at phi = 0)";
        plot::Panel pan;
        pan.xlabel = std::string(pname) + (spec.param == analysis::ContParam::Omega ? " [rad/s]" : "");
        pan.ylabel = "x [mm]";
        const plot::Color colors[] = {{31, 119, 180, 255}, {255, 127, 14, 255}, {44, 160, 44, 255}, {148, 103, 189, 255}};
        for (int per : {1, 2, 4, 8, 16, 32}) {
            plot::Series st{plot::Series::Kind::Line, {}, {}, colors[std::min(3, static_cast<int>(std::log2(per)))], 2.0f,
                            "period " + std::to_string(per) + " stable"};
            plot::Series un{plot::Series::Kind::Points, {}, {}, st.color, 0.8f, "period " + std::to_string(per) + " unstable"};
            for (const auto& b : r.branches) {
                if (b.period != per) continue;
                // Each of the k section points of an orbit is a point of the diagram, as in a sweep: one
                // curve per section point.
                for (std::size_t c = 0; c < static_cast<std::size_t>(per); ++c) {
                    for (const auto& q : b.points) {
                        if (c >= q.sections.size()) continue;
                        (q.stable ? st : un).x.push_back(q.param);
                        (q.stable ? st : un).y.push_back(1e3 * q.sections[c][0]);
                        (q.stable ? un : st).x.push_back(NAN);
                        (q.stable ? un : st).y.push_back(NAN);
                    }
                    st.x.push_back(NAN);
                    st.y.push_back(NAN);
                }
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
        plot::save_png(fig, a.str("--png", ""));
        std::fprintf(stderr, "plot -> %s\n", a.str("--png", "").c_str());
    }
    return 0;
}

int cmd_lyapunov(const std::vector<std::string>& argv) {
    if (wants_help(argv, "usage: impactlab lyapunov --model A1C --omega 16 [--periods N]\n"
                         "       impactlab lyapunov --model A1C --sweep up --out lyap.csv [--png lyap.png]\n\n"
                         "Largest Lyapunov exponent of the hybrid flow (Benettin: tangent with saltation at impacts,\n"
                         "re-orthonormalised once per forcing period). Prints lambda_max in 1/s; with --sweep, writes\n"
                         "omega,lambda_max along the CF sweep (omega_j = 25 j/300, each from the previous state).\n"
                         "  --omega W        forcing frequency [rad/s] (one value)\n"
                         "  --periods N      periods averaged (default 500; with --sweep: --record, default 70)\n"
                         "  --transient N    periods discarded first (default 100; with --sweep 20)\n"
                         "  --x0 X, --v0 V   initial state (default: the left well's bottom, at rest)\n"
                         "  --check          also the two-trajectory estimate\n"
                         "  --sweep up|down  the CF sweep; --omega-min, --omega-max, --steps, --record as bifurcation's\n"
                         "  --out FILE       CSV output omega,lambda_max,lambda_min,period (with --sweep)\n"
                         "  --png FILE       plot lambda_max over omega (with --sweep)\n"))
        return 0;
    const Args a("lyapunov", argv,
                 with_model_flags({"--omega", "--periods", "--transient", "--x0", "--v0", "--sweep", "--out", "--png",
                                   "--omega-min", "--omega-max", "--steps", "--record"}),
                 {"--check"});
    const Params p = model_from(a, "A1C");
    const Tolerances tol = tolerances_from(a);
    if (a.has("--sweep")) {
        const std::string sw = a.str("--sweep", "up");
        if (sw != "up" && sw != "down") throw UsageError("lyapunov: option '--sweep': '" + sw + "' is not one of up, down");
        for (const char* f : {"--omega", "--periods", "--x0", "--v0", "--check"})
            if (a.has(f)) throw UsageError(std::string("lyapunov: ") + f + " is for one omega, not with --sweep");
        CfSpec spec;
        spec.steps = a.integer("--steps", spec.steps, 1, 100000);
        spec.omega_min = a.num("--omega-min", 25.0 / spec.steps, 1e-3, 1000.0);
        spec.omega_max = a.num("--omega-max", spec.omega_max, 1e-3, 1000.0);
        if (spec.omega_max < spec.omega_min) throw UsageError("lyapunov: --omega-max is below --omega-min");
        spec.transient = a.integer("--transient", spec.transient, 0, 1000000);
        spec.record = a.integer("--record", spec.record, 1, 1000000);
        spec.direction = sw == "up" ? SweepDirection::Up : SweepDirection::Down;
        const std::string out_path = a.required("--out");
        auto out = open_out(out_path);
        Progress progress;
        std::vector<analysis::LyapunovPoint> pts;
        {
            ProgressBar bar("lyapunov " + p.name, progress);
            pts = analysis::lyapunov_sweep(p, spec, &progress, tol);
        }
        out << "omega,lambda_max,lambda_min,period\n";
        for (const auto& q : pts) out << q.omega << ',' << q.lambda_max << ',' << q.lambda_min << ',' << q.period << '\n';
        if (!out) throw std::runtime_error(out_path + ": write failed");
        std::fprintf(stderr, "%s: %zu omegas -> %s\n", p.name.c_str(), pts.size(), out_path.c_str());
        if (a.has("--png")) {
            plot::Figure fig;
            fig.width = 1200;
            fig.panel_height = 350;
            fig.title = p.name + ": largest Lyapunov exponent along the CF sweep";
            plot::Panel pan;
            pan.xlabel = "omega [rad/s]";
            pan.ylabel = "lambda_max [1/s]";
            plot::Series s{plot::Series::Kind::Line, {}, {}, {31, 119, 180, 255}, 1.5f, ""};
            plot::Series zero{plot::Series::Kind::Line, {spec.omega_min, spec.omega_max}, {0.0, 0.0}, {120, 120, 120, 255}, 1.0f, ""};
            for (const auto& q : pts) {
                s.x.push_back(q.omega);
                s.y.push_back(std::max(q.lambda_max, -5.0));   // a resting cart's -inf-like values clipped
            }
            pan.series = {zero, s};
            fig.panels.push_back(pan);
            plot::save_png(fig, a.str("--png", ""));
        }
        return 0;
    }
    if (!a.has("--omega")) throw UsageError("lyapunov: missing required option '--omega' (or '--sweep')");
    if (a.has("--out") || a.has("--png")) throw UsageError("lyapunov: '--out' and '--png' go with '--sweep'");
    for (const char* f : {"--omega-min", "--omega-max", "--steps", "--record"})
        if (a.has(f)) throw UsageError(std::string("lyapunov: ") + f + " goes with '--sweep'");
    const double omega = a.num("--omega", 0, 1e-2, 1000.0);
    const int periods = a.integer("--periods", 500, 1, 100000000);
    const int transient = a.integer("--transient", 100, 0, 100000000);
    State s;
    s.x = a.num("--x0", analysis::left_well(p), -0.1, 0.1);
    check_start(p, s.x, "lyapunov", "--x0");
    s.v = a.num("--v0", 0.0, -10.0, 10.0);
    const State s0 = s;
    Progress progress;
    analysis::LyapunovResult r;
    {
        ProgressBar bar("lyapunov " + p.name, progress);
        r = analysis::lyapunov(p, omega, s, transient, periods, tol, &progress);
    }
    std::printf("lambda_max = %.6g 1/s\n", r.lambda_max);
    std::printf("lambda_min = %.6g 1/s (averaged over %.6g s)\n", r.lambda_min, r.seconds);
    if (a.has("--check")) {
        const Tolerances tight = analysis::analysis_tolerances(1e-11);
        State sb = s0;
        const analysis::LyapunovResult rb = analysis::lyapunov(p, omega, sb, transient, periods, tight);
        const double two = analysis::lyapunov_two_trajectory(p, omega, s0, transient, periods, tight, 1e-6);
        std::printf("check at rtol 1e-11: Benettin %.6g 1/s, two trajectories %.6g 1/s\n", rb.lambda_max, two);
    }
    return 0;
}

int cmd_basins(const std::vector<std::string>& argv) {
    if (wants_help(argv, "usage: impactlab basins --model A1G --omega 13 --grid 200 --out basins.csv [--png basins.png]\n\n"
                         "Basins of attraction at constant omega: a grid of starts (x0, v0) at phi = 0 (cell centres), each\n"
                         "simulated until its Poincare section points recur (period k) or its budget ends (chaos), and\n"
                         "labelled by its attractor (the same orbit from different cells gets the same label). Writes\n"
                         "x0,v0,label rows; prints the legend: label, kind (period k, chaos, resting at the bumper), well,\n"
                         "a section point of the attractor, the cells reaching it.\n"
                         "  --omega W        forcing frequency [rad/s] (required)\n"
                         "  --grid N         N x N starts (default 200)\n"
                         "  --x-range A:B    x0 range [m] (default -0.03:xI, or -0.03:0.03 without a bumper)\n"
                         "  --v-range A:B    v0 range [m/s] (default -0.3:0.3)\n"
                         "  --transient N    periods a cell may take to settle (default 60)\n"
                         "  --periods N      further periods before a cell counts as chaotic; its last N section points\n"
                         "                   are its attractor (default 40)\n"
                         "  --max-period K   the longest period recognised (default 16)\n"
                         "  --threads N      worker threads (default: all cores); the labels do not depend on it\n"
                         "  (--rtol: the integrator's tolerance, default 1e-6 here: the attractor, not its digits)\n"
                         "  --out FILE       CSV output x0,v0,label (required)\n"
                         "  --png FILE       the coloured basin map with the attractors' section points and a legend\n"))
        return 0;
    const Args a("basins", argv,
                 with_model_flags({"--omega", "--grid", "--x-range", "--v-range", "--transient", "--periods", "--max-period",
                                   "--threads", "--out", "--png"}));
    const Params p = model_from(a, "A1G");
    if (!a.has("--omega")) throw UsageError("basins: missing required option '--omega'");
    analysis::BasinSpec spec;
    spec.omega = a.num("--omega", 0, 1e-2, 1000.0);
    spec.nx = spec.nv = a.integer("--grid", 200, 1, 4000);
    const double x_hi = p.has_bumper() ? std::min(p.xI, 0.03) : 0.03;
    std::tie(spec.x_min, spec.x_max) = parse_range(a, "--x-range", "basins", -1.0, 1.0, {std::min(-0.03, x_hi - 0.03), x_hi});
    std::tie(spec.v_min, spec.v_max) = parse_range(a, "--v-range", "basins", -100.0, 100.0, {-0.3, 0.3});
    check_start(p, spec.x_max, "basins", "--x-range (its upper end)");
    spec.transient = a.integer("--transient", spec.transient, 0, 1000000);
    spec.periods = a.integer("--periods", spec.periods, 1, 1000000);
    spec.max_period = a.integer("--max-period", spec.max_period, 1, 256);
    spec.threads = a.integer("--threads", 0, 0, 1024);
    if (a.has("--rtol")) spec.sim = tolerances_from(a);
    const std::string out_path = a.required("--out");
    const std::string png = a.str("--png", "");
    if (a.has("--png")) check_writable(png, "--png");
    auto out = open_out(out_path);
    Progress progress;
    analysis::BasinResult r;
    {
        ProgressBar bar("basins " + p.name, progress);
        r = analysis::compute_basins(p, spec, &progress);
    }
    out << "x0,v0,label\n";
    for (int j = 0; j < spec.nv; ++j)
        for (int i = 0; i < spec.nx; ++i)
            out << r.x0(i) << ',' << r.v0(j) << ',' << r.label[static_cast<std::size_t>(j) * spec.nx + i] << '\n';
    if (!out) throw std::runtime_error(out_path + ": write failed");
    const std::size_t ncells = r.label.size();
    std::fprintf(stderr, "%s omega = %g rad/s: %d x %d starts, %zu attractors, %.3g periods per start, %.2f s on %d threads -> %s\n",
                 p.name.c_str(), spec.omega, spec.nx, spec.nv, r.attractors.size(),
                 static_cast<double>(r.periods_run) / static_cast<double>(ncells), r.seconds, r.threads, out_path.c_str());
    // The legend: one line per label.
    auto describe = [](const analysis::Attractor& at) {
        std::string kind = at.kind == analysis::AttractorKind::Periodic ? "period " + std::to_string(at.period)
                           : at.kind == analysis::AttractorKind::Resting ? "resting at the bumper"
                                                                         : std::string(analysis::attractor_kind_name(at.kind));
        const char* well = at.well < 0 ? "left well" : at.well > 0 ? "right well" : "at x = 0";
        return kind + ", " + well;
    };
    std::printf("label,kind,period,well,x,v,cells,fraction\n");
    for (const auto& at : r.attractors)
        std::printf("%d,%s,%d,%s,%.6g,%.6g,%zu,%.4f\n", at.id, analysis::attractor_kind_name(at.kind), at.period,
                    at.well < 0 ? "left" : at.well > 0 ? "right" : "hilltop", at.representative[0], at.representative[1],
                    at.cells, static_cast<double>(at.cells) / static_cast<double>(ncells));
    if (r.cancelled) {
        std::fprintf(stderr, "basins: cancelled\n");
        return 1;
    }
    if (a.has("--png")) {
        plot::Figure fig;
        fig.width = 1000;
        fig.panel_height = 800;
        char omega_txt[32];
        std::snprintf(omega_txt, sizeof omega_txt, "%g", spec.omega);
        fig.title = p.name + ": basins of attraction at omega = " + omega_txt + " rad/s (starts at phi = 0)";
        plot::Panel pan;
        pan.xlabel = "x0 [m]";
        pan.ylabel = "v0 [m/s]";
        pan.xmin = spec.x_min;
        pan.xmax = spec.x_max;
        pan.ymin = spec.v_min;
        pan.ymax = spec.v_max;
        pan.grid = false;
        const plot::Color palette[] = {{31, 119, 180, 255}, {255, 127, 14, 255}, {44, 160, 44, 255}, {214, 39, 40, 255},
                                       {148, 103, 189, 255}, {140, 86, 75, 255}, {227, 119, 194, 255}, {188, 189, 34, 255},
                                       {23, 190, 207, 255}, {127, 127, 127, 255}};
        std::vector<plot::Series> fills(r.attractors.size());
        for (std::size_t k = 0; k < r.attractors.size(); ++k) {
            const auto& at = r.attractors[k];
            fills[k].kind = plot::Series::Kind::Points;
            fills[k].color = palette[k % std::size(palette)];
            if (at.kind == analysis::AttractorKind::Chaos) fills[k].color = {190, 190, 190, 255};
            char rep[96];
            std::snprintf(rep, sizeof rep, " (%.2f mm, %.3f m/s)", at.representative[0] * 1e3, at.representative[1]);
            fills[k].label = std::to_string(at.id) + ": " + describe(at) + rep;
        }
        for (int j = 0; j < spec.nv; ++j)
            for (int i = 0; i < spec.nx; ++i) {
                const int id = r.label[static_cast<std::size_t>(j) * spec.nx + i];
                if (id < 0) continue;
                fills[static_cast<std::size_t>(id)].x.push_back(r.x0(i));
                fills[static_cast<std::size_t>(id)].y.push_back(r.v0(j));
            }
        plot::Series att{plot::Series::Kind::Points, {}, {}, {0, 0, 0, 255}, 2.5f, "section points of the attractors"};
        for (const auto& at : r.attractors)
            for (const auto& q : at.points) {
                att.x.push_back(q[0]);
                att.y.push_back(q[1]);
            }
        pan.series = fills;
        pan.series.push_back(att);
        fig.panels.push_back(pan);
        // Each cell painted as sub x sub dots, each just covering its sub-rectangle (corner to corner): the
        // overlap into a neighbour stays below a pixel, so the basin boundaries are the grid's.
        const plot::Mapping m = plot::layout(fig)[0];
        const double cw = static_cast<double>(m.right - m.left) / spec.nx, ch = static_cast<double>(m.bottom - m.top) / spec.nv;
        const int sub = std::max(1, static_cast<int>(std::ceil(std::max(cw, ch) / 1.5)));
        const double dx = (spec.x_max - spec.x_min) / spec.nx, dv = (spec.v_max - spec.v_min) / spec.nv;
        for (std::size_t k = 0; k < fills.size(); ++k) {
            plot::Series& f = fig.panels[0].series[k];
            f.size = static_cast<float>(0.5 * std::hypot(cw, ch) / sub + 0.25);
            std::vector<double> fx, fy;
            fx.reserve(f.x.size() * static_cast<std::size_t>(sub * sub));
            fy.reserve(fx.capacity());
            for (std::size_t c = 0; c < f.x.size(); ++c)
                for (int sa = 0; sa < sub; ++sa)
                    for (int sb = 0; sb < sub; ++sb) {
                        fx.push_back(f.x[c] + ((sa + 0.5) / sub - 0.5) * dx);
                        fy.push_back(f.y[c] + ((sb + 0.5) / sub - 0.5) * dv);
                    }
            f.x = std::move(fx);
            f.y = std::move(fy);
        }
        plot::save_png(fig, png);
        std::fprintf(stderr, "plot -> %s\n", png.c_str());
    }
    return 0;
}

}  // namespace impactlab::cli
