// bench: impactlab's throughput on the paper's diagrams, single-threaded.
//   CF diagram (run_cf_sweep, default CfSpec: 300 omegas x (20 + 70) periods) of A1C, A1C1, A3C, A1G, A1H,
//   EF ramp (run_ef_ramp, 0 -> 25.1 rad/s in 2800 s) of A1C and A1H.
// For each: wall seconds, simulated seconds, simulated seconds per wall second, accepted steps, impacts.
//   --fit: the measured-data loop (identify::run_fit) on a 300 s record at 1 kHz of A1H with quadratic
//   damping and of A1C with a sensor offset, without plots (target: under 10 s each on 2 cores).
//   --scan: impactlab scan's thread pool on a 12 x 64 plane of A1C (omega 8..14 rad/s, xI -4..4 mm): points
//   per second on 1 thread and on every core, and the parallel efficiency (target >= 90 %).
//   --analysis: the analysis jobs a researcher waits on (targets on a 2-core machine): the largest Lyapunov
//   exponent along A1C's CF sweep, 150 omegas from 0.5 (<= 60 s); A1C1's 100-omega lambda strip of the
//   visualiser (< 60 s); 200 x 200 basins of A1G at 13 rad/s on 2 threads (<= 20 s); A1C's continuation over
//   5..25 rad/s (<= 5 s).
#include <cmath>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <string>
#include <thread>
#include <vector>

#include "impactlab/analysis.hpp"
#include "impactlab/identify.hpp"
#include "impactlab/params.hpp"
#include "impactlab/scan.hpp"
#include "impactlab/sweep.hpp"

namespace {

struct Options {
    bool quick = false;
    bool cf = true, ef = true, fit = false, scan = false, analysis = false;
    int identify = 0;   // records of the loop's randomized benchmark (0: not run)
    int record = 0;     // > 0: that record of the benchmark alone
    std::string report; // its fit's report folder
    unsigned seed = 1;
    std::vector<std::string> only;   // empty: the paper's versions
    impactlab::Tolerances tol;
};

[[noreturn]] void usage(int rc) {
    std::printf(
        "usage: bench [--quick] [--only VERSION]... [--rtol R] [--cf-only | --ef-only | --fit | --scan | --analysis]\n"
        "  --quick       CF with 60 omegas instead of 300, EF ramp 5x faster (560 s instead of 2800 s)\n"
        "  --only V      this version only (repeatable; any XY name, e.g. A1H, A3G)\n"
        "  --rtol R      relative tolerance of the integrator (default %g)\n"
        "  --cf-only     skip the EF ramps;  --ef-only  skip the CF diagrams\n"
        "  --fit         only the measured-data loop: 300 s records at 1 kHz and a 120 s input-forced one at 2 kHz\n"
        "  --scan        only impactlab scan's thread pool: points per second on 1 thread and on every core\n"
        "  --analysis    only the analysis jobs: Lyapunov sweep and strip, basins on 2 threads, continuation\n"
        "  --identify N  only the loop's randomized benchmark: N records of effects the library has no name for, and\n"
        "                a null family; the rates of false claims, better models and honest verdicts (--seed S, default 1);\n"
        "                --record K fits record K alone (its row, its injected laws) and --report DIR writes its report\n",
        impactlab::Tolerances{}.rtol);
    std::exit(rc);
}

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) usage(2);
            return argv[++i];
        };
        if (a == "--quick") o.quick = true;
        else if (a == "--only") o.only.push_back(value());
        else if (a == "--rtol") o.tol.rtol = std::stod(value());
        else if (a == "--cf-only") o.ef = false;
        else if (a == "--ef-only") o.cf = false;
        else if (a == "--fit") o.fit = true;
        else if (a == "--scan") o.scan = true;
        else if (a == "--analysis") o.analysis = true;
        else if (a == "--identify") o.identify = std::stoi(value());
        else if (a == "--seed") o.seed = static_cast<unsigned>(std::stoul(value()));
        else if (a == "--record") o.record = std::stoi(value());
        else if (a == "--report") o.report = value();
        else if (a == "-h" || a == "--help") usage(0);
        else {
            std::fprintf(stderr, "bench: unknown option '%s'\n", a.c_str());
            usage(2);
        }
    }
    if (!(o.tol.rtol > 0)) {
        std::fprintf(stderr, "bench: --rtol must be positive\n");
        std::exit(2);
    }
    return o;
}

