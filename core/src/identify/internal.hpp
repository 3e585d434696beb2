// Internals of impactlab fit shared by the files of this folder (not installed).
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "impactlab/drive.hpp"
#include "impactlab/rosenbrock.hpp"
#include "impactlab/identify.hpp"

namespace impactlab::identify::detail {

constexpr double kPi = 3.141592653589793;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---- signal.cpp ---------------------------------------------------------------------------------------
// Standard deviation of white noise on a smooth signal, from the MAD of its 4th differences.
double noise_sigma(const std::vector<double>& x);
// The same from the spectrum's high-frequency floor (Welch, the top fifth of the band): it holds where the
// signal itself has power up to a good part of the band (where 4th differences see signal). +inf for fewer
// than 2048 samples.
double noise_sigma_spectral(const std::vector<double>& x);
// The rounding noise q / sqrt(12) of a record whose values change in whole steps q (counts), else 0.
double quantum_sigma(const std::vector<double>& x);
// Welch's periodogram: the sum over Hann segments of `seg` samples, half overlapping, each with its mean (and
// with remove_line its straight line) removed, of |FFT|^2 at bins 0..seg/2; `segments` says how many were
// summed. Empty when x is shorter than one segment.
std::vector<double> welch_sum(const std::vector<double>& x, std::size_t seg, bool remove_line, std::size_t& segments);
// Savitzky-Golay weights c[0..2M] (offsets -M..M) of the `deriv`-th derivative of a degree-`degree` fit.
std::vector<double> savgol(int half, int degree, int deriv, double dt);
// Centred FIR: y[i] = sum_k c[k] x[i + k - M]; NaN where the window leaves the data.
std::vector<double> apply_fir(const std::vector<double>& x, const std::vector<double>& c);
// Weights of one-sided polynomial fits evaluated at the split between samples (for impact detection):
// derivative at t = +dt/2 past the last of n samples (left) or dt/2 before the first (right).
std::vector<double> onesided_slope(int n, int degree, double dt, bool left);

// The weak-form kernel phi(tau) = (1 - tau^2/L^2)^6, L = (H+1) dt: w = phi/sum(phi), w1 = -phi'/sum(phi)
// (applied to x gives the averaged velocity), w2 = phi''/sum(phi) (the averaged acceleration).
struct Kernel {
    int H = 0;
    std::vector<double> w, w1, w2;   // index k = 0..2H for offsets -H..H
    double noise_gain = 0;           // sqrt(sum w2^2): sigma of the averaged acceleration per unit sigma_x
};
Kernel make_kernel(int H, double dt);

// omega(t) piecewise linear with knots every `spacing` seconds, fitted to the unwrapped phi by least squares
// (phi itself being the exact integral); rms: fit residual [rad].
Drive fit_drive(const std::vector<double>& t, const std::vector<double>& phi, double spacing, double& rms);
// Sample standard deviation of the finite values of v[a, b) (0 for fewer than two).
double stdev(const std::vector<double>& v, std::size_t a, std::size_t b);
// The period of the strongest spectral line of x (detrended) [s].
double dominant_period(const std::vector<double>& x, double dt);
// x with every Fourier component below `cut_hz` removed (the mean too), as a record integrated by FFT with the
// bins below the cut zeroed. A length with a prime factor above 7 is bridged to the next that has none (the
// FFT's cost stays N log N). Non-finite samples leave x as it is.
std::vector<double> highpass_fft(const std::vector<double>& x, double dt, double cut_hz);

// ---- impacts.cpp --------------------------------------------------------------------------------------
struct ImpactObs {
    double t_in, t_out, level, v_minus, v_plus;   // [s], [s], [m], [m/s] (v- > 0), [m/s] (v+ <= 0)
    std::size_t i_first, i_last;                  // samples spanned by the event (first after entry ... last held)
};
// Finds impacts on a bumper at the right (+x) end: abrupt drops of the one-sided velocity, each fitted by
// quadratic flight before, a held plateau (possibly of zero length) and quadratic flight after.
std::vector<ImpactObs> find_impacts(const std::vector<double>& t, const std::vector<double>& x, double sigma_x,
                                    double level_hint);


// ---- residual.cpp -------------------------------------------------------------------------------------
// The data made ready for the residual: smoothed signals, drive, kernel, masks, rows.
struct Prep {
    const MeasuredData* data = nullptr;
    std::size_t n = 0;
    double dt = 0, sigma_x = 0, period = 0, drive_rms = 0;
    double x_span = 0;                       // the record's extent, 0.5 % to 99.5 % quantiles of x
    // The record's own scales (its units, whatever they are): half its extent, its RMS speed and input, and
    // the inertial force m a they imply. Steps, floors and ceilings are set from them, never absolutely.
    double x_typ = 0, v_typ = 0, u_typ = 0, f_typ = 0;
    bool phi_forced = true;
    bool unforced = false;                   // a free run: no phi, u zero throughout (its period, horizon, gain)
    double x_highpass_hz = 0;                // FitOptions::x_highpass_hz: applied to every free run before comparison
    // One drive per run (MeasuredData::run_starts): omega(t) fitted to the run's phi, or its input u(t).
    std::vector<Drive> drives;
    std::vector<std::size_t> run_start;   // first sample of each run, ascending, run_start[0] = 0
    std::size_t run_of(std::size_t i) const {
        return static_cast<std::size_t>(std::upper_bound(run_start.begin(), run_start.end(), i) - run_start.begin()) - 1;
    }
    std::size_t run_last(std::size_t i) const {   // last sample of the run holding sample i
        const std::size_t r = run_of(i);
        return r + 1 < run_start.size() ? run_start[r + 1] - 1 : n - 1;
    }
    const Drive& drive_of(std::size_t i) const { return drives[run_of(i)]; }
    std::vector<double> xs, vs;              // S-G position and velocity (measured coordinates)
    std::vector<double> phi, omega, alpha;   // from the drive (phi data); zeros otherwise
    std::vector<double> u;
    Kernel K;
    int Hv = 0;
    std::vector<ImpactObs> impacts;
    // Reversals at the end of the travel the model has no stop at (stops.cpp): side -1 the lower end, +1 the
    // upper one (a model without a bumper), 0 none. Levels in measured x.
    std::vector<ImpactObs> stray;
    int stray_side = 0;
    std::vector<char> zone;                  // 1: the sample lies in or next to an impact
    // The narrowest strong feature of the baseline's residual against x and against v (features.cpp), in true
    // coordinates; lo == hi: none. The local generic terms put their knots there.
    struct Feature {
        double lo = 0, hi = 0, z = 0;
        bool found() const { return hi > lo; }
    } x_feature, v_feature;
    // A slow cycle of the residual's spring rate (features.cpp): the residual's part x S(t) with S periodic
    // over at least 1.5 cycles of the record and 6 forcing periods or more; period 0: none.
    struct Cycle {
        double period = 0, chi2 = 0;   // [s], the peak's reduction of the residual against the periodogram's
        bool found() const { return period > 0; }
    } cycle;
    std::vector<std::size_t> rows;           // centres of the residual windows used
    std::size_t j_lo = 0, j_hi = 0;          // samples the rows' windows touch [j_lo, j_hi)
    FitProgress* progress = nullptr;         // run_fit's, if any: checked for cancellation per simulation
    // The record's own predictability (horizon.cpp), measured once by run_fit; not measured: the model's
    // shooting error growth decides the judging windows.
    struct Predictability {
        bool measured = false, regular = false;
        double periods = 0, lambda = 0;   // separation doubling time [forcing periods] (inf: regular), exponent [1/s]
        std::size_t pairs = 0;
        std::vector<std::pair<double, double>> log_separation;   // (periods ahead, mean ln separation)
    } predictability;
    // Throws FitCancelled if the fit's watcher asked to stop (called between simulations).
    void check_cancel() const {
        if (progress && progress->cancel.load(std::memory_order_relaxed)) throw FitCancelled();
    }
};
Prep prepare(const MeasuredData& d, const Model& m, const FitOptions& o, std::vector<std::string>& notes);

// The impact laws a fit can find (impact_duration: the dwell T_imp(v-); restitution: kappa(v-)), both
// (p0 - p1) exp(-a v-) + p1: what each impact shows of them, and the law's residual over a set of impacts.
double apparent_kappa(const ImpactObs& im);   // -v+/v- as the data show it (0 for no approach speed)
struct ImpactLawData {
    bool dwell = true;              // true: impact_duration, false: restitution
    std::vector<double> vm, obs;    // approach speeds (true coordinates) and what each impact shows
};
// The impacts with use[k] set (all when use is empty); restitution only from approaches above 2 cm/s.
ImpactLawData impact_law_data(const Prep& pr, const Model& m, bool dwell, const std::vector<char>& use = {});
// Parameter names of the law, in order (Ti0, Ti1, a_T or kappa0, kappa1, a_kappa).
std::array<const char*, 3> impact_law_names(bool dwell);
// th = (p0, p1, a) -> law(v-) - observed, impact by impact.
Eigen::VectorXd impact_law_residual(const ImpactLawData& d, const Eigen::VectorXd& th);

// The impacts the model predicts where the data show one, as the data would show them: each measured
// impact's approach is simulated with the full model (every force on, on the core Simulator) from the
// flight before it, sampled at the data's times with the data's noise, and read by the same detector
// (find_impacts). So the apparent penetration and the flat top a compliant contact leaves in sampled data,
// and the dwell and restitution of a rigid law, are compared like with like. ok[k] is false where the
// model makes no impact near the measured one.
struct PredictedImpacts {
    std::vector<ImpactObs> obs;
    std::vector<char> ok;
};
PredictedImpacts predict_impacts(const Prep& pr, const Model& m, double rtol);

// ---- stops.cpp -----------------------------------------------------------------------------------------
// Finds pr.stray (at least three reversals clustered at one end of the travel) and zones them out.
void find_stray_impacts(const MeasuredData& d, const Model& m, Prep& pr);

// Weak-form residual at prep.rows [N]; `pointwise` is scratch.
void residual(const Prep& pr, const Model& m, Eigen::VectorXd& R, std::vector<double>& pointwise);
// Filtered pointwise derivative of effect `e`'s force with respect to parameter k at the current values,
// i.e. the regressor column X = -dR/dp_k [N per unit]; `m` supplies the measurement map.
void effect_column(const Prep& pr, const Model& m, const EffectInstance& e, int k, double h, Eigen::Ref<Eigen::VectorXd> X,
                   std::vector<double>& pointwise);

// ---- least_squares.cpp ----------------------------------------------------------------------------------
// A parameter a fit may move: its address, finite-difference step and bounds.
struct Knob {
    double* value;
    double step, lo, hi;
    std::string name;
};
// Fills the residual at the knobs' current values and returns |R|^2 (+inf if it cannot be evaluated).
using ResidualFn = std::function<double(Eigen::VectorXd&)>;
// The finite-difference step of a knob at a value.
using StepFn = std::function<double(const Knob&, double)>;
struct LsqOptions {
    int max_iterations = 30;
    double function_tolerance = 1e-9;   // stop when an iteration lowers the cost by less than this share
    double huber_delta = 0;             // > 0: Huber loss with this scale on each residual (outliers, saturated samples)
    long max_evaluations = 0;           // residual evaluations (a Jacobian costs one per knob); 0: 2 (knobs + 2) per iteration
    double max_seconds = 0;             // wall clock, a safety net for evaluations that turn slow; 0: none
    // The residual at given knob values (in the knobs' order) without touching the knobs, safe to call from
    // several threads at once; where set, a Jacobian's columns are evaluated in parallel, with the same values.
    std::function<bool(const std::vector<double>& values, Eigen::VectorXd& R)> eval_at;
};
struct LsqSummary {
    double initial_cost = 0, final_cost = 0;   // |R|^2
    int iterations = 0;
    bool converged = false;
    bool budget_spent = false;                 // ended by its budget, at the best point reached
};
// Bounded Levenberg-Marquardt (Ceres) over the knobs, each clamped to [lo, hi]; leaves the knobs at the
// solution, the residual there in R and, if J is given, its forward-difference Jacobian dR/dknob.
LsqSummary least_squares(std::vector<Knob>& knobs, const ResidualFn& eval, const StepFn& step_of, const LsqOptions& options,
                         Eigen::VectorXd& R, Eigen::MatrixXd* J = nullptr);

// ---- residual.cpp, for the least-squares passes ---------------------------------------------------------
// The weak-form residual of one model while a least-squares pass moves its knobs (the knobs must point into
// `m`, which outlives the cache): each sample's rig forces and each effect's force are kept, so a step of force
// effects' parameters alone (a Jacobian column, a trial point of the effects) re-evaluates those effects only.
// Its values are residual()'s bit for bit: the same terms, summed in the same order.
// The index of the effect instance of `m` whose parameters hold `value`, or -1 (a base parameter).
int effect_holding(const Model& m, const double* value);
class ResidualCache {
public:
    ResidualCache(const Prep& pr, const Model& m, const std::vector<Knob>& knobs);
    void eval(Eigen::VectorXd& R);   // at the knobs' current values

private:
    void full(Eigen::VectorXd& R);
    void finish(Eigen::VectorXd& R) const;   // pw_ -> R with the rows' kept accelerations
    void pointwise(std::size_t j, double effects);   // pw_[j] from the kept rig forces and the effects' sum
    const Prep& pr_;
    const Model& m_;
    const std::vector<Knob>& knobs_;
    std::vector<int> owner_;                   // a knob's force effect, -1: the base or a sensor (a full evaluation)
    std::vector<double> at_;                   // the knobs' values at the kept evaluation
    bool kept_ = false;
    std::vector<double> unbalance_, resistance_, spring_magnet_, impact_, x_, v_;   // per sample
    std::vector<std::vector<double>> effect_;  // per effect, per sample
    std::vector<double> acc_;                  // per row: m's factor, sum w2 x (no knob moves it but a sensor's)
    std::vector<double> pw_;
    std::vector<char> moved_;                  // per effect: its parameters moved (scratch)
    double scale_ = 1.0;
};

// ---- wells.cpp ----------------------------------------------------------------------------------------
WellReport well_report(const Model& m, const std::vector<FoundEffect>& found, const Prep& pr);

// ---- linear algebra helpers (stats.cpp) -----------------------------------------------------------------
struct Folds {   // contiguous blocks of rows for cross-validation, with per-block Gram matrices
    int K = 5;
    std::vector<Eigen::MatrixXd> G;   // X_f' X_f over all columns
    std::vector<Eigen::VectorXd> b;   // X_f' R_f
    std::vector<double> rr;           // R_f' R_f
    Eigen::MatrixXd Gt;
    Eigen::VectorXd bt;
    double rrt = 0;
};
Folds make_folds(const Eigen::MatrixXd& X, const Eigen::VectorXd& R, int K = 5);
// Cross-validated SSE and in-sample SSE of the regression of R on columns `cols`.
void cv_sse(const Folds& f, const std::vector<int>& cols, double& cv, double& in_sample, Eigen::VectorXd* beta = nullptr);
// Newey-West (Bartlett, lag L) covariance of the least-squares coefficients of R on X.
Eigen::MatrixXd hac_cov(const Eigen::MatrixXd& X, const Eigen::VectorXd& e, int L);
// A chi-square statistic with p degrees of freedom as the equivalent standard-normal z (Wilson-Hilferty).
double chi2_to_z(double W, int p);
// An F(d1, d2) statistic as the equivalent standard-normal z (Paulson's cube-root approximation): the
// small-sample counterpart of chi2_to_z when the variance is estimated from d2 degrees of freedom.
double f_to_z(double F, double d1, double d2);
// Weighted quantile / median helpers.
double median(std::vector<double> v);
// The standard error of the median of x from its own spread: 1.2533 (a median's standard error over a
// mean's, normal data) x 1.4826 MAD about `center` (the normal-consistent scale) / sqrt(n); the scale is
// never taken below `floor` (what quantisation or too few values cannot show). Non-finite values are
// left out; 0 for none.
double median_se(const std::vector<double>& x, double center, double floor = 0.0);
double quantile(std::vector<double> v, double q);
// Wasserstein-1 distance of two sorted, non-empty samples: the mean gap between their quantile functions at
// `quantiles` mid-points (k + 1/2) / quantiles.
double wasserstein1_sorted(const std::vector<double>& a, const std::vector<double>& b, int quantiles);

// ---- shooting.cpp -------------------------------------------------------------------------------------
// Simulates samples i0..i1 from the state estimated at i0 (refined by Gauss-Newton if asked); returns the
// simulated measurement g x + o at each sample (empty if the window cannot start).
// With refine_end, the initial state is fitted to samples [i0, refine_end] only (the flight before an impact).
std::vector<double> simulate_window(const Prep& pr, const Model& m, std::size_t i0, std::size_t i1, bool refine, double rtol,
                                    std::size_t refine_end = static_cast<std::size_t>(-1));
struct ShootOut {
    double rms1 = 0, rms10 = 0;
    std::size_t n1 = 0, n10 = 0;
    std::vector<std::pair<std::size_t, double>> windows10;   // first sample and RMS of each 10-period window
};
ShootOut shooting(const Prep& pr, const Model& m, const FitOptions& o);
// First sample at or after i (before limit) where a simulation may start: clear of impacts, with smoothed
// estimates of x and v.
std::size_t usable_start(const Prep& pr, std::size_t i, std::size_t limit);
// Window boundaries (sample indices [a, b]) of `periods` forcing periods each.
std::vector<std::pair<std::size_t, std::size_t>> windows(const Prep& pr, double periods);
// Sum of squared errors (measured coordinates) of each window's simulation; +inf where it fails.
std::vector<double> window_sse(const Prep& pr, const Model& m, const std::vector<std::pair<std::size_t, std::size_t>>& wins,
                               bool refine, double rtol);
// How far the record can be predicted: the shooting error of the model for windows of 0.25 to 5 forcing
// periods (dominant periods for input-forced data); the horizon is the longest length whose error is at
// most twice the shortest's.
struct Horizon {
    double periods = 0;
    std::vector<std::pair<double, double>> growth;   // (window length [periods], shooting RMS [m])
};
Horizon predictability_horizon(const Prep& pr, const Model& m, double rtol);

// ---- remainder.cpp --------------------------------------------------------------------------------------
// The share of the residual R (at pr.rows) that smooth functions of each variable alone explain, cross-validated
// over contiguous blocks, largest first: "a constant", "x", "v", "the forcing phase", "time", "the time since an
// impact".
// Finds Prep::x_feature, v_feature and cycle in the residual R (one value per row) of the model m.
void locate_features(Prep& pr, const Model& m, const Eigen::VectorXd& R);
std::vector<std::pair<std::string, double>> remainder_dependence(const Prep& pr, const Eigen::VectorXd& R);

// ---- data_wells.cpp -------------------------------------------------------------------------------------
// Each run's own well from its data (input-forced records only), and the sentence on the asymmetry they show.
std::vector<RunWell> data_wells(const Prep& pr, int hac_lag);
std::string wells_asymmetry(const std::vector<RunWell>& wells, const std::string& x_unit);
// Whether the record pins its well's frequency: not where the model written and the run's own local law put it
// more than 15 % apart, or where k and another base parameter trade off. The sentence, or empty.
std::string well_frequency_identifiability(const std::vector<RunWell>& wells, const WellReport& model_wells,
                                           const std::vector<UnseparatedPair>& unseparated);

// ---- horizon.cpp ----------------------------------------------------------------------------------------
// The record's predictability from the data alone: nearest returns of the measured trajectory in a delay
// embedding with the forcing, followed forward (Rosenstein); the doubling time of their mean separation.
using DataHorizon = Prep::Predictability;
DataHorizon data_horizon(const Prep& pr);
// The integrator's tolerances for the fit's simulations of model m on record pr (shooting.cpp).
Tolerances fit_tolerances(const Prep& pr, const Model& m, double rtol);
// Free run over the whole record from the first usable sample: simulated measurement at every sample
// (NaN before the start).
std::vector<double> free_run(const Prep& pr, const Model& m, double rtol);
// Section points (omega, x) at phi = 2 pi k: simulated in a free run, or measured.
std::vector<std::pair<double, double>> free_run_sections(const Prep& pr, const Model& m, double rtol);
std::vector<std::pair<double, double>> measured_sections(const Prep& pr);
// Mean over omega bins of the 1-D Wasserstein distance between two (omega, x) clouds.
double diagram_distance(const std::vector<std::pair<double, double>>& a, const std::vector<std::pair<double, double>>& b,
                        double bin, std::size_t& bins, std::vector<std::pair<double, double>>* per_bin = nullptr);


// ---- gate.cpp -----------------------------------------------------------------------------------------
// One error the report prints, as sums over units (blocks of rows or samples, shooting windows, impacts,
// omega bins) so that two models can be compared unit by unit. num is +inf where a model could not be
// simulated. Rms: sqrt(sum num / sum den); Mean: sum num / sum den; AbsMedian: the median of num (signed
// values, compared by magnitude).
inline constexpr const char* kErrResidual = "residual RMS";
inline constexpr const char* kErrShoot1 = "shooting RMS, 1 period";
inline constexpr const char* kErrShoot10 = "shooting RMS, 10 periods";
inline constexpr const char* kErrShootJudge = "shooting RMS at the judging horizon";
inline constexpr const char* kErrKappa = "impact law: kappa RMS error";
inline constexpr const char* kErrDwell = "impact law: dwell RMS error";
inline constexpr const char* kErrLevel = "impact law: bumper level offset";
inline constexpr const char* kErrDiagram = "diagram distance";
inline constexpr const char* kErrFree = "free-run simulation RMS";
inline constexpr const char* kErrTestFree = "free-run simulation RMS on the test rows";
inline constexpr const char* kErrTestShoot = "shooting RMS on the test rows";
struct PrintedError {
    enum class Kind { Rms, Mean, AbsMedian };
    std::string name;
    std::vector<double> num, den;
    Kind kind = Kind::Rms;
    std::vector<double> keys;   // the units' omega (diagram bins, paired by omega); empty: paired by position
    std::vector<double> noise;  // each unit's own sampling noise (a diagram bin's distance), if any
    double resolution = 0;      // the least change of the value the data resolve
    double quantum = 0;         // a unit's own quantum (an impact's dwell: one sample): a one-quantum change of one unit
    bool missing_fails = true;  // a unit only the given model has counts against the other (not so for impacts)
    // Past the record's predictability horizon a trajectory error is printed but judges nothing: any model
    // diverges there, the right one too, and the attractor's statistics judge instead.
    bool decides = true;
    double value() const;       // NaN when no unit is finite
};
// ---- attractor.cpp ------------------------------------------------------------------------------------
inline constexpr const char* kErrHistX = "attractor: x distribution, Wasserstein / std x";
inline constexpr const char* kErrHistV = "attractor: v distribution, Wasserstein / std v";
inline constexpr const char* kErrWells = "attractor: well changes per second, |ln ratio|";
inline constexpr const char* kErrSpectrum = "attractor: power spectrum, RMS dB";
// Two wells in a record's x: a dip in its histogram below half of both humps; the hilltop at the dip and a
// band of 15 % of the humps' distance on either side, which a passage must cross to count as a well change.
// A chaotic record without the dip: the median, if its sides' visits oscillate inside them.
struct WellBand {
    bool found = false;
    double hilltop = 0, band = 0;
};
WellBand well_band(const std::vector<double>& x, bool chaotic = false);
std::size_t well_changes(const std::vector<double>& x, double mid, double band);
std::size_t well_changes(const std::vector<double>& x, const WellBand& wb);
// A free run's statistics against the record's, by blocks of the samples both define (from sample `from`):
// the distance between the x and v distributions (Wasserstein-1 over the record's std), the well changes'
// rate (|ln| of the ratio), and the spectrum's RMS difference in dB over the band the record has power in.
struct AttractorStats {
    bool ok = false, wells_found = false;
    std::vector<double> hist_x, hist_v, wells, spectrum_db;   // one per block
    double rate_data = 0, rate_sim = 0;                        // well changes per second
    static double mean(const std::vector<double>& v);
};
AttractorStats attractor_stats(const Prep& pr, const std::vector<double>& sim, std::size_t from = 0);
// The same as errors the final gate compares, one unit per block (all missing for a run that stalled).
std::vector<PrintedError> attractor_errors(const AttractorStats& st);

// Every error the report prints for one model, with what the plots need of the same runs.
struct PrintedErrors {
    std::vector<PrintedError> e;
    Eigen::VectorXd R;                     // the equation error at pr.rows
    PredictedImpacts pred;
    std::vector<std::pair<double, double>> diagram, diagram_measured;
    AttractorStats attractor;              // the free run's (input-forced data)
    const PrintedError* find(const std::string& name) const;
    double value(const char* name) const {
        const PrintedError* p = find(name);
        return p ? p->value() : -1.0;
    }
};
PrintedErrors printed_errors(const Prep& pr, const Model& m, const FitOptions& o, double judge_periods, const Prep* test);


// Whether `cand` is worse than `given` on any printed error: a rise of the printed value beyond z_tol times
// its scatter over the paired units (two standard errors; visible at four significant digits), or a unit it
// cannot simulate.
struct GateCheck {
    bool worse = false;
    std::string why;
    std::vector<std::string> within;   // errors that rose, but within their scatter (said in the report)
};
GateCheck gate_check(const PrintedErrors& given, const PrintedErrors& cand, double z_tol = 2.0);

}  // namespace impactlab::identify::detail

