// Shared by the peer benchmarks (bench_cvode, bench_odeint): the Model filled from impactlab's Params, the CF grid,
// the command line, and the comparison with impactlab's own diagram run in the same process.
//
// impactlab::core is used only for the parameter values (make_version), the CF grid (CfSpec) and for running
// impactlab's run_cf_sweep on the same diagram. The force laws, the Jacobian and the event logic are the peers'
// own (peer_model.hpp).
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "impactlab/params.hpp"
#include "impactlab/sweep.hpp"
#include "peer_model.hpp"

namespace peer {

inline Model make_model(const impactlab::Params& p) {
    if (!p.effects.empty()) throw std::runtime_error("the peer benchmarks model the base equation only (no effects)");
    Model M;
    M.m = p.m;
    M.m0e = p.m0e;
    M.k = p.k;
    M.c = p.c;
    M.T = p.T;
    M.eps = p.eps;
    M.xI = p.xI;
    for (std::size_t i = 0; i < 4; ++i) {
        M.a[i] = p.a[i];
        M.b[i] = p.b[i];
    }
    M.rigid = p.rigid();
    for (std::size_t i = 0; i < 8; ++i) M.ip[i] = p.ip[i];
    M.eps_v = p.impact->eps_v;
    return M;
}

// The omegas of run_cf_sweep for this spec, in sweep order.
inline CfGrid cf_grid(const impactlab::CfSpec& spec) {
    CfGrid g;
    g.transient = spec.transient;
    g.record = spec.record;
    g.omegas.resize(static_cast<std::size_t>(spec.steps));
    for (int j = 0; j < spec.steps; ++j)
        g.omegas[static_cast<std::size_t>(j)] =
            spec.steps == 1 ? spec.omega_min : spec.omega_min + (spec.omega_max - spec.omega_min) * j / (spec.steps - 1);
    if (spec.direction == impactlab::SweepDirection::Down) std::reverse(g.omegas.begin(), g.omegas.end());
    return g;
}

// ---------------------------------------------------------------------------------------------------------------
// Comparison with impactlab. Settled period-1 orbits: omega above the creep threshold sqrt(T / m0e) (6.98 rad/s
// for A1: below it the unbalance cannot overcome the dry friction, the cart creeps at 1e-10 to 1e-7 m/s and its
// section points drift slowly from level to level, so they are transients, not orbits) and the 70 recorded x
// within period_tol = 1 um of each other in both diagrams. Reported: the largest |dx| between their section
// points there. The same where only b (impactlab, the reference) has settled and omega > 1.1 x the threshold
// (just above it the cart is still settling from its creep): this one counts the peer's own jitter of its
// section points. Printed apart: where the cart leaves the hilltop for the well (the first omega with a recorded
// |x| > 1 mm), which depends on the creep and differs by a centimetre between two diagrams that get it
// differently, and the omegas where both are period 1 but on different orbits (|dx| > 1 mm).
struct Comparison {
    int settled = 0;            // omegas where both have settled on the same period-1 orbit
    double max_dx = 0, omega_at_max = 0;
    int settled_b = 0;          // omegas > 1.1 omega_creep where b has settled on a period-1 orbit
    double max_dx_b = 0, omega_at_max_b = 0;
    std::vector<double> other_branch;   // period 1 on different orbits (|dx| > branch_tol): listed, not in max_dx
    double leaves_a = 0, leaves_b = 0;  // first omega with a recorded |x| > 1 mm (0: never)
    double omega_creep = 0;
};

template <class PA, class PB>
Comparison compare(const std::vector<PA>& a, const std::vector<PB>& b, int record, double omega_creep,
                   double period_tol = 1e-6, double branch_tol = 1e-3) {
    Comparison c;
    c.omega_creep = omega_creep;
    const std::size_t r = static_cast<std::size_t>(record);
    const std::size_t n = std::min(a.size(), b.size()) / r;
    auto spread = [&](const auto& d, std::size_t j) {
        double lo = 1e300, hi = -1e300;
        for (std::size_t k = 0; k < r; ++k) {
            lo = std::min(lo, d[j * r + k].x);
            hi = std::max(hi, d[j * r + k].x);
        }
        return hi - lo;
    };
    for (std::size_t j = 0; j < n; ++j) {
        const std::size_t j0 = j * r;
        if (std::abs(a[j0].omega - b[j0].omega) > 1e-12) throw std::runtime_error("compare: omega grids differ");
        for (std::size_t k = 0; k < r; ++k) {
            if (c.leaves_a == 0 && std::abs(a[j0 + k].x) > 1e-3) c.leaves_a = a[j0].omega;
            if (c.leaves_b == 0 && std::abs(b[j0 + k].x) > 1e-3) c.leaves_b = b[j0].omega;
        }
        if (a[j0].omega <= omega_creep || spread(b, j) > period_tol) continue;
        double dx = 0;
        for (std::size_t k = 0; k < r; ++k) dx = std::max(dx, std::abs(a[j0 + k].x - b[j0 + k].x));
        if (a[j0].omega > 1.1 * omega_creep && dx <= branch_tol) {
            ++c.settled_b;
            if (dx > c.max_dx_b) {
                c.max_dx_b = dx;
                c.omega_at_max_b = a[j0].omega;
            }
        }
        if (spread(a, j) > period_tol) continue;
        if (dx > branch_tol) {
            c.other_branch.push_back(a[j0].omega);
            continue;
        }
        ++c.settled;
        if (dx > c.max_dx) {
            c.max_dx = dx;
            c.omega_at_max = a[j0].omega;
        }
    }
    return c;
}

inline void print_comparison(const char* what, const char* b_name, const Comparison& c) {
    std::printf("  %-24s both settled (period 1) at %3d omegas: max |dx| %.2e m (omega %.4g)\n", what, c.settled,
                c.max_dx, c.omega_at_max);
    std::printf("  %-24s %s settled, omega > %.3g: %3d omegas: max |dx| %.2e m (omega %.4g)\n", "", b_name,
                1.1 * c.omega_creep, c.settled_b, c.max_dx_b, c.omega_at_max_b);
    std::printf("  %-24s leaves the hilltop (|x| > 1 mm) at omega %.4g vs %.4g\n", "", c.leaves_a, c.leaves_b);
    if (!c.other_branch.empty()) {
        std::printf("  %-24s period 1 on different orbits (|dx| > 1 mm) at %zu omegas:", "", c.other_branch.size());
        for (std::size_t i = 0; i < c.other_branch.size() && i < 12; ++i) std::printf(" %.4g", c.other_branch[i]);
        std::printf("%s\n", c.other_branch.size() > 12 ? " ..." : "");
    }
}

template <class P>
void write_csv(const std::string& path, const std::vector<P>& pts) {
    std::ofstream f(path);
    if (!f) throw std::runtime_error("cannot write " + path);
    f.precision(12);
    f << "omega,x,v\n";
    for (const auto& p : pts) f << p.omega << ',' << p.x << ',' << p.v << '\n';
}

// ---------------------------------------------------------------------------------------------------------------
// Command line shared by the peers.
struct Options {
    double rtol = 0;            // the peer's default unless rtol_given
    bool rtol_given = false;
    double v_scale = Accuracy{}.scale_v;   // atol of v = rtol x v_scale
    double h_max = Accuracy{}.h_max;       // largest step [s], 0: none
    double il_rtol = 0;         // 0: impactlab's default Tolerances
    bool quick = false;         // 60 omegas instead of 300
    bool ref = false;           // also run impactlab at rtol 1e-10 and compare both with it
    bool verbose = false;       // the peer prints one line per omega on stderr
    bool peer_only = false;     // skip impactlab (no ratio, no comparison)
    bool extra = false;         // the peer's own switch (parse_options' extra_flag)
    std::vector<std::string> versions{"A1C", "A1H"};
    std::string csv_dir;        // write the diagrams there
};

inline Options parse_options(int argc, char** argv, const char* name, double default_rtol,
                             const char* extra_flag = nullptr, const char* extra_help = nullptr) {
    Options o;
    auto usage = [&](int rc) {
        std::printf(
            "usage: %s [--rtol R] [--v-scale S] [--h-max H] [--quick] [--only VERSION] [--ref] [--il-rtol R] [--csv DIR] [--peer-only] [--verbose]\n"
            "  --rtol R      the peer's relative tolerance (default %g)\n"
            "  --v-scale S   absolute tolerance of v = rtol x S (default %g m/s; that of x is rtol x %g m)\n"
            "  --h-max H     largest step in seconds, 0 for none (default %g s, as impactlab)\n"
            "  --quick       60 omegas instead of 300\n"
            "  --only V      one version (default: A1C and A1H)\n"
            "  --ref         also compute impactlab's diagram at rtol 1e-10 and compare both with it\n"
            "  --il-rtol R   rtol of the impactlab run used for the time ratio (default: impactlab's default)\n"
            "  --csv DIR     write the diagrams as DIR/<peer>_<V>.csv and DIR/impactlab_<V>.csv\n"
            "  --peer-only   run the peer alone (no impactlab run, no ratio, no comparison)\n"
            "  --verbose     the peer prints one line per omega on stderr\n",
            name, default_rtol, Accuracy{}.scale_v, Accuracy{}.scale_x, Accuracy{}.h_max);
        if (extra_flag) std::printf("  %s\n", extra_help);
        std::exit(rc);
    };
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) usage(2);
            return argv[++i];
        };
        if (a == "--rtol") {
            o.rtol = std::stod(value());
            o.rtol_given = true;
        }
        else if (a == "--v-scale") o.v_scale = std::stod(value());
        else if (a == "--h-max") o.h_max = std::stod(value());
        else if (a == "--il-rtol") o.il_rtol = std::stod(value());
        else if (a == "--quick") o.quick = true;
        else if (a == "--ref") o.ref = true;
        else if (a == "--verbose") o.verbose = true;
        else if (a == "--peer-only") o.peer_only = true;
        else if (a == "--only") o.versions = {value()};
        else if (a == "--csv") o.csv_dir = value();
        else if (extra_flag && a == extra_flag) o.extra = true;
        else if (a == "-h" || a == "--help") usage(0);
        else {
            std::fprintf(stderr, "%s: unknown option '%s'\n", name, a.c_str());
            usage(2);
        }
    }
    if (!o.rtol_given) o.rtol = default_rtol;
    if (!(o.rtol > 0) || o.il_rtol < 0 || !(o.v_scale > 0) || !(o.h_max >= 0)) {
        std::fprintf(stderr, "%s: tolerances must be positive\n", name);
        std::exit(2);
    }
    return o;
}