// Wall and process CPU seconds of f() (the machine may be shared: CPU time is the steadier number).
struct Times { double wall, cpu; };
template <class F>
Times timed(F&& f) {
    const auto w0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    f();
    return {std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count(),
            double(std::clock() - c0) / CLOCKS_PER_SEC};
}


void header() {
    std::printf("%-6s %-6s %9s %9s %10s %10s %11s %8s %8s %7s\n", "model", "run", "wall[s]", "cpu[s]", "sim[s]",
                "sim/wall", "steps", "impacts", "ns/step", "points");
}

void row(const impactlab::Diagram& d, Times t) {
    std::printf("%-6s %-6s %9.3f %9.3f %10.1f %10.1f %11llu %8llu %8.1f %7zu\n", d.model.c_str(), d.protocol.c_str(),
                t.wall, t.cpu, d.simulated_seconds, d.simulated_seconds / t.wall,
                static_cast<unsigned long long>(d.steps), static_cast<unsigned long long>(d.impacts),
                1e9 * t.cpu / std::max(1.0, double(d.steps)), d.points.size());
    std::fflush(stdout);
}

}  // namespace

// The measured-data loop on a 300 s record at 1 kHz (synthesised, then fitted with the version's parameters).
void bench_fit() {
    namespace id = impactlab::identify;
    std::printf("fit: 300 s at 1 kHz, steps at 9, 13.5, 16 and 18 rad/s, no plots\n\n%-6s %-20s %9s %9s %s\n", "model", "injected",
                "wall[s]", "cpu[s]", "found");
    const std::pair<const char*, std::pair<const char*, double>> cases[] = {{"A1H", {"quadratic_damping", 4.0}},
                                                                            {"A1C", {"sensor_offset", 3e-4}}};
    for (const auto& [version, effect] : cases) {
        id::Model truth = id::resolve_fit_model(version, id::Forcing::Unbalance);
        id::apply_effect(truth, effect.first, {{"", effect.second}});
        id::SynthOptions so;
        so.duration = 300.0;
        id::steps_profile({9.0, 13.5, 16.0, 18.0}, 73.5, 2.0, so.knot_t, so.knot_omega);
        const id::MeasuredData d = id::synthesize(truth, so);
        id::FitOptions fo;
        fo.plots = false;
        id::FitReport r;
        const Times t = timed([&] { r = id::run_fit(d, id::resolve_fit_model(version, id::Forcing::Unbalance), fo); });
        std::printf("%-6s %-20s %9.3f %9.3f %s\n", version, effect.first, t.wall, t.cpu,
                    r.effects_found.empty() ? "none" : r.effects_found.front().id.c_str());
        std::fflush(stdout);
    }
    // An input-forced record at 2 kHz, the kind a shaker rig gives: 120 s of a hardening Duffing oscillator
    // driven at 6.5 Hz (with a 1.5 % second harmonic in the drive), with quadratic damping, fitted with
    // 'duffing' (the baseline fitted, then refined on the free-run error).
    {
        id::Model truth = id::resolve_fit_model("duffing", id::Forcing::Input);
        truth.p.k = 2527.0;    // 8 Hz
        truth.p.c = 1.0;
        truth.p.a[1] = 1.0e7;
        truth.p.input_gain = 1.0;
        id::apply_effect(truth, "quadratic_damping", {{"cq", 40.0}});
        id::SynthOptions so;
        so.duration = 120.0;
        so.rate = 2000.0;
        so.noise = 1e-7;
        so.quantum = 0.0;
        so.x0 = 0.0;
        so.input_dt = 1.0 / so.rate;
        for (std::size_t i = 0; i <= static_cast<std::size_t>(so.duration * so.rate); ++i) {
            const double tt = static_cast<double>(i) / so.rate, w = 2.0 * 3.141592653589793 * 6.5;
            so.input.push_back(1.3 * std::sin(w * tt) + 0.02 * std::sin(2.0 * w * tt + 0.3));
        }
        const id::MeasuredData d = id::synthesize(truth, so);
        id::FitOptions fo;
        fo.plots = false;
        fo.fit_baseline = true;
        id::FitReport r;
        const Times t = timed([&] { r = id::run_fit(d, id::resolve_fit_model("duffing", id::Forcing::Input), fo); });
        std::printf("%-6s %-20s %9.3f %9.3f %s   (120 s at 2 kHz, input-forced, baseline fitted)\n", "duffing", "quadratic_damping",
                    t.wall, t.cpu, r.effects_found.empty() ? "none" : r.effects_found.front().id.c_str());
        std::fflush(stdout);
    }
}

