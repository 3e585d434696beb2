// Commands over the simulator and the sweeps: models, simulate, poincare, bifurcation, figure3.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <tuple>

#include "commands.hpp"
#include "common.hpp"
#include "impactlab/input_file.hpp"
#include "impactlab/figures.hpp"
#include "impactlab/forces.hpp"
#include "impactlab/identify.hpp"
#include "impactlab/identify_data.hpp"
#include "impactlab/params_json.hpp"
#include "impactlab/simulator.hpp"
#include "impactlab/sweep.hpp"

namespace impactlab::cli {

int cmd_models(const std::vector<std::string>& argv) {
    if (show_help_if_asked(argv, "usage: impactlab models [--json NAME]\n\n"
                         "Lists every model version XY (stiffness X, impact Y) with its parameters (SI units).\n"
                         "  --json NAME   print the parameter file of version NAME (a starting point for --model FILE.json)\n"))
        return 0;
    const Args a("models", argv, {"--json"});
    if (a.has("--json")) {
        Params p;
        try {
            p = make_version(a.str("--json", ""));
        } catch (const ParamError& e) {
            throw UsageError(std::string("--json: ") + e.what());
        }
        std::printf("%s", params_to_json_text(p).c_str());
        return 0;
    }
    std::printf("Stiffness versions (Table 1), m = 6.73766 kg, eps = 1e-6 m/s:\n");
    std::printf("  %-4s %-9s %-8s %-7s %-7s %-10s %-11s %-9s %-10s\n", "id", "m0e", "k", "c", "T", "a1", "a3", "b2", "b4");
    for (const auto& s : stiffness_sets())
        std::printf("  %-4s %-9.6g %-8.6g %-7.5g %-7.5g %-10.6g %-11.5g %-9.6g %-10.5g\n", s.id, s.m0e, s.k, s.c, s.T,
                    s.a[0], s.a[1], s.b[0], s.b[1]);
    std::printf("\nImpact versions (Tables 2, 3):\n");
    for (const auto& m : impact_models()) {
        std::printf("  %-3s %s\n      ", m.id, m.summary);
        for (std::size_t i = 0; i < kMaxLawParams && m.names[i]; ++i)
            std::printf("%s = %g %s%s", m.names[i], m.defaults[i], m.units[i],
                        (i + 1 < kMaxLawParams && m.names[i + 1]) ? ", " : "\n");
    }
    std::printf("\nVersions (any XY; the paper's five first):\n  ");
    const auto names = version_names();
    for (std::size_t i = 0; i < names.size(); ++i) std::printf("%s%s", names[i].c_str(), i + 1 < names.size() ? " " : "\n");
    std::printf("\nExtra effects (for parameter files and impactlab fit):\n");
    for (const auto& e : effect_laws()) std::printf("  %-22s %s\n", e.id, e.meaning);
    std::printf("\nEffects that change the base model instead of adding a force (impactlab fit finds them, synth --effect sets them):\n");
    for (const auto& e : identify::effect_catalogue())
        if (e.changes_base) std::printf("  %-22s %s\n", e.id.c_str(), e.meaning.c_str());
    std::printf("\nValid ranges (a parameter file outside them is refused, naming the key):\n");
    for (const auto& r : param_ranges())
        std::printf("  %-16s [%g, %g] %s  (%s)\n", r.key, r.lo, r.hi, r.unit, r.why);
    std::printf("  every force law (a, b of F_SA, the bumper at penetrations up to 0.1 mm, each effect) stays within "
                "%g N on |x| <= 0.1 m, |v| <= 10 m/s, omega <= 1000 rad/s\n", kMaxLawForce);
    return 0;
}

int cmd_simulate(const std::vector<std::string>& argv) {
    if (show_help_if_asked(argv, "usage: impactlab simulate --model A1H --omega 18 --duration 60 --out traj.csv [options]\n\n"
                         "Integrates one run at constant omega from rest (or --x0/--v0) and writes\n"
                         "t,x,v,phi,regime (regime 1 = free flight, 2 = sticking, 3 = permanent contact).\n"
                         "  --omega W        forcing frequency [rad/s] (required)\n"
                         "  --duration D     simulated time [s] (required)\n"
                         "  --out FILE       CSV output (required)\n"
                         "  --dt DT          output sample step [s] (default 1e-3)\n"
                         "  --x0 X, --v0 V   initial state [m], [m/s] (default 0, 0)\n"
                         "  --input FILE     drive the model by input_gain * u(t), u from a record (re-timed from t = 0;\n"
                         "                   then --omega defaults to 0, --duration and --dt to the record's); map its\n"
                         "                   columns with --u-col C, --x-col C, --t-col C, --input-rate HZ, --u-scale S.\n"
                         "                   The model's input_gain (a fitted model_after.json has it) sets the force.\n", kModelHelp))
        return 0;
    std::set<std::string> flags = with_model_flags({"--omega", "--duration", "--out", "--dt", "--x0", "--v0"});
    flags.insert(kInputFlags.begin(), kInputFlags.end());
    const Args a("simulate", argv, flags);
    const Params p = model_from(a);
    const std::optional<identify::MeasuredData> rec = input_from(a, "simulate");
    const bool input = rec.has_value();
    double in_dt = 0;
    if (input) {
        in_dt = (rec->t.back() - rec->t.front()) / static_cast<double>(rec->size() - 1);
        if (p.input_gain == 0.0) std::fprintf(stderr, "simulate: note: the model's input_gain is 0, so the input does not act on it\n");
    }
    const double omega = a.num("--omega", 0, 0.0, 1000.0);
    if (!a.has("--omega") && !input) throw UsageError("simulate: missing required option '--omega'");
    if (!a.has("--duration") && !input) throw UsageError("simulate: missing required option '--duration'");
    const double duration = a.num("--duration", input ? in_dt * static_cast<double>(rec->size() - 1) : 0.0, 1e-6, 1e6);
    const double dt = a.num("--dt", input ? in_dt : 1e-3, 1e-7, 1e3);
    check_rows("simulate", duration / dt, "--duration / --dt");
    check_run_span(p, 0.0, duration, "simulate");
    auto out = open_out(a.required("--out"));
    Drive drive(omega);
    if (input) drive.set_input(0.0, in_dt, rec->u);
    State s;
    s.x = a.num("--x0", 0.0, -0.1, 0.1);
    s.v = a.num("--v0", 0.0, -10.0, 10.0);
    check_start(p, s.x, "simulate", "--x0", !a.has("--x0"));
    out << (input ? "t,x,v,u,regime\n" : "t,x,v,phi,regime\n");
    Progress progress;
    ProgressBar bar("simulate " + p.name, progress);
    simulate_sampled(p, drive, s, duration, dt, tolerances_from(a), &progress, [&](const Sample& smp) {
        out << smp.t << ',' << smp.x << ',' << smp.v << ',' << (input ? drive.input(smp.t) : smp.phi) << ',' << static_cast<int>(smp.regime)
            << '\n';
    });
    bar.finish();
    out.commit();
    std::fprintf(stderr, "%s: %.6g s simulated, %llu steps, %llu impacts -> %s\n", printable(p.name).c_str(), duration,
                 static_cast<unsigned long long>(s.steps), static_cast<unsigned long long>(s.impacts),
                 printable(a.required("--out")).c_str());
    return 0;
}

int cmd_poincare(const std::vector<std::string>& argv) {
    if (show_help_if_asked(argv, "usage: impactlab poincare --model A1H --omega 18 --periods 200 --out sec.csv [options]\n\n"
                         "Samples (x, v) once per revolution of the unbalance and writes n,x,v. The start (phi = 0 at t = 0) is\n"
                         "no row; row n is the (N + n)-th passage of phi through phi0 after it (N = --transient), at\n"
                         "phi = phi0 + 2 pi (N + n - 1) for phi0 > 0, and at phi = 2 pi (N + n) for phi0 = 0 (as 2 pi).\n"
                         "  --omega W        forcing frequency [rad/s] (required)\n"
                         "  --periods N      section points to record (required)\n"
                         "  --transient N    periods discarded first (default 0)\n"
                         "  --phi0 RAD       section phase, 0 <= RAD <= 2 pi (default 0; phi = 0 at the start)\n"
                         "  --out FILE       CSV output (required)\n"
                         "  --x0 X, --v0 V   initial state (default 0, 0)\n", kModelHelp))
        return 0;
    const Args a("poincare", argv,
                 with_model_flags({"--omega", "--periods", "--transient", "--phi0", "--out", "--x0", "--v0"}));
    const Params p = model_from(a);
    if (!a.has("--omega")) throw UsageError("poincare: missing required option '--omega'");
    if (!a.has("--periods")) throw UsageError("poincare: missing required option '--periods'");
    const double omega = a.num("--omega", 0, 1e-3, 1000.0);
    const int periods = a.integer("--periods", 0, 1, 10000000);
    const int transient = a.integer("--transient", 0, 0, 10000000);
    const double phi0 = a.num("--phi0", 0.0, 0.0, kTwoPi);
    auto out = open_out(a.required("--out"));
    State s;
    s.x = a.num("--x0", 0.0, -0.1, 0.1);
    s.v = a.num("--v0", 0.0, -10.0, 10.0);
    check_start(p, s.x, "poincare", "--x0", !a.has("--x0"));
    Progress progress;
    ProgressBar bar("poincare " + p.name, progress);
    const auto pts = poincare_section(p, omega, periods, transient, s, tolerances_from(a), &progress, phi0);
    bar.finish();
    out << "n,x,v\n";
    for (const auto& sp : pts) out << sp.n - transient << ',' << sp.x << ',' << sp.v << '\n';
    out.commit();
    std::fprintf(stderr, "%s: %zu section points -> %s\n", printable(p.name).c_str(), pts.size(), printable(a.required("--out")).c_str());
    return 0;
}

namespace {

// The CF sweep the flags ask for: over omega (--omega-min, --omega-max or --range) or over xI or m0e at --omega.
ParamSweep param_sweep_from(const Args& a, const Params& p, const std::string& sweep) {
    constexpr double kAny = std::numeric_limits<double>::infinity();   // check_sweep says which range applies
    ParamSweep s;
    const std::string over = a.str("--over", "omega");
    const auto which = parse_sweep_param(over);
    if (!which) throw UsageError("bifurcation: option '--over': '" + over + "' is not one of omega, xI, m0e");
    s.over = *which;
    s.direction = sweep == "up" ? SweepDirection::Up : SweepDirection::Down;
    s.steps = a.integer("--steps", s.steps, 1, 100000);
    if (s.over == SweepParam::Omega) {
        if (a.has("--omega")) throw UsageError("bifurcation: --omega is the fixed frequency of an xI or m0e sweep; over omega "
                                               "give --range or --omega-min, --omega-max");
        if (a.has("--range") && (a.has("--omega-min") || a.has("--omega-max")))
            throw UsageError("bifurcation: --range and --omega-min/--omega-max say the same: give one");
        s.lo = a.num("--omega-min", 25.0 / s.steps, 1e-3, 1000.0);
        s.hi = a.num("--omega-max", 25.0, 1e-3, 1000.0);
        if (s.hi < s.lo) throw UsageError("bifurcation: --omega-max is below --omega-min");
        std::tie(s.lo, s.hi) = a.range("--range", -kAny, kAny, {s.lo, s.hi});
    } else {
        for (const char* f : {"--omega-min", "--omega-max"})
            if (a.has(f)) throw UsageError(std::string("bifurcation: ") + f + " goes with --over omega; over " + over +
                                           " give --range A:B and the fixed --omega");
        if (!a.has("--range")) throw UsageError("bifurcation: --over " + over + " needs --range A:B [" +
                                                sweep_param_unit(s.over) + "]");
        if (!a.has("--omega")) throw UsageError("bifurcation: --over " + over + " needs the fixed forcing frequency --omega W [rad/s]");
        s.omega = a.num("--omega", 0.0, 1e-3, 1000.0);
        std::tie(s.lo, s.hi) = a.range("--range", -kAny, kAny, {0.0, 0.0});
    }
    if (const std::string why = check_sweep(p, s); !why.empty()) {
        // Names the flag at fault: the fixed omega, a model without a bumper, or the range.
        const char* flag = why.rfind("omega ", 0) == 0 && s.over != SweepParam::Omega ? "--omega"
                           : why.rfind("xI: ", 0) == 0                                 ? "--over"
                           : a.has("--range")                                          ? "--range"
                                                                                       : "--omega-min/--omega-max";
        throw UsageError(std::string("bifurcation: ") + flag + ": " + why);
    }
    return s;
}

}  // namespace

int cmd_bifurcation(const std::vector<std::string>& argv) {
    if (show_help_if_asked(argv,
                   "usage: impactlab bifurcation --model A1H --sweep up|down|ramp --out diag.csv [--png diag.png] [options]\n\n"
                   "  --sweep up       CF sweep: omega_j = 25 j/300, 20 transient + 70 recorded periods each,\n"
                   "                   each omega starting from the previous final state (MODEL.md)\n"
                   "  --sweep down     the same omegas in reverse (hysteresis)\n"
                   "  --sweep ramp     EF ramp: omega = 25.1 t/2800 for 0 <= t <= 2800 s, x at every phi = 2 pi i\n"
                   "  --omega-min W, --omega-max W, --steps N, --transient N, --record N   override the CF defaults\n"
                   "                   (for ramp: --omega-max is the final omega, --ramp-time T its duration)\n"
                   "  --over xI|m0e|omega   the parameter the CF sweep moves (default omega); xI or m0e are moved\n"
                   "                   quasi-statically at the fixed --omega, from the start of --range to its end\n"
                   "  --range A:B      the swept parameter's range in its SI units: xI [m] (a model with a bumper,\n"
                   "                   within [-0.1, 0.1]), m0e [kg m] (in (0, 10]), omega [rad/s] (as --omega-min:--omega-max)\n"
                   "  --omega W        the forcing frequency [rad/s] of an xI or m0e sweep (required with them)\n"
                   "  --out FILE       CSV output with columns omega,x,v (required; xI,x,v or m0e,x,v for those sweeps)\n"
                   "  --settle N       judge each CF level by the map's own test: a level whose section values do not\n"
                   "                   yet recur in order (periods up to 32) runs on, a record at a time, up to N more\n"
                   "                   records; it then reads its period, or -1: not settled, no period up to 32 (chaos,\n"
                   "                   or a transient longer than that: drawn grey), in a 4th CSV column, period\n"
                   "                   (default 10; 0: the paper's 20 + 70 periods alone, 3 columns)\n"
                   "  --png FILE       also plot the diagram\n", kModelHelp))
        return 0;
    const Args a("bifurcation", argv,
                 with_model_flags({"--sweep", "--out", "--png", "--omega-min", "--omega-max", "--steps", "--transient",
                                   "--record", "--ramp-time", "--over", "--range", "--omega", "--settle"}));
    const Params p = model_from(a);
    const std::string sweep = a.str("--sweep", "up");
    if (sweep != "up" && sweep != "down" && sweep != "ramp")
        throw UsageError("bifurcation: option '--sweep': '" + sweep + "' is not one of up, down, ramp");
    if (sweep == "ramp")
        for (const char* f : {"--over", "--range", "--omega", "--settle"})
            if (a.has(f)) throw UsageError(std::string("bifurcation: ") + f + " is for the CF sweeps (up, down), not the ramp");
    const std::string out_path = a.required("--out");
    auto out = open_out(out_path);
    if (a.has("--png")) check_writable(a.str("--png", ""), "--png");
    Progress progress;
    Diagram d;
    const int settle = a.integer("--settle", 10, 0, 1000);
    {
        ProgressBar bar("bifurcation " + p.name + " " + sweep, progress);
        if (sweep == "ramp") {
            EfSpec spec;
            spec.omega_max = a.num("--omega-max", spec.omega_max, 0.01, 1000.0);
            spec.t_ramp = a.num("--ramp-time", spec.t_ramp, 1.0, 1e6);
            // One point per forcing period: the phase of a linear ramp is omega_max t_ramp / 2.
            check_rows("bifurcation", spec.omega_max * spec.t_ramp / (2 * kTwoPi), "--omega-max x --ramp-time / 4 pi");
            d = run_ef_ramp(p, spec, &progress, tolerances_from(a));
        } else {
            const ParamSweep ps = param_sweep_from(a, p, sweep);
            CfSpec spec;
            spec.transient = a.integer("--transient", spec.transient, 0, 1000000);
            spec.record = a.integer("--record", spec.record, 1, 1000000);
            check_rows("bifurcation", static_cast<double>(ps.steps) * spec.record, "--steps x --record");
            d = run_cf_param_sweep(p, ps, spec.transient, spec.record, &progress, tolerances_from(a), nullptr, settle);
        }
    }
    write_diagram_csv(d, out);   // renamed into place when the command succeeds, the PNG included
    std::fprintf(stderr, "%s %s: %zu points, %.0f s simulated, %llu steps -> %s\n", printable(p.name).c_str(), d.protocol.c_str(),
                 d.points.size(), d.simulated_seconds, static_cast<unsigned long long>(d.steps), printable(out_path).c_str());
    if (!d.levels.empty()) {
        int periodic = 0, unsettled = 0;
        for (const DiagramLevel& lv : d.levels) (lv.period > 0 ? periodic : unsettled) += 1;
        std::fprintf(stderr, "levels: %d periodic, %d not settled (no period up to %d within --settle %d more records: "
                     "chaos or a longer transient)\n", periodic, unsettled, kDiagramMaxPeriod, settle);
    }
    if (sweep != "ramp" && d.over == SweepParam::Omega) {   // Fig. 3's transitions are of omega, from the hilltop
        const Transitions tr = find_transitions(d);
        // A transition the sweep did not meet is NaN: say "none" rather than print "nan".
        const auto at = [](double w, const char* fmt) {
            if (std::isnan(w)) return std::string("none");
            char buf[32];
            std::snprintf(buf, sizeof buf, fmt, w);
            return std::string(buf);
        };
        std::string chaos = "none";
        if (!std::isnan(tr.chaos_start)) chaos = at(tr.chaos_start, "%.4g") + ".." + at(tr.chaos_end, "%.4g");
        std::fprintf(stderr, "transitions (omega, rad/s): leaves x~0 %s, period 2 %s, chaos %s, period 1 again %s",
                     at(tr.jump, "%.3g").c_str(), at(tr.period_doubling, "%.4g").c_str(), chaos.c_str(),
                     at(tr.period1_return, "%.4g").c_str());
        for (const auto& w : tr.windows) std::fprintf(stderr, ", window %.4g..%.4g", w.first, w.second);
        std::fprintf(stderr, "\n");
    }
    if (a.has("--png")) {
        save_diagram_png(d, a.str("--png", ""));
        std::fprintf(stderr, "plot -> %s\n", printable(a.str("--png", "")).c_str());
    }
    return 0;
}

int cmd_figure3(const std::vector<std::string>& argv) {
    if (show_help_if_asked(argv, "usage: impactlab figure3 --out fig3.png [--steps N] [--rtol R]\n\n"
                         "Computes and stacks the panels of the paper's Fig. 3: the EF forcing omega(t), A1C-EF, and the\n"
                         "CF diagrams of A1C, A1C1, A3C, A1G, A1H (increasing omega).\n"
                         "  --steps N   omegas per CF diagram (default 300)\n"))
        return 0;
    const Args a("figure3", argv, {"--out", "--steps", "--rtol"});
    const std::string out_path = a.required("--out");
    const int steps = a.integer("--steps", 300, 2, 100000);
    const Tolerances tol = tolerances_from(a);
    check_writable(out_path, "--out");
    Figure3Data data;
    Progress progress;
    {
        ProgressBar bar("figure3", progress);
        data = compute_figure3(steps, tol, &progress);
    }
    save_figure3_png(data, out_path);
    std::fprintf(stderr, "figure 3 -> %s\n", printable(out_path).c_str());
    return 0;
}

}  // namespace impactlab::cli
