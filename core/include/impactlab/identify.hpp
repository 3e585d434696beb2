// impactlab fit: close the loop with measured data. A measured run goes in; out come where the model is
// wrong (the residual in three forms), which physical effect it lacks (a library of named effects chosen by
// sparse regression with cross-validation and a significance test, or a generic smooth force named by the
// variable it depends on), the model with that effect added, and the error before and after.
//
// The equation error is taken in weak form: r_K(t_i) = sum_j K(t_j - t_i) [m x'' + F_R + F_SA + F_I -
// forcing - effects](t_j), a local average over a smooth bump K of half-width `window`, with m x'' moved
// onto K'' by parts (so no acceleration is differentiated out of noisy x) and v from a Savitzky-Golay
// derivative where a force is nonlinear in v (refined at velocity reversals, where dry friction kinks the
// motion). Samples whose window touches an impact, or a turning point where the cart may stick, are left out.
// Input-forced data (u) with fitted parameters are refined on the free-run simulation error as well, and an
// effect is kept there only if it improves the simulation of the part of the record the fit did not use.
#pragma once

#include <algorithm>
#include <atomic>
#include <functional>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "impactlab/identify_data.hpp"
#include "impactlab/params.hpp"

namespace impactlab::identify {

enum class Forcing { Unbalance, Input };   // phi drives m0e phi'^2 sin(phi); or a measured input u
inline const char* forcing_name(Forcing f) { return f == Forcing::Unbalance ? "phi (unbalance)" : "u (measured input)"; }

// The model impactlab fit works with: the physical parameters (with any effects), and how the data force it.
struct Model {
    Params p;               // p.input_gain: the force per unit of u; impact model "none": no bumper
    Forcing forcing = Forcing::Unbalance;
    // Starting values only (resolve_fit_model's "duffing"), not a model of any rig: the fit judges its changes
    // against the baseline it fits, never against these.
    bool placeholder = false;
    bool bumper() const { return p.has_bumper(); }
    // The measurement map x_measured = sensor_gain * c(x) + sensor_offset, from the sensor_* effects; c is
    // the identity unless a curved sensor effect bends the scale.
    double sensor_gain() const;
    double sensor_offset() const;
    bool sensor_curved() const;
    double measure(double x) const;         // what the sensor reads at the true position x
    double true_x(double x_measured) const; // its inverse
    double measure_slope(double x) const;   // d x_measured / dx at the true position x
};

// A version name ("A1H"), a parameter file (*.json), or "duffing": m y'' + d y' + k y + k3 y^3 = gain u
// (m = 1, no bumper; for the Silverbox benchmark). Throws ParamError.
Model resolve_fit_model(const std::string& name_or_path, Forcing forcing);
// What drives a record: the unbalance where it has phi, else its measured input u (the one rule the CLI and
// the GUI both follow; the loader refuses a record with neither).
inline Forcing forcing_of(const MeasuredData& data) { return data.has_phi() ? Forcing::Unbalance : Forcing::Input; }

// The effects impactlab fit and synth know: the registry's force laws plus four that change the base
// model instead of adding a force (bumper_offset, impact_duration, restitution, cart_mass).
struct EffectInfo {
    std::string id, meaning;
    std::vector<std::string> names, units;
    std::vector<double> defaults;
    bool generic = false;      // unexplained_*: only the last-resort generic stage uses it
    bool changes_base = false; // bumper_offset, impact_duration, restitution, cart_mass
};
const std::vector<EffectInfo>& effect_catalogue();
const EffectInfo* find_catalogue_effect(const std::string& id);
// A generic (unexplained_*) term by its catalogue row: a shape described, no physics named.
inline bool generic_effect(const std::string& id) {
    const EffectInfo* e = find_catalogue_effect(id);
    return e && e->generic;
}
// Sets effect `id` with its parameter values (missing ones keep their defaults) into the model: a force law
// is appended to p.effects, a base-changing effect edits p (xI, the impact law, m). Throws ParamError.
void apply_effect(Model& m, const std::string& id, const std::vector<std::pair<std::string, double>>& values);

struct FitOptions {
    bool fit_baseline = false;           // false: validate the model with its parameters fixed
    std::vector<std::string> fit_params; // base parameters to fit (empty: a default set for the model)
    double window = 0.0;                 // half-width of the weak-form kernel [s]; 0: automatic
    double z_threshold = 5.0;            // significance (|coefficient| / its HAC standard error)
    double min_gain = 0.01;              // least share of the current residual an effect must explain
    int max_effects = 4;
    bool generic = true;                 // allow the generic smooth fits (unexplained_*)
    std::vector<std::string> only;       // restrict the library to these ids (empty: all)
    std::vector<std::string> exclude;    // never consider these ids
    bool refine_shooting = true;         // shooting: refine each window's initial state (Gauss-Newton)
    double knot_spacing = 0.5;           // [s] knots of the omega(t) fitted to phi
    double omega_bin = 0.25;             // [rad/s] bins of the diagram distance
    double rtol = 1e-8;                  // integrator tolerance for the shooting
    bool plots = true;
    // The measurement chain: the record's x was high-passed at this frequency [Hz] (every FFT bin below it
    // zeroed, as when x is integrated from a velocity). The model's free runs are filtered the same way before
    // any comparison with x; 0: x is the displacement itself.
    double x_highpass_hz = 0.0;