inline impactlab::CfSpec cf_spec(const Options& o) {
    impactlab::CfSpec spec;
    if (o.quick) spec.steps = 60;
    return spec;
}

// Wall and process CPU seconds of one run (the machine may be shared: CPU time is the steadier number).
struct Stopwatch {
    std::chrono::steady_clock::time_point w0 = std::chrono::steady_clock::now();
    std::clock_t c0 = std::clock();
    double wall() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count(); }
    double cpu() const { return double(std::clock() - c0) / CLOCKS_PER_SEC; }
};

// The peer's main loop: for each version, the peer's diagram, impactlab's on the same grid, times and accuracy.
// run_peer(Model&, const CfGrid&, const Accuracy&) -> PeerDiagram
template <class RunPeer>
int peer_main(const Options& o, const char* name, const char* method, RunPeer&& run_peer) {
    const impactlab::CfSpec spec = cf_spec(o);
    impactlab::Tolerances il_tol;
    if (o.il_rtol > 0) il_tol.rtol = o.il_rtol;
    std::printf("%s: %s\n", name, method);
    Accuracy acc;
    acc.rtol = o.rtol;
    acc.scale_v = o.v_scale;
    acc.h_max = o.h_max;
    std::printf("CF diagram: %d omegas in [%.4g, %.4g] x (%d + %d) periods; %s rtol %g, atol rtol x (%g m, %g m/s), "
                "h_max %g s; impactlab rtol %g; single thread\n\n",
                spec.steps, spec.omega_min, spec.omega_max, spec.transient, spec.record, name, acc.rtol, acc.scale_x,
                acc.scale_v, acc.h_max, il_tol.rtol);
    auto line = [](const char* who, double wall, double cpu, std::uint64_t steps, double sim, std::uint64_t impacts) {
        std::printf("  %-10s wall %8.3f s  cpu %8.3f s  steps %10llu  sim %8.1f s  impacts %6llu  %6.1f ns/step\n", who,
                    wall, cpu, static_cast<unsigned long long>(steps), sim, static_cast<unsigned long long>(impacts),
                    1e9 * cpu / std::max(1.0, double(steps)));
    };
    for (const std::string& vname : o.versions) {
        const impactlab::Params p = impactlab::make_version(vname);
        std::printf("%s\n", vname.c_str());
        std::fflush(stdout);

        Model M = make_model(p);
        CfGrid grid = cf_grid(spec);
        grid.verbose = o.verbose;
        Stopwatch sw;
        const PeerDiagram pd = run_peer(M, grid, acc);
        const double t_peer = sw.wall(), c_peer = sw.cpu();
        line(name, t_peer, c_peer, pd.steps, pd.simulated_seconds, pd.impacts);
        if (!o.csv_dir.empty()) write_csv(o.csv_dir + "/" + name + "_" + vname + ".csv", pd.points);
        if (o.peer_only) {
            std::printf("\n");
            continue;
        }

        sw = Stopwatch();
        const impactlab::Diagram il = impactlab::run_cf_sweep(p, spec, nullptr, il_tol);
        const double t_il = sw.wall(), c_il = sw.cpu();
        line("impactlab", t_il, c_il, il.steps, il.simulated_seconds, il.impacts);
        std::printf("  ratio %s / impactlab: wall %.2f, cpu %.2f, steps %.2f\n", name, t_peer / t_il, c_peer / c_il,
                    double(pd.steps) / std::max(1.0, double(il.steps)));
        const double w_creep = std::sqrt(p.T / p.m0e);
        print_comparison((std::string(name) + " vs impactlab:").c_str(), "impactlab",
                         compare(pd.points, il.points, spec.record, w_creep));
        if (!o.csv_dir.empty()) write_csv(o.csv_dir + "/impactlab_" + vname + ".csv", il.points);
        if (o.ref) {
            impactlab::Tolerances rt;
            rt.rtol = 1e-10;
            sw = Stopwatch();
            const impactlab::Diagram ref = impactlab::run_cf_sweep(p, spec, nullptr, rt);
            std::printf("  reference: impactlab rtol 1e-10, wall %.3f s, cpu %.3f s, steps %llu\n", sw.wall(), sw.cpu(),
                        static_cast<unsigned long long>(ref.steps));
            print_comparison((std::string(name) + " vs ref:").c_str(), "ref",
                             compare(pd.points, ref.points, spec.record, w_creep));
            print_comparison("impactlab vs ref:", "ref", compare(il.points, ref.points, spec.record, w_creep));
            if (!o.csv_dir.empty()) write_csv(o.csv_dir + "/reference_" + vname + ".csv", ref.points);
        }
        std::printf("\n");
        std::fflush(stdout);
    }
    return 0;
}

}  // namespace peer
