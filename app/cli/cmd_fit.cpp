// impactlab fit: close the loop with measured data (see core/include/impactlab/identify.hpp).
#include <cmath>
#include <cstdio>
#include <sstream>

#include "commands.hpp"
#include "common.hpp"

#include <filesystem>
#include "impactlab/identify.hpp"
#include "impactlab/input_file.hpp"

namespace impactlab::cli {

namespace {

constexpr const char* kFitHelp =
    "usage: impactlab fit DATA.csv[.gz] [MORE.csv ...] --model A1H --report DIR [options]\n\n"
    "Several files are runs of one rig fitted together with shared parameters (each its own forcing, initial\n"
    "state and rows): a left-well and a right-well run, or several drive levels. Only so is an asymmetry\n"
    "between the wells identifiable; the report gives both wells' depths and frequencies with uncertainties.\n"
    "Runs the whole loop on a measured run: the residual of the model (equation error on free flight, impact law,\n"
    "multiple-shooting simulation error, bifurcation-diagram distance), the missing effect it traces to (a library\n"
    "of named effects, or a generic smooth force named by its variable), the model with it, the error before and\n"
    "after. Writes DIR/report.json, DIR/report.md, DIR/model_after.json and PNG plots.\n\n"
    "Model:\n"
    "  --model NAME|FILE.json  version (A1H, A1G, ...), a parameter file, or 'duffing' (m y''+d y'+k y+k3 y^3 = gain u)\n"
    "  --xI X, --m0e M         override the bumper position [m] / the unbalance [kg m]\n"
    "  --baseline fixed|fit    validate the parameters as given (default; 'duffing' always fits) or fit them\n"
    "  --fit-params LIST       base parameters to fit, comma-separated (c,T,k,a1,a3,b2,b4,m0e,gain,m,xI;\n"
    "                          k2 where the model carries an even_stiffness)\n"
    "  --gain G                starting gain of the input u [N per unit of u] (default 1)\n"
    "Data (MODEL.md layout: t,x and phi or u; '#' comments):\n"
    "  --t-col C, --x-col C, --phi-col C, --u-col C   map a column by header name or 1-based number\n"
    "  --rate HZ               sample rate of a file without a time column\n"
    "  --free                  a free run (a decay): nothing forced it, u = 0 (implied where every column is motion)\n"
    "  --x-scale S, --u-scale S, --phi-scale S, --t-scale S   unit factors (e.g. --x-scale 1e-3 for mm)\n"
    "  --rows A:B              use data rows A..B-1 (0-based); the whole file is still checked\n"
    "  --test-rows A:B         rows held out: their free-run simulation error, and their shooting error within\n"
    "                          the predictability horizon (what a chaotic test part can be judged by), before and after\n"
    "Analysis:\n"
    "  --window S              half-width of the residual's averaging window [s] (default: 1/12 of the shortest\n"
    "                          forcing period, at least 6 samples)\n"
    "  --z Z                   significance an effect needs (default 5)\n"
    "  --min-gain F            least share of the residual an effect must explain (default 0.01)\n"
    "  --max-effects N         at most N force effects (default 4)\n"
    "  --only LIST, --exclude LIST   restrict the library (ids, comma-separated)\n"
    "  --no-generic            never fall back to the generic fits (unexplained_x, _v, _phi, _x_signv)\n"
    "  --no-refine             shooting: use the smoothed initial states as they are\n"
    "  --knots S               knot spacing of the omega(t) fitted to phi [s] (default 0.5)\n"
    "  --omega-bin W           omega bin of the diagram distance [rad/s] (default 0.25)\n"
    "  --rtol R                integrator tolerance of the simulations (default 1e-8)\n"
    "  --x-highpass HZ         the record's x was high-passed at HZ (FFT bins below it zeroed, as when x is\n"
    "                          integrated from v): the model's free runs are filtered alike before any comparison\n"
    "  --no-plots              skip the PNGs\n";

// Before anything is read: the report's files can be written and none of them is an input.
void check_report_outputs(const std::vector<std::string>& paths, const std::string& dir) {
    check_report_dir(dir);
    for (const char* name : {"report.json", "report.md", "model_after.json"})
        check_not_input((std::filesystem::path(dir) / name).string(), "--report");
    for (const auto& p : paths)
        if (std::filesystem::path(p).extension() == ".png")
            check_not_input((std::filesystem::path(dir) / std::filesystem::path(p).filename()).string(), "--report");
}

// The data flags: columns, rate and unit factors.
identify::LoadOptions load_options(const Args& a) {
    identify::LoadOptions lo;
    lo.columns.t = a.str("--t-col", "");
    lo.columns.x = a.str("--x-col", "");
    lo.columns.phi = a.str("--phi-col", "");
    lo.columns.u = a.str("--u-col", "");
    lo.rate = a.num("--rate", 0.0, 1e-6, 1e9);
    lo.x_scale = a.num("--x-scale", 1.0, -1e9, 1e9);
    lo.u_scale = a.num("--u-scale", 1.0, -1e12, 1e12);
    lo.phi_scale = a.num("--phi-scale", 1.0, -1e9, 1e9);
    lo.t_scale = a.num("--t-scale", 1.0, 1e-12, 1e9);
    lo.free_run = a.has("--free");
    return lo;
}

// The runs fitted together, joined, and the rows held out of the first (--test-rows).
struct Records {
    identify::MeasuredData data, test;
    bool has_test = false;
};

Records load_records(const Args& a, const std::vector<std::string>& paths, identify::LoadOptions lo) {
    Records rec;
    try {
        if (a.has("--rows")) identify::parse_row_range(a.str("--rows", ""), lo.row_begin, lo.row_end);
        std::vector<identify::MeasuredData> runs;
        for (const auto& p : paths) runs.push_back(identify::load_measured(p, lo));
        rec.data = identify::join_records(runs);
        if (a.has("--test-rows")) {
            identify::LoadOptions lt = lo;
            identify::parse_row_range(a.str("--test-rows", ""), lt.row_begin, lt.row_end);
            rec.test = identify::load_measured(paths[0], lt);
            rec.has_test = true;
        }
    } catch (const identify::DataError& e) {
        throw UsageError(e.what());
    }
    return rec;
}

// The model flags: the model resolved for the data's forcing, with its overrides.
identify::Model fit_model(const Args& a, const identify::MeasuredData& data) {
    const std::string model_name = a.str("--model", "A1H");
    identify::Model model;
    try {
        model = identify::resolve_fit_model(model_name, identify::forcing_of(data));
    } catch (const ParamError& e) {
        throw UsageError(std::string("--model: ") + e.what());
    }
    if (a.has("--xI")) model.p.xI = a.num("--xI", 0.0, -0.1, 0.1);
    if (a.has("--m0e")) model.p.m0e = a.num("--m0e", model.p.m0e, 0.0, 10.0);
    if (a.has("--gain")) model.p.input_gain = a.num("--gain", 1.0, -1e12, 1e12);
    if (identify::forcing_of(data) == identify::Forcing::Input) model.forcing = identify::Forcing::Input;   // a model file may say otherwise
    return model;
}

// The analysis flags, checked against the effect library.
identify::FitOptions fit_options(const Args& a, const identify::Model& model) {
    identify::FitOptions o;
    const std::string baseline = a.str("--baseline", model.bumper() ? "fixed" : "fit");
    if (baseline != "fixed" && baseline != "fit") throw UsageError("fit: --baseline must be 'fixed' or 'fit'");
    o.fit_baseline = baseline == "fit";
    o.fit_params = split_list(a.str("--fit-params", ""));
    if (!o.fit_params.empty()) o.fit_baseline = true;
    o.window = a.num("--window", 0.0, 0.0, 100.0);
    o.z_threshold = a.num("--z", 5.0, 0.0, 1e6);
    o.min_gain = a.num("--min-gain", 0.01, 0.0, 1.0);
    o.max_effects = a.integer("--max-effects", 4, 0, 20);
    o.only = split_list(a.str("--only", ""));
    o.exclude = split_list(a.str("--exclude", ""));
    o.generic = !a.has("--no-generic");
    o.refine_shooting = !a.has("--no-refine");
    o.knot_spacing = a.num("--knots", 0.5, 1e-3, 1e6);
    o.omega_bin = a.num("--omega-bin", 0.25, 1e-6, 1e3);
    o.rtol = a.num("--rtol", 1e-8, 1e-13, 1e-2);
    o.x_highpass_hz = a.num("--x-highpass", 0.0, 0.0, 1e9);
    o.plots = !a.has("--no-plots");
    for (const auto& id : o.only)
        if (!identify::find_catalogue_effect(id)) throw UsageError("fit: --only: unknown effect '" + id + "'");
    for (const auto& id : o.exclude)
        if (!identify::find_catalogue_effect(id)) throw UsageError("fit: --exclude: unknown effect '" + id + "'");
    return o;
}

// The fit with a progress bar naming its stage; the bar is gone before the report is written.
identify::FitReport fit_with_progress(const Records& rec, const identify::Model& model, const identify::FitOptions& o) {
    identify::FitProgress progress;
    ProgressBar bar("fit " + model.p.name, progress.fraction, [&progress] {
        const int s = progress.stage.load();
        return s >= 0 ? std::string(identify::fit_stage_name(static_cast<identify::FitStage>(s))) : std::string();
    });
    try {
        return identify::run_fit(rec.data, model, o, rec.has_test ? &rec.test : nullptr, &progress);
    } catch (const identify::DataError& e) {
        throw UsageError(e.what());
    }
}

// What was found: the effects, the validation, the record's horizon, the gate and verdict, the base
// parameters and the wells seen in the data.
void print_findings(const identify::FitReport& r, const std::string& path) {
    if (r.metres())
        std::printf("%s: %zu samples, model %s (%s), sensor noise %.3g um\n", printable(path).c_str(), r.samples, printable(r.before.p.name).c_str(),
                    identify::baseline_name(r.baseline), r.sigma_x * 1e6);
    else
        std::printf("%s: %zu samples, model %s (%s), sensor noise %.3g (%s)\n", printable(path).c_str(), r.samples, printable(r.before.p.name).c_str(),
                    identify::baseline_name(r.baseline), r.sigma_x, r.x_unit());
    if (r.effects_found.empty()) std::printf("effects found: none\n");
    for (const auto& f : r.effects_found) {
        std::printf("effect %-22s explains %5.1f %%  z = %6.1f  %s\n", f.id.c_str(), 100 * f.explained_fraction, f.z, f.sentence.c_str());
        if (!f.not_told_from.empty())
            std::printf("       its shape is not resolved: the data do not tell it from %s (a force of this size, no finding of its law)\n",
                        f.not_told_from.c_str());
    }
    for (const auto& f : r.effects_rejected) std::printf("rejected %-22s %s\n", f.id.c_str(), f.reason.c_str());
    if (r.horizon_periods > 0)
        std::printf("validated on %zu held-out windows of %.3g forcing periods (within the predictability horizon): shooting RMS %.3g -> %.3g %s\n",
                    r.validation_windows, r.horizon_periods, r.validation_rms_before_m, r.validation_rms_after_m,
                    r.x_unit());
    if (r.data_free_run)
        std::printf("the record is a free run: regular by its dynamics, judged over whole periods of its own oscillation\n");
    else if (r.data_horizon_measured && r.data_regular)
        std::printf("the record is regular: nearby returns stay together for 10 forcing periods (judged over whole periods)\n");
    else if (r.data_horizon_measured)
        std::printf("the record's own horizon: nearby returns double their separation in %.3g forcing periods (lambda ~ %.3g 1/s)\n",
                    r.data_horizon_periods, r.data_lambda);
    for (const auto& ro : r.run_offsets)
        std::printf("run %zu's x shifted by %+.4g +/- %.2g %s (its well's place; the chain had centred it on zero)\n", ro.run + 1, ro.offset,
                    ro.sigma, r.x_unit());
    for (const auto& g : r.gate) std::printf("final gate: %s\n", g.c_str());
    std::printf("final gate passed: %s\n", r.gate_passed.c_str());
    std::printf("verdict: %s\n", r.verdict.c_str());
    for (const auto& bp : r.base_estimates)
        std::printf("base parameter %s = %.6g +/- %.2g%s\n", bp.name.c_str(), bp.value, bp.sigma,
                    bp.stood_in_by.empty() ? "" : (" (not separated from " + bp.stood_in_by + ": no finding)").c_str());
    for (const auto& u : r.unseparated)
        std::printf("the data do not separate %s and %s (correlation %.4f): they pin %s %s %s = %.6g +/- %.2g\n", u.a.c_str(), u.b.c_str(),
                    u.correlation, u.a.c_str(), u.ratio ? "/" : "*", u.b.c_str(), u.value, u.sigma);
    for (const auto& w : r.data_wells)
        std::printf("run %zu's own well (from its data): %s, %.4g +/- %.2g Hz, local k2 %.3g +/- %.2g\n", w.run + 1,
                    w.side.empty() ? "side unclear" : w.side.c_str(), w.omega / (2 * 3.141592653589793), w.somega / (2 * 3.141592653589793),
                    w.k2, w.sk2);
    if (!r.wells_from_data.empty()) std::printf("wells from the data: %s\n", r.wells_from_data.c_str());
    if (!r.well_frequency.empty()) std::printf("%s\n", r.well_frequency.c_str());
}

// The two wells of the model written, with their asymmetry.
void print_wells(const identify::FitReport& r) {
    const auto& wa = r.wells_after;
    if (wa.wells.size() == 2 && std::isfinite(wa.hill_x)) {
        const double s = r.metres() ? 1e3 : 1.0;
        const std::string depth_unit = r.metres() ? "J" : "(data units/s)^2 per unit mass";
        for (int k = 0; k < 2; ++k) {
            const auto& w = wa.wells[static_cast<std::size_t>(k)];
            // A Duffing model in the data's units has m = 1: its depths are per unit mass, not joules.
            std::printf("%s well: x = %.4g +/- %.2g %s, depth %.4g +/- %.2g %s, omega %.4g +/- %.2g rad/s (%.4g Hz)%s\n", k ? "right" : "left ",
                        w.x * s, w.sx * s, r.metres() ? "mm" : r.x_unit(), w.depth, w.sdepth, depth_unit.c_str(), w.omega,
                        w.somega, w.omega / (2 * 3.141592653589793), w.beyond_bumper ? " (beyond the bumper)" : "");
        }
        std::printf("wells, right minus left: depth %.3g +/- %.2g %s, omega %.3g +/- %.2g rad/s (%zu run%s:", wa.depth_asym, wa.sdepth_asym,
                    depth_unit.c_str(), wa.omega_asym, wa.somega_asym, r.runs, r.runs > 1 ? "s" : "");
        for (const auto& rw : wa.run_wells) std::printf(" %s", rw.c_str());
        std::printf(")\n");
    }
}

// The error table: the model given, the fitted baseline (when the gate kept one) and the model written.
void print_errors(const identify::FitReport& r) {
    const auto& b = r.error_before;
    const auto& e = r.error_after;
    const std::string xu = std::string("[") + r.x_unit() + "]";
    const std::string fu = r.metres() ? "[N]" : "[force units]";
    const bool bc = r.baseline_column;
    const auto& eb = r.error_baseline;
    if (bc) std::printf("%-38s %14s %14s %14s\n", "", "given", "baseline", "written");
    else std::printf("%-38s %14s %14s\n", "", "given", "written");
    auto row = [&](const std::string& name, double vb, double vbase, double va) {
        if (bc) std::printf("%-38s %14.5g %14.5g %14.5g\n", name.c_str(), vb, vbase, va);
        else std::printf("%-38s %14.5g %14.5g\n", name.c_str(), vb, va);
    };
    row("residual RMS " + fu, b.residual_rms_N, eb.residual_rms_N, e.residual_rms_N);
    row("shooting RMS 1 period " + xu + (r.past_horizon(1.0) ? " *" : ""), b.shooting_rms_1_m, eb.shooting_rms_1_m, e.shooting_rms_1_m);
    row("shooting RMS 10 periods " + xu + (r.past_horizon(10.0) ? " *" : ""), b.shooting_rms_10_m, eb.shooting_rms_10_m,
        e.shooting_rms_10_m);
    if (b.shooting_rms_judge_m >= 0 && r.horizon_periods != 1.0 && r.horizon_periods != 10.0) {
        char name[80];
        std::snprintf(name, sizeof name, "shooting RMS %.3g periods %s", r.horizon_periods, xu.c_str());
        row(name, b.shooting_rms_judge_m, eb.shooting_rms_judge_m, e.shooting_rms_judge_m);
    }
    if (b.impact.impacts) {
        row("impact law kappa RMS", b.impact.kappa_rms, eb.impact.kappa_rms, e.impact.kappa_rms);
        row("impact law dwell RMS [ms]", b.impact.duration_rms_s * 1e3, eb.impact.duration_rms_s * 1e3, e.impact.duration_rms_s * 1e3);
        row("impact law bumper level offset [m]", b.impact.level_offset_m, eb.impact.level_offset_m, e.impact.level_offset_m);
    }
    if (b.diagram_distance_m >= 0) row("diagram distance [m]", b.diagram_distance_m, eb.diagram_distance_m, e.diagram_distance_m);
    if (b.simulation_rms_m >= 0)
        row(std::string("free-run simulation RMS") + (r.past_horizon(INFINITY) ? " *" : ""), b.simulation_rms_m, eb.simulation_rms_m,
            e.simulation_rms_m);
    if (b.attractor_x_w1 >= 0) {
        row("attractor x distance / std", b.attractor_x_w1, eb.attractor_x_w1, e.attractor_x_w1);
        row("attractor v distance / std", b.attractor_v_w1, eb.attractor_v_w1, e.attractor_v_w1);
        if (r.data_well_changes_per_s >= 0) {
            char name[80];
            std::snprintf(name, sizeof name, "well changes /s (record %.3g)", r.data_well_changes_per_s);
            row(name, b.attractor_wells_per_s, eb.attractor_wells_per_s, e.attractor_wells_per_s);
        }
        if (b.attractor_spectrum_db >= 0) row("spectrum RMS difference [dB]", b.attractor_spectrum_db, eb.attractor_spectrum_db, e.attractor_spectrum_db);
    }
    if (r.past_horizon(1.0) || r.past_horizon(10.0) || r.past_horizon(INFINITY))
        std::printf("* past the record's predictability horizon (%.3g periods): printed, not judged; the attractor judges there\n",
                    r.data_horizon_periods);
    if (b.test_simulation_rms_m >= 0)
        row("free-run simulation RMS (test)", b.test_simulation_rms_m, eb.test_simulation_rms_m, e.test_simulation_rms_m);
    if (b.test_shooting_rms_m >= 0) row("shooting RMS (test) " + xu, b.test_shooting_rms_m, eb.test_shooting_rms_m, e.test_shooting_rms_m);
    for (const auto& w : r.gate_within) std::printf("rose within its scatter: %s\n", w.c_str());
}

}  // namespace

int cmd_fit(const std::vector<std::string>& argv) {
    if (show_help_if_asked(argv, kFitHelp)) return 0;
    const Args a("fit", argv, {"--model",    "--xI",          "--m0e",     "--rtol",    "--report",    "--baseline",  "--fit-params",
                               "--gain",     "--t-col",       "--x-col",   "--phi-col", "--u-col",     "--rate",      "--x-scale",
                               "--u-scale",  "--phi-scale",   "--t-scale", "--rows",    "--test-rows", "--window",    "--z",
                               "--min-gain", "--max-effects", "--only",    "--exclude", "--knots",     "--omega-bin", "--x-highpass"},
                 {"--no-generic", "--no-refine", "--no-plots", "--free"}, /*takes_files=*/true);
    if (a.positional().empty()) throw UsageError("fit: give a data file, or several runs of one rig (see impactlab fit --help)");
    const std::vector<std::string> paths = a.positional();
    const std::string path = paths.size() == 1 ? paths[0] : paths[0] + " + " + std::to_string(paths.size() - 1) + " more";
    if (paths.size() > 1 && a.has("--test-rows")) throw UsageError("fit: --test-rows needs a single data file");
    const std::string dir = a.required("--report");
    for (const auto& p : paths) note_input(p);
    note_input(a.str("--model", "A1H"));
    check_report_outputs(paths, dir);
    const Records rec = load_records(a, paths, load_options(a));
    const identify::Model model = fit_model(a, rec.data);
    const identify::FitOptions o = fit_options(a, model);
    const identify::FitReport r = fit_with_progress(rec, model, o);
    identify::write_report(r, dir, o.plots);
    print_findings(r, path);
    print_wells(r);
    print_errors(r);
    std::printf("report: %s/report.json, report.md (%.2f s)\n", printable(dir).c_str(), r.runtime_s);
    return 0;
}

}  // namespace impactlab::cli
