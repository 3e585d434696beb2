// impactlab orbit: a period-k orbit by Newton on the k-th Poincare map, with its Floquet multipliers.
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
#include "impactlab/plot.hpp"
#include "impactlab/simulator.hpp"

namespace impactlab::cli {

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
    const double omega = a.num("--omega", 0, 0.05, 1000.0);   // as continue: below, a period outlasts any budget
    const int k = a.integer("--period", 1, 1, 64);
    const double dt = a.num("--dt", 1e-3, 1e-7, 1.0);
    check_rows("orbit", kTwoPi * k / omega / dt, "--period x 2 pi / --omega / --dt");
    const std::string out_path = a.required("--out");
    auto out = open_out(out_path);
    const Tolerances tol = analysis_tol(a);
    analysis::OrbitOptions opt;
    opt.period = k;
    opt.sim = tol;
    Vec2 guess = a.has("--from") ? to_vec2(a.pair("--from"))
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
    out.check();
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

}  // namespace impactlab::cli