// impactlab scan's rows on a thread pool: the same plane on 1 thread and on every core.
void bench_scan() {
    using namespace impactlab;
    ScanSpec spec;
    spec.x = parse_scan_axis("omega:8:14:12");
    spec.y = parse_scan_axis("xI:-0.004:0.004:64");
    spec.measures = parse_scan_measures("period,impacts,xrange");
    const Params p = make_version("A1C");
    std::vector<int> todo(static_cast<std::size_t>(spec.y.n));
    for (int j = 0; j < spec.y.n; ++j) todo[static_cast<std::size_t>(j)] = j;
    const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    const double points = static_cast<double>(spec.x.n) * spec.y.n;
    std::printf("scan: A1C, omega 8..14 rad/s x xI -4..4 mm, %d x %d points, 20 + 70 periods each\n\n%8s %9s %9s %12s %10s\n",
                spec.x.n, spec.y.n, "threads", "wall[s]", "cpu[s]", "points/s", "efficiency");
    double one = 0;
    for (int threads : {1, cores}) {
        if (threads == 1 && one > 0) continue;
        const Times t = timed([&] { scan_rows(p, spec, todo, threads, nullptr, {}, [](int, const std::vector<ScanPoint>&) {}); });
        if (threads == 1) one = t.wall;
        std::printf("%8d %9.2f %9.2f %12.1f %9.0f%%\n", threads, t.wall, t.cpu, points / t.wall, 100.0 * one / (t.wall * threads));
        std::fflush(stdout);
        if (cores == 1) break;
    }
}