    // Whether `only` and `exclude` let effect `id` into the fit: never when excluded; with an `only` list,
    // just the ids on it. The screening's candidate list and the end-stop stage both ask this.
    bool wants(const std::string& id) const {
        return std::find(exclude.begin(), exclude.end(), id) == exclude.end() &&
               (only.empty() || std::find(only.begin(), only.end(), id) != only.end());
    }
};

// Measured impacts against the same impacts simulated with the model and read by the same detector.
struct ImpactLawError {
    std::size_t impacts = 0;     // measured impacts the model also makes (the pairs compared)
    double kappa_rms = 0;        // RMS of measured minus simulated apparent restitution -v+/v-
    double duration_rms_s = 0;   // RMS of measured minus simulated dwell at the bumper [s]
    double level_offset_m = 0;   // median of measured minus simulated flat-top level (measured coordinates) [m]
};

struct ErrorSummary {
    double residual_rms_N = 0;        // RMS of the weak-form equation error on free-flight samples
    double shooting_rms_1_m = 0;      // multiple shooting over windows of one forcing period
    double shooting_rms_10_m = 0;     // ... of ten forcing periods
    ImpactLawError impact;
    double diagram_distance_m = -1;   // mean per omega bin of the Wasserstein distance; < 0: not computed
    std::size_t diagram_bins = 0;
    std::vector<std::pair<double, double>> diagram_per_bin;   // (omega at the bin's centre, distance [m])
    double simulation_rms_m = -1;     // free run over the whole record (input-forced data); < 0: not computed
    double test_simulation_rms_m = -1;// the same on the test rows, if given
    // Shooting on the test rows over windows as long as the held-out validation's (within the predictability
    // horizon, initial states fitted): a chaotic test part's free run drifts onto another trajectory whatever
    // the model, so only this says whether the model predicts the test rows better. < 0: no test rows.
    double test_shooting_rms_m = -1;
    // Shooting over windows as long as the held-out judge's (the judging horizon); < 0: not computed.
    double shooting_rms_judge_m = -1;
    // The free run's attractor against the record's (input-forced data), what judges a chaotic record past its
    // predictability horizon; < 0: not computed. Distances of the x and v distributions (Wasserstein-1 over
    // the record's std), the model's well changes per second, the spectra's RMS difference [dB].
    double attractor_x_w1 = -1, attractor_v_w1 = -1, attractor_wells_per_s = -1, attractor_spectrum_db = -1;
};

// What showed an effect: the equation error (a force law) or the impacts (an impact law).
enum class Evidence { EquationError, ImpactLaw, StrayImpacts };
const char* evidence_name(Evidence e);   // "equation error", "impact law", "stray impacts"

struct FoundEffect {
    std::string id;
    double explained_fraction = 0;    // share of the baseline residual (of the impact-law error for impact effects)
    std::vector<std::pair<std::string, double>> parameters, sigma;   // fitted values and standard errors
    std::string sentence;
    double z = 0;                     // significance
    Evidence evidence = Evidence::EquationError;
    // The held-out check that kept it: relative fall of the short-horizon simulation error on the fold the
    // effect's parameters were not fitted to, and the paired z of that fall over the windows.
    double validation_gain = 0, validation_z = 0;
    // A law or shape of the same variable the data do not tell this one from (empty: its shape is resolved).
    // Then it is a force of the size fitted, kept because it predicts held-out data at least as well as the
    // alternatives, and no finding of its law.
    std::string not_told_from;
};

struct CandidateScore {              // every library candidate tried in the first round
    std::string id;
    double gain = 0, z = 0;          // share of the residual it would explain alone, and its significance
    bool selected = false;
    std::vector<std::pair<std::string, double>> coefficients;   // its parameters fitted alone
    double cv_gain = 0;              // cross-validated share of the residual it explains (what ranked it)
};

// An effect the residual pointed to and the held-out simulation error turned down.
struct RejectedEffect {
    std::string id, reason;
    double validation_gain = 0, validation_z = 0;
    std::vector<std::pair<std::string, double>> parameters;
};

// Plot material kept from the run.
struct Trace {
    std::vector<double> t, measured, before, after;
};
struct ResidualCloud {
    std::vector<double> x, v, phi, before, after;
};
// A measured impact, and the same impact simulated with the model before and after (NaN: none there).
struct ImpactPoint {
    double t, v_minus, v_plus, dwell, level;
    double kappa_before, dwell_before, kappa_after, dwell_after;
};

// The wells of a model's static force (springs, magnets and every effect at v = 0, averaged over the forcing
// phase): position, depth below the hilltop between them [J] and the linearised frequency [rad/s], with
// standard errors propagated from the found effects' parameter uncertainties. A well beyond the bumper is
// listed too (flagged): the rail's magnets still make it.
struct Well {
    double x = 0, depth = 0, omega = 0;
    double sx = 0, sdepth = 0, somega = 0;
    bool beyond_bumper = false;
};
struct WellReport {
    std::vector<Well> wells;                 // ascending x; two for a bistable rig
    double hill_x = 0;                       // the unstable equilibrium between two wells
    double depth_asym = 0, sdepth_asym = 0;  // right depth minus left depth [J], and its standard error
    double omega_asym = 0, somega_asym = 0;  // right minus left linearised frequency [rad/s]
    std::vector<std::string> run_wells;      // per run of the data: "left", "right" or "both"
};

// One run's own well, measured from its data (input-forced records): the local force law per unit mass
// a + c v + k x + k2 x^2 + k3 x^3 - F0 = g u fitted on the run's free-flight samples.
struct RunWell {
    std::size_t run = 0;
    double x0 = 0;                 // the equilibrium in the data's coordinates
    double omega = 0, somega = 0;  // linear frequency there [rad/s] and its standard error
    double k2 = 0, sk2 = 0;        // local even term per unit mass (< 0: softer toward +x, the left well)
    std::string side;              // "left", "right" or "" (no clear even term)
    double depth = 0;              // by the local law's barrier, per unit mass [x unit^2 / s^2]; NaN: none within reach
    double barrier = 0;            // distance from x0 to that barrier [x unit]
    double c = 0, gain = 0;        // the damping and input gain per unit mass the runs share in the same regression
};
// A run's x shifted to where its well lies (a chain that removed each run's mean, runs in different wells):
// the offset added and its standard error, from the wells' local laws tied to one force law.
struct RunOffset {
    std::size_t run = 0;
    double offset = 0, sigma = 0;   // [x unit]
};

// Whether a fit's base parameters were fitted to the data or kept as given.
enum class Baseline { Fixed, Fit };
const char* baseline_name(Baseline b);   // "fixed", "fit"

// Units of x and of the equation error: metres and newtons for the rig; a plain Duffing model (m = 1) works in
// the data's own units, which the report names as such.
enum class FitUnits { Metres, DataUnits };

// A base parameter written, with its standard error from the equation error (inf: the data do not see it).
struct BaseEstimate {
    std::string name;
    double value = 0, sigma = 0;
    std::string stood_in_by;   // the effects found that can stand in for it (then its value is no finding), or empty
};
// Two base parameters the data do not separate (correlation beyond 0.98): what they pin is their ratio a/b
// (correlated) or their product a*b (anticorrelated), with its standard error.
struct UnseparatedPair {
    std::string a, b;
    double correlation = 0;
    bool ratio = true;
    double value = 0, sigma = 0;
};

struct FitReport {
    std::string data_source, model_name;
    Forcing forcing = Forcing::Unbalance;
    Baseline baseline = Baseline::Fixed;
    std::size_t samples = 0, rows_used = 0;
    double dt = 0, duration = 0, sigma_x = 0, window_s = 0, noise_floor_N = 0;
    double omega_min = 0, omega_max = 0, drive_fit_rms_rad = 0, period_s = 0;
    Model before, after;
    std::vector<FoundEffect> effects_found;
    std::vector<RejectedEffect> effects_rejected;
    // The predictability horizon: shooting error of the baseline against window length, and the length the
    // held-out validation used.
    std::vector<std::pair<double, double>> horizon_growth;   // (window [forcing periods], RMS [m])
    double horizon_periods = 0;
    // The record's own predictability, from nearby returns of the measured trajectory (not the model): the
    // doubling time of their separation [forcing periods] (inf: regular, no doubling in 10 periods) and the
    // exponent it implies [1/s]; not measured on records too short for it.
    bool data_horizon_measured = false, data_regular = false;
    bool data_free_run = false;   // nothing drives the record: regular by its dynamics, no returns measured
    double data_horizon_periods = 0, data_lambda = 0;
    // Whether a trajectory error over `periods` forcing periods lies past the record's predictability horizon
    // (a chaotic record): printed, never judged.
    bool past_horizon(double periods) const { return data_horizon_measured && !data_regular && data_horizon_periods < periods; }
    double data_well_changes_per_s = -1;   // the record's passages between two wells; < 0: one well (or phi-forced)
    std::size_t validation_windows = 0;
    double validation_rms_before_m = 0, validation_rms_after_m = 0;   // held-out shooting RMS
    std::vector<CandidateScore> candidates;
    ErrorSummary error_before, error_after;   // the model given and the model written
    // With a fitted baseline that passed the gate: its errors (the effects were judged against it too).
    ErrorSummary error_baseline;
    bool baseline_column = false;
    std::string baseline_step;
    std::vector<ImpactPoint> impacts;
    ResidualCloud residual;
    Trace trace;
    std::vector<std::pair<double, double>> diagram_measured, diagram_before, diagram_after;   // (omega, x)
    std::vector<std::string> notes;
    double runtime_s = 0;
    double x_highpass_hz = 0;   // the high-pass declared for x (FitOptions::x_highpass_hz); 0: none
    FitUnits units = FitUnits::Metres;
    bool metres() const { return units == FitUnits::Metres; }
    const char* x_unit() const { return metres() ? "m" : "data units"; }
    const char* force_unit() const { return metres() ? "N" : "model force units (m = 1: data units / s^2)"; }
    std::string verdict;   // one sentence on the residual against its noise floor, after the validation
    std::size_t runs = 1;  // records fitted together
    WellReport wells_before, wells_after;
    // The final gate: each change it undid and why (the model written worse than the model given on a printed
    // error beyond its scatter), and the step of the fit whose model it passed.
    std::vector<std::string> gate;
    // What the final residual depends on: the cross-validated share explained by a smooth function of each
    // variable alone ("x", "v", "the forcing phase", "time", "the time since an impact", "a constant").
    std::vector<std::pair<std::string, double>> remainder;
    // Each run's well measured from the data, and what they say of an asymmetry (empty: not measured).
    std::vector<RunWell> data_wells;
    std::vector<RunOffset> run_offsets;   // runs shifted to their wells before the fit (empty: none)
    std::string wells_from_data;
    // Where the record cannot pin its well's frequency (the model's and the data's own disagree, or k trades
    // off against another parameter), the sentence that says so; empty otherwise.
    std::string well_frequency;
    std::string gate_passed;
    std::vector<std::string> gate_within;   // printed errors that rose, within their scatter (said beside the table)
    // The fitted base parameters of the model written, with their standard errors, and the pairs the data
    // do not separate (empty for a fixed baseline).
    std::vector<BaseEstimate> base_estimates;
    std::vector<UnseparatedPair> unseparated;
};

// The sensor noise of a uniformly sampled record [its units]: the smaller of the MAD of its 4th differences
// (white noise on a smooth signal) and the spectrum's high-frequency floor (a signal with power up to a good
// part of the band). Signal only ever raises either, so the smaller is the honest floor.
double estimate_noise(const std::vector<double>& x);

// The stages of a fit, in the order they run.
enum class FitStage { Prepare, Baseline, Candidates, Selection, Refit, ImpactLaw, Validation, Errors, Count };
const char* fit_stage_name(FitStage s);   // "preparing the data", "fitting the baseline", ...

// A fit in progress, shared between the thread that runs run_fit and any thread that watches it.
struct FitProgress {
    std::atomic<int> stage{-1};          // the FitStage running; written by the fit's thread
    std::atomic<double> fraction{0.0};   // of the whole fit, 0..1 (by the stages' typical cost); fit's thread
    std::atomic<bool> cancel{false};     // any thread: the fit stops at its next check and throws FitCancelled
};
struct FitCancelled : std::runtime_error {
    FitCancelled() : std::runtime_error("the fit was cancelled") {}
};

// The whole loop. `test` (optional): data held out for the simulation error (same layout as `data`).
// `progress` (optional): stage and fraction as the fit goes, and a cancel flag it honours within a few
// simulated windows (then it throws FitCancelled and returns nothing).
FitReport run_fit(const MeasuredData& data, const Model& model, const FitOptions& options = {},
                  const MeasuredData* test = nullptr, FitProgress* progress = nullptr);

// The errors of one given model on the data (no selection, no fitting): what a panel that switches effects
// on and off shows. Diagram distance only when omega spans more than two bins.
ErrorSummary evaluate_model(const MeasuredData& data, const Model& model, const FitOptions& options = {});

// DIR/report.json, DIR/report.md, DIR/model_after.json and the PNGs. Throws std::runtime_error.
void write_report(const FitReport& report, const std::string& dir, bool plots = true);
std::string report_json_text(const FitReport& report);

// Synthetic measured data: the model (with its effects) driven by `omega_knots`, sampled at exact integrator
// stops, with Gaussian noise on x then quantised, and phi quantised to an encoder's counts.
struct SynthOptions {
    double duration = 60.0;            // [s]
    double rate = 1000.0;              // [Hz]
    double noise = 3e-6;               // [m] standard deviation added to x
    double quantum = 1e-6;             // [m] x is rounded to multiples of this (0: not at all)
    int phi_counts = 4096;             // counts per revolution of the encoder (0: exact phi)
    std::vector<double> knot_t{0.0}, knot_omega{16.0};   // omega(t) piecewise linear through the knots
    double x0 = -0.01, v0 = 0.0;
    unsigned seed = 1;
    double rtol = 1e-10;
    // A sampled input u at input_t0 + k input_dt: the model is driven by input_gain * u (as well as by its
    // unbalance, if m0e > 0) and the record carries u instead of phi (an input-forced record).
    std::vector<double> input;
    double input_t0 = 0.0, input_dt = 1e-3;
};
MeasuredData synthesize(const Model& model, const SynthOptions& options);
// Knots of the steps profile: plateaus of `plateau` seconds at each omega, joined by `ramp`-second ramps.
void steps_profile(const std::vector<double>& omegas, double plateau, double ramp, std::vector<double>& t,
                   std::vector<double>& w);

}  // namespace impactlab::identify

