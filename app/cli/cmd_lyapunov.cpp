// impactlab lyapunov: Lyapunov exponents at one omega or along a CF sweep.
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
                         "  --check          also the two-trajectory estimate, both with their scatter over 10 blocks of\n"
                         "                   periods, and whether they agree within it (or what their difference follows)\n"
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
        out.check();
        std::fprintf(stderr, "%s: %zu omegas -> %s\n", printable(p.name).c_str(), pts.size(), printable(out_path).c_str());
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
    check_start(p, s.x, "lyapunov", "--x0", !a.has("--x0"));
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
        const analysis::LyapunovCheck c =
            analysis::lyapunov_check(p, omega, s0, transient, periods, analysis::analysis_tolerances(1e-11), 1e-6, 10);
        std::printf("check at rtol 1e-11: Benettin %.6g +- %.2g 1/s, two trajectories (d0 = %g) %.6g +- %.2g 1/s "
                    "(d0 / 10: %.6g 1/s)\n",
                    c.benettin, c.benettin_se, c.d0, c.two, c.two_se, c.two_small);
        std::printf("check: %s\n", c.why.c_str());
    }
    return 0;
}

}  // namespace impactlab::cli