// The analysis jobs, each as the CLI or the visualiser runs it.
void bench_analysis() {
    using namespace impactlab;
    std::printf("analysis jobs (targets for a 2-core machine)\n\n%-58s %9s %9s %9s  %s\n", "job", "wall[s]", "cpu[s]",
                "target[s]", "result");
    auto line = [](const char* job, Times t, double target, const std::string& result) {
        std::printf("%-58s %9.2f %9.2f %9.0f  %s\n", job, t.wall, t.cpu, target, result.c_str());
        std::fflush(stdout);
    };
    char buf[160];
    {
        CfSpec spec;
        spec.omega_min = 0.5;
        spec.steps = 150;
        std::vector<analysis::LyapunovPoint> pts;
        const Times t = timed([&] { pts = analysis::lyapunov_sweep(make_version("A1C"), spec); });
        int positive = 0;
        for (const auto& q : pts) positive += q.lambda_max > 0.05;
        std::snprintf(buf, sizeof buf, "%zu omegas, %d with lambda_max > 0.05 1/s", pts.size(), positive);
        line("lyapunov A1C, CF up, 150 omegas 0.5..25, 20 + 70 periods", t, 60, buf);
    }
    {
        CfSpec spec;   // the visualiser's strip: omega_j = 25 j / 100, 20 + 40 periods
        spec.omega_min = 0.25;
        spec.steps = 100;
        spec.record = 40;
        std::vector<analysis::LyapunovPoint> pts;
        const Times t = timed([&] { pts = analysis::lyapunov_sweep(make_version("A1C1"), spec); });
        std::snprintf(buf, sizeof buf, "%zu omegas", pts.size());
        line("lambda strip A1C1, 100 omegas 0.25..25, 20 + 40 periods", t, 60, buf);
    }
    {
        analysis::BasinSpec spec;
        spec.omega = 13;
        spec.threads = 2;
        analysis::BasinResult r;
        const Times t = timed([&] { r = analysis::compute_basins(make_version("A1G"), spec); });
        std::snprintf(buf, sizeof buf, "%zu attractors, %.1f periods per start", r.attractors.size(),
                      static_cast<double>(r.periods_run) / (spec.nx * spec.nv));
        line("basins A1G, omega 13, 200 x 200, 2 threads", t, 20, buf);
    }
    {
        analysis::ContinuationSpec spec;
        spec.lo = 5;
        spec.hi = 25;
        analysis::ContinuationResult r;
        const Times t = timed([&] { r = analysis::continue_orbits(make_version("A1C"), spec); });
        std::snprintf(buf, sizeof buf, "%zu branches, %zu points, %llu maps", r.branches.size(), r.points.size(),
                      static_cast<unsigned long long>(r.map_evaluations));
        line("continue A1C, omega 5..25, periods up to 8", t, 5, buf);
    }
    {
        // Through the grazings (a rigid bumper): the impacting period-2 branch between 12.80 and 15.97.
        analysis::ContinuationSpec spec;
        spec.lo = 8;
        spec.hi = 25;
        spec.start = 9;
        analysis::ContinuationResult r;
        const Times t = timed([&] { r = analysis::continue_orbits(make_version("A1G"), spec); });
        int crossed = 0;
        for (const auto& q : r.points) crossed += !q.scenario.empty();
        std::snprintf(buf, sizeof buf, "%zu branches, %zu points (%d grazings crossed), %llu maps", r.branches.size(),
                      r.points.size(), crossed, static_cast<unsigned long long>(r.map_evaluations));
        line("continue A1G, omega 8..25 from 9, through grazings", t, 5, buf);
    }
    {
        Params p = make_version("A1G");
        p.xI = -0.004;
        analysis::BifCurve g, f;
        const Times tg = timed([&] {
            g = analysis::continue_grazing_curve(p, analysis::ContParam::XI, 9.60049627, Vec2(-0.0156163, -0.00744857), 1,
                                                 -0.008, -0.002, 1.25e-4);
        });
        std::snprintf(buf, sizeof buf, "%zu points", g.points.size());
        line("grazing curve A1G, xI -8..-2 mm (the plane's half step)", tg, 5, buf);
        const Times tf = timed([&] {
            f = analysis::continue_fold_curve(p, analysis::ContParam::XI, 9.548943, Vec2(-0.0157368, 0.00230387), 1, -0.008,
                                              -0.002, 1.25e-4);
        });
        std::snprintf(buf, sizeof buf, "%zu points", f.points.size());
        line("fold curve A1G, xI -8..-2 mm (the plane's half step)", tf, 5, buf);
    }
}