namespace impactlab::identify::detail {

// ---- catalogue.cpp ------------------------------------------------------------------------------------
// How the selection treats one library effect.
struct Candidate {
    std::string id;
    const EffectLaw* law = nullptr;
    std::vector<int> free;          // parameters fitted (indices into the law's parameters)
    std::vector<double> step;       // their finite-difference steps (also their natural scale)
    std::vector<int> linear;        // of `free`, those fitted in the linear screening (the others stay at start)
    std::vector<double> starts;     // starting values of the nonlinear parameter free[linear.size()]
    bool generic = false, sensor = false;
    bool positive = false;          // the first linear parameter must come out > 0 to make physical sense
    // A base-changing candidate (law == nullptr): the base parameter it moves by its one parameter (cart_mass:
    // "m", moved by dm), within [lo, hi]; screened by that parameter's column, applied by apply_effect.
    const char* base = nullptr;
    const char* param = nullptr;   // its parameter's name ("dm")
    double lo = 0, hi = 0;
};
// How the selection treats library law `law`: its fitted parameters, steps and starts from its fit hint.
Candidate candidate_of(const EffectLaw& law);
std::vector<Candidate> library_candidates(const Model& m, const Prep& pr, const FitOptions& o);
// The instance a candidate starts from: shape parameters from the model, the free ones at their null value
// (or `start` for the nonlinear one); an empty instance (no law) for a base-changing candidate.
EffectInstance start_instance(const Candidate& c, const Model& m, const Prep& pr, double start);

struct SentenceContext {
    double v_typ = 0, x_typ = 0;
};
std::string sentence(const std::string& id, const Model& before, const std::vector<std::pair<std::string, double>>& values,
                     const std::vector<std::pair<std::string, double>>& sigma, const SentenceContext& ctx);
// An end stop proposed from pr.stray (position from the reversals' level, restitution from their speeds),
// appended to rep.effects_found for the held-out validation; nothing when the model has one already.
void end_stop_stage(const Prep& pr, const FitOptions& o, const SentenceContext& sc, const Model& after, FitReport& rep);
// The end stop's sentence: its law's description of `f` added to `m`, and how many reversals showed it.
std::string end_stop_sentence(const Prep& pr, const Model& m, const FoundEffect& f, const SentenceContext& sc);
// The end stop's parameters (xS, kS, cS, side) from the reversals with use[k] set (all when empty): first
// estimates from their level, dwell and restitution, then refined on the simulation error of short windows
// around them. Empty when fewer than three are used. sigma_xS, if given: xS's standard error.
std::vector<std::pair<std::string, double>> end_stop_values(const Prep& pr, const Model& m, const std::vector<char>& use, double rtol,
                                                            double* sigma_xS = nullptr);

// ---- base_effects.cpp -------------------------------------------------------------------------------------
// An effect that changes the base model instead of adding a force (bumper_offset, impact_duration,
// restitution, cart_mass): its catalogue entry, how it edits the model, its sentence, and, if the screening
// looks for it, the candidate it makes.
// What of the measured impacts a base effect changes: the flat tops' level (where the bumper stands), the dwell
// at the bumper, the speed of the rebound; None: not an impact effect. The impact-law stage and the held-out
// validation refit each effect by it (a bumper moved until the simulated flat tops sit on the measured ones,
// an impact law refitted to the dwells or to the rebounds).
enum class ImpactTrait { None, Level, Dwell, Rebound };
struct BaseEffect {
    EffectInfo info;
    bool needs_bumper = false;
    ImpactTrait impacts = ImpactTrait::None;
    // Edits m with the values v (defaults where not given; the row may complete v from what was given).
    void (*apply)(Model& m, std::vector<double>& v, const std::vector<bool>& given) = nullptr;
    std::string (*describe)(const Model& before, const std::vector<std::pair<std::string, double>>& values,
                            const std::vector<std::pair<std::string, double>>& sigma) = nullptr;
    // Fills the screening candidate (id set) for model m; false: not looked for here.
    bool (*candidate)(const Model& m, const FitOptions& o, Candidate& c) = nullptr;
};
const std::vector<BaseEffect>& base_effects();
const BaseEffect* find_base_effect(const std::string& id);
// The impact trait of effect `id`'s row (None for a force law, or an id no row has).
ImpactTrait impact_trait(const std::string& id);

// Base parameters that `fit` mode estimates: name and address in the model.
struct BaseParam {
    std::string name;
    double* value;
    double step;
};
std::vector<BaseParam> base_params(Model& m, const std::vector<std::string>& names);
// A base parameter's natural size in the record's units: the change that moves its force by the record's
// typical force f_typ where x, v and u take their typical sizes (k by f/x, a3 by f/x^3, c by f/v, ...).
double base_scale(const std::string& name, const Prep& pr, const Model& m);
std::vector<std::string> default_fit_params(const Model& m, const Prep& pr);
// A placeholder whose spring fit/origin.cpp centred on its record (it carries a sensor_offset as its origin).
bool centred_placeholder(const Model& m);
// The base parameters a fit fits: FitOptions::fit_params, else default_fit_params (none without fit_baseline),
// and a centred placeholder's origin x0.
std::vector<std::string> fitted_base_names(const Model& m, const Prep& pr, const FitOptions& o);

}  // namespace impactlab::identify::detail