namespace impactlab::identify {

// The randomized benchmark of the loop (benchmark.cpp): `records` records drawn from families of effects the
// library has no name for (polynomials in x and v of any symmetry, mixed x-v terms, narrow bumps, piecewise
// springs, a cycling stiffness, pairs) and a null family (every seventh), over versions, regimes and noise
// levels, each fitted with the version's parameters fixed. Deterministic for a seed.
struct IdentifyBenchRecord {
    std::string family, version, regime;
    double noise = 0;
    std::vector<std::string> allowed, named;   // library ids whose physics is in the record; ids the fit named
    bool null_family = false;
    bool false_claim = false;   // a named (not generic) law that is not in the data
    bool better = false;        // 1-period shooting down 3x, or to 1.5x the noise
    bool honest = false;        // the noise floor claimed exactly when the model written is at the noise
    bool before_at_floor = false;
    double before = 0, after = 0, runtime_s = 0;
    std::string error;          // the fit's error, if it failed
    std::string truth;          // the injected laws and their coefficients, e.g. "bench_poly_x(0, 0, 0.12, 0, -0.3, 0)"
};
struct IdentifyBenchOptions {
    int records = 200;
    unsigned seed = 1;
    double duration = 30.0;     // [s] per record, at 1 kHz
    int only = 0;               // > 0: fit record `only` (1-based) alone; the others are drawn, not fitted
    std::string report_dir;     // with only: that fit's report written here (report.md, report.json)
    const std::atomic<bool>* cancel = nullptr;
    std::function<void(int done, int total, const IdentifyBenchRecord& last)> progress;
};
struct IdentifyBenchResult {
    std::vector<IdentifyBenchRecord> rows;
    double false_claim_rate = 0, better_rate = 0, honest_rate = 0;
    std::size_t null_claims = 0, null_records = 0, better_records = 0, errors = 0;
};
IdentifyBenchResult run_identify_bench(const IdentifyBenchOptions& options);

// The recovery matrix: an effect injected by synth into a version at a moderate strength, and what the loop
// makes of it. Recovered when the effect is named first, its parameter lies within 3 sigma of the truth,
// and the held-out simulation error falls.
struct RecoveryCase {
    std::string version, effect, param;
    double truth = 0;
};
struct RecoveryResult {
    RecoveryCase c;
    std::string first;            // the effect named first ("" if none)
    double estimate = 0, sigma = 0;
    double rms_before_m = 0, rms_after_m = 0;   // held-out shooting RMS
    bool named_first = false, within = false, lowered = false;
    bool recovered() const { return named_first && within && lowered; }
};
// Every library effect at a moderate strength (restitution only for the rigid versions).
std::vector<RecoveryCase> recovery_cases(const std::vector<std::string>& versions);
// Synthesises the case (steps 9 and 16 rad/s, `duration` seconds, noise seed) and runs the loop on it.
RecoveryResult run_recovery(const RecoveryCase& c, double duration, unsigned seed);
// The null check: noise-only data of `version` (same profile), fitted with the version; the ids it names
// (none is the right answer) and whether the model written equals the model given.
struct NullResult {
    std::vector<std::string> found;
    bool model_unchanged = false;
    double rms_m = 0;   // 1-period shooting RMS (the sensor noise when the model is right)
};
NullResult run_null(const std::string& version, double duration, unsigned seed);

}  // namespace impactlab::identify