// The loop's randomized benchmark: each record's family, what the fit named, and the rates.
int bench_identify(int n, unsigned seed, int record, const std::string& report) {
    namespace id = impactlab::identify;
    id::IdentifyBenchOptions bo;
    bo.records = n;
    bo.seed = seed;
    bo.only = record;
    bo.report_dir = report;
    std::printf("identify: %d records of 30 s at 1 kHz, seed %u (versions A1H A1C A1G A3G; periodic, chaotic, steps; noise 1-10 um)\n\n",
                n, seed);
    std::printf("%4s %-22s %-5s %-9s %8s %10s %10s %5s %5s %5s %7s  %s\n", "#", "family", "model", "regime", "noise[um]", "before[um]",
                "after[um]", "false", "better", "honest", "wall[s]", "named");
    bo.progress = [record](int done, int, const id::IdentifyBenchRecord& r) {
        if (record > 0) done = record;
        std::string named;
        for (const auto& x : r.named) named += (named.empty() ? "" : " ") + x;
        if (!r.error.empty()) named = "ERROR: " + r.error;
        std::printf("%4d %-22s %-5s %-9s %8.2f %10.3g %10.3g %5s %5s %5s %7.2f  %s\n", done, r.family.c_str(), r.version.c_str(),
                    r.regime.c_str(), r.noise * 1e6, r.before * 1e6, r.after * 1e6, r.false_claim ? "yes" : "-",
                    r.null_family ? "n/a" : (r.better ? "yes" : "no"), r.honest ? "yes" : "no", r.runtime_s, named.c_str());
        if (record > 0) std::printf("     injected: %s\n", r.truth.c_str());
        std::fflush(stdout);
    };
    const Times t = timed([&] {
        const id::IdentifyBenchResult res = id::run_identify_bench(bo);
        std::printf("\n(a law marked ? stays in the model, but the data do not resolve its shape from another law's: no claim)\n");
        std::printf("false physical claims: %.1f %% of %zu records; null family: %zu claims in %zu records\n",
                    100.0 * res.false_claim_rate, res.rows.size() - res.errors, res.null_claims, res.null_records);
        std::printf("better (1-period shooting down 3x or to 1.5x the noise): %.1f %% of %zu records not at the noise before\n",
                    100.0 * res.better_rate, res.better_records);
        std::printf("honest verdicts: %.1f %%; fits that failed: %zu\n", 100.0 * res.honest_rate, res.errors);
    });
    std::printf("total wall %.1f s, cpu %.1f s\n", t.wall, t.cpu);
    return 0;
}

int main(int argc, char** argv) {
    const Options o = parse(argc, argv);
    if (o.identify > 0) return bench_identify(o.identify, o.seed, o.record, o.report);
    if (o.analysis) {
        bench_analysis();
        return 0;
    }
    if (o.scan) {
        bench_scan();
        return 0;
    }
    if (o.fit) {
        try {
            bench_fit();
        } catch (const std::exception& e) {
            std::fprintf(stderr, "bench: %s\n", e.what());
            return 1;
        }
        return 0;
    }
    try {
        const std::vector<std::string> cf_versions =
            o.only.empty() ? std::vector<std::string>{"A1C", "A1C1", "A3C", "A1G", "A1H"} : o.only;
        const std::vector<std::string> ef_versions = o.only.empty() ? std::vector<std::string>{"A1C", "A1H"} : o.only;
        impactlab::CfSpec cf;
        impactlab::EfSpec ef;
        if (o.quick) {
            cf.steps = 60;
            ef.t_ramp = 560.0;
        }
        std::printf("impactlab bench, single thread, rtol %g\n", o.tol.rtol);
        if (o.cf)
            std::printf("CF: %d omegas in [%.4g, %.4g] rad/s x (%d + %d) periods\n", cf.steps, cf.omega_min,
                        cf.omega_max, cf.transient, cf.record);
        if (o.ef) std::printf("EF: omega 0 -> %.4g rad/s in %.0f s\n", ef.omega_max, ef.t_ramp);
        std::printf("\n");
        header();
        Times total{0, 0};
        if (o.cf)
            for (const auto& name : cf_versions) {
                const impactlab::Params p = impactlab::make_version(name);
                impactlab::Diagram d;
                const Times t = timed([&] { d = impactlab::run_cf_sweep(p, cf, nullptr, o.tol); });
                total.wall += t.wall;
                total.cpu += t.cpu;
                row(d, t);
            }
        if (o.ef)
            for (const auto& name : ef_versions) {
                const impactlab::Params p = impactlab::make_version(name);
                impactlab::Diagram d;
                const Times t = timed([&] { d = impactlab::run_ef_ramp(p, ef, nullptr, o.tol); });
                total.wall += t.wall;
                total.cpu += t.cpu;
                row(d, t);
            }
        std::printf("\ntotal wall %.3f s, cpu %.3f s\n", total.wall, total.cpu);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
