// The fit as a session: what run_fit carries from stage to stage, and the tools the stages share (not
// installed). Each stage reads what the stages before it left in the FitSession and adds its own part.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <numeric>
#include <string>
#include <vector>

#include "identify/internal.hpp"
#include "impactlab/forces.hpp"

namespace impactlab::identify::detail {

// The changes a fit made to the model given, in order: each step's model, the effects it holds and its
// held-out shooting RMS. The final gate walks back from the last step until the model is not worse than the
// model given on any error the report prints.
struct ChainStep {
    std::string what;
    Model model;
    std::vector<FoundEffect> found;
    double held_out_rms_m = -1;
    bool baseline = false;   // a step of the baseline fit (before any effect)
    bool equation_error_fit = false;   // this model's parameters minimise the record's own equation error
};
using Chain = std::vector<ChainStep>;

// The record cut for held-out checks: windows within the predictability horizon of `m`, and blocks of
// about an eighth of the record alternately in fold 0 and fold 1 (rows and windows by fold).
struct HeldOutSplit {
    Horizon hz;
    double periods = 0;   // window length [forcing periods]
    std::vector<std::pair<std::size_t, std::size_t>> wins;
    std::array<Prep, 2> fold_pr;
    std::array<std::vector<std::size_t>, 2> fold_wins;   // indices into wins
    double t0 = 0, block = 1;
    int fold_of(const Prep& pr, std::size_t i) const { return static_cast<int>(std::floor((pr.data->t[i] - t0) / block)) % 2; }
};
// Two models' held-out errors compared window by window: the relative fall of the summed error, and the
// paired z of the fall. The paired test runs over the informative windows, where the two models' errors
// differ by more than a tenth of the window's noise: an impact-law effect changes only the windows with
// impacts in them. The t statistic is read through F(1, n-1), so a few windows need a large and consistent
// fall.
struct Compare { double gain = 0, z = 0, sum_cur = 0, sum_new = 0; };

struct Group {
    std::size_t cand;
    double start;
    EffectInstance inst;
    std::vector<int> cols;
};
struct Screen {
    std::vector<Candidate> cands;
    std::vector<Group> groups;
    std::vector<int> base_cols;
    Eigen::MatrixXd X;
    Folds folds;
};
// A generic term set aside for named effects that explained about as much on the equation error (named
// physics before curve fits): the held-out judge decides between them in the validation.
struct Rival {
    std::vector<std::size_t> named;    // group indices of the named effect (or pair) chosen
    std::size_t generic = 0;           // group index of the generic term set aside
    EffectInstance generic_inst;       // its coefficients fitted in their place
    double z = 0;                      // its significance there
};
struct Selection {
    std::vector<std::size_t> chosen;   // group indices, in the order chosen
    std::vector<double> step_gain;     // the in-sample share each one added
    double in_base = 0;                // in-sample SSE with the base columns alone
    std::vector<Rival> rivals;
};

// One fit in progress: the data, the model given and the options, then what each stage leaves for the next.
struct FitSession {
    FitSession(const MeasuredData& d, const Model& given, const FitOptions& options, const MeasuredData* test_data,
               FitProgress* watcher)
        : data(d), model0(given), o(options), test(test_data), progress(watcher), ee_base(given), base(given), after(given) {}
    const MeasuredData& data;
    const Model& model0;          // the model given
    FitOptions o;                 // a baseline fit that does not hold on held-out data turns into a fixed baseline
    const MeasuredData* test;     // rows held out for the simulation error, if any
    FitProgress* progress;
    Prep prep;
    int hac_lag = 0;                          // Newey-West lag of the residual rows
    std::vector<std::string> base_names;      // the base parameters fitted (none for a fixed baseline)
    Model ee_base;                            // the baseline fitted to the equation error
    Model base;                               // the baseline the effects are added to
    bool base_refined = false;                // base was refined on the free-run simulation error (output error)
    Chain chain;                              // the changes made to the model given, for the final gate
    Eigen::VectorXd R0;                       // the baseline's residual at prep.rows
    double in0 = 0;                           // its sum of squares
    Screen screen;
    Selection sel;
    SentenceContext sc;                       // typical speed and position, for the effects' sentences
    Model after;                              // the model with the effects
    FitReport rep;

    // Where each stage starts in the whole fit's progress (their typical share of the run time); the last
    // entry closes the last stage.
    static constexpr std::array<double, static_cast<std::size_t>(FitStage::Count) + 1> kStageStart{
        0.0, 0.04, 0.10, 0.14, 0.18, 0.24, 0.34, 0.80, 1.0};
    // Enters stage s: the watcher sees it, and a cancel asked for stops the fit here (throws FitCancelled).
    void enter(FitStage s) const {
        if (!progress) return;
        if (progress->cancel.load(std::memory_order_relaxed)) throw FitCancelled();
        progress->stage.store(static_cast<int>(s), std::memory_order_relaxed);
        progress->fraction.store(kStageStart[static_cast<std::size_t>(s)], std::memory_order_relaxed);
    }
    // A share `within` (0..1) of stage s done.
    void report_progress(FitStage s, double within) const {
        if (!progress) return;
        const auto k = static_cast<std::size_t>(s);
        progress->fraction.store(kStageStart[k] + within * (kStageStart[k + 1] - kStageStart[k]), std::memory_order_relaxed);
    }
};

// The Newey-West lag of the equation error's rows: two kernel widths, in rows (every H/4-th sample).
int hac_lag_of(const Prep& pr);

// ---- the stages, in the order run_fit calls them ------------------------------------------------------------
// run_offsets.cpp: 0, runs in different wells whose chain centred each run's x: `shifted` gets the record with
// each run at its well, model0 the tied cubic's starting values, rep the offsets and a note. False: nothing to do.
bool run_offsets_stage(const MeasuredData& data, Model& model0, const FitOptions& o, MeasuredData& shifted, FitReport& rep);
// origin.cpp: 0, a placeholder whose record lies far from its zero: its spring centred on the record (model0's
// origin x0, a note in rep). False: the origin is kept.
bool centre_placeholder(const MeasuredData& data, Model& model0, const FitOptions& o, FitReport& rep);
void fit_baseline_stage(FitSession& fs);   // baseline.cpp: 1, the baseline (fs.base, fs.ee_base)
void screen_candidates(FitSession& fs);    // screening.cpp: 2, the candidates' columns (fs.screen)
void select_effects(FitSession& fs);       // screening.cpp: 3, greedy selection (fs.sel)
void refit_stage(FitSession& fs);          // refit.cpp: 4, the model with the effects (fs.after)
void impact_law_stage(FitSession& fs);     // impact_law.cpp: 5, bumper position, impact duration, restitution
void validate_effects(FitSession& fs);     // validation.cpp: 6, held-out validation
void output_error_stage(FitSession& fs);   // validation.cpp: 6b, the output-error refit of an input-forced record

class HeldOutJudge;   // judge.hpp: the held-out judge of stage 6
// shape.cpp: the last pass of 6, each named law the judge's model keeps held against the generic terms of its
// variables (fit.rivals): replaced by it where the generic term beside it predicts held-out data better and does
// as well without it; the generic term added beside it where both are needed. The judge follows the changes.
void named_against_generic(FitSession& fs, HeldOutJudge& judge);
void errors_stage(FitSession& fs);         // errors.cpp: 7 and 8, the final gate, errors, plots, verdict
void uncertainty_stage(FitSession& fs);    // uncertainty.cpp: 9, the base parameters' standard errors

// ---- tools.cpp, held_out.cpp ----------------------------------------------------------------------------------
// Levenberg-Marquardt on the weak-form residual over `knobs` (numerical Jacobian). Returns the final
// residual in R and the Jacobian dR/dknob in J.
void lm_residual(const Prep& pr, Model& m, std::vector<Knob>& knobs, int max_iter, Eigen::VectorXd& R, Eigen::MatrixXd& J);
// Measured positions a rig model can describe, or a DataError that says what is wrong and what to try: a
// position beyond the rail's travel (a unit slip, mm as m) or a record that runs through the bumper.
void check_plausible(const MeasuredData& data, const Model& m, const FitOptions& o);
// The output-error fit uses samples [a, end]; the rest of the record validates it.
std::size_t oe_fit_end(const Prep& pr, std::size_t a, std::size_t max_samples);
// RMS of a free run against the measured x over samples [from, end) where the run is defined; -1 if none.
double free_run_rms(const std::vector<double>& fr, const std::vector<double>& x, std::size_t from = 0);
// Levenberg-Marquardt on the free-run simulation error (input-forced data only: there a free run over the
// record is meaningful, and it weighs the resonance the way the benchmark's simulation error does).
void lm_simulation(const Prep& pr, Model& m, std::vector<Knob>& knobs, int max_iter, double rtol);
// The impact laws' small fit: minimises sum f(theta)^2 within bounds; returns the covariance scale (J'J)^-1.
Eigen::MatrixXd lm_small(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f, Eigen::VectorXd& th,
                         const Eigen::VectorXd& lo, const Eigen::VectorXd& hi);
// Integrated correlation time of a residual series, by batch means over blocks of B rows (1 for white noise).
double corr_time(const Eigen::VectorXd& e, int B);
// Significance of a group of columns by the rise of the sum of squares if they were held at their null
// values and the others refitted (linearised: delta' S delta with S the Schur complement), against the
// residual's variance and correlation time. Robust where the group is nearly collinear with the rest.
double group_z_dss(const Eigen::MatrixXd& J, const Eigen::VectorXd& R, const std::vector<int>& sub, const Eigen::VectorXd& delta, int B);
// Knobs for the fitted base parameters, with their physical bounds: mass, damping, friction and unbalance
// never negative, the input gain keeps the sign it starts with, the magnets' b2 keeps F_SA's denominator
// positive.
std::vector<Knob> base_knobs(Model& m, const std::vector<std::string>& names, const Prep& pr);
// Knobs for the free parameters of effect instance `inst` as candidate `c` fits them, with their bounds.
void effect_knobs(const Candidate& c, EffectInstance& inst, std::vector<Knob>& knobs);
// A base parameter's value in model m.
double base_value(const Model& m, const char* name);
// The knob of a base-changing candidate (cart_mass: m), its bounds about the base model's value.
Knob base_change_knob(const Candidate& c, Model& m, const Model& base);
// The value of a base-changing candidate's parameter in model m (what it moved from the base model).
double base_change(const Candidate& c, const Model& m, const Model& base);
// Knobs of the effects a fit added to model m (the effects after base's, and a base parameter a
// base-changing candidate moved), as their candidates fit them. With `owner`: each knob's index in
// m.p.effects (SIZE_MAX for a base parameter).
std::vector<Knob> found_effect_knobs(Model& m, const Model& base, const std::vector<Candidate>& cands,
                                     std::vector<std::size_t>* owner = nullptr);
// Why a model is not physical, or empty: what a fit must never write.
std::string unphysical(const Model& m);
ImpactLawError impact_error(const Prep& pr, const PredictedImpacts& pred);
std::vector<std::pair<std::string, double>> named(const EffectInstance& e);
double rms_of(const Eigen::VectorXd& R);
// The flat-top shift that puts a model's simulated impacts on the measured ones, from the impacts with
// use[k] set: the median of the paired level differences, corrected until the moved bumper's own forces
// (and a compliant contact's penetration with them) are accounted for. Returns the shift of xI [m]; the model
// is left with it.
double fit_bumper_shift(const Prep& pr, Model& m, const std::vector<char>& use, double rtol, double tol);
// An impact law (impact_duration or restitution) refitted to the impacts with use[k] set, in the form the
// whole record chose (a constant when its decay rate is 0, else the full law from the whole record's values).
std::vector<std::pair<std::string, double>> refit_impact_law(const Prep& pr, const Model& m, const FoundEffect& f,
                                                             const std::vector<char>& use);
// One-sample t test of mean > 0, as the equivalent standard-normal z (read through F(1, n-1), signed).
double t_test_z(const std::vector<double>& d);
// The window length [forcing periods] of every held-out judgement: the record's own predictability (measured
// from the data), not the model's, whose error grows from its own faults and would make a periodic record look
// chaotic. A regular record is judged over whole periods; a chaotic one within the doubling time of nearby
// returns; windows short enough that there are about 40 of them (the paired test's power). Where the record is
// too short to measure, `model_horizon` (the model's error growth) decides.
double judging_periods(const Prep& pr, const std::function<double()>& model_horizon);
HeldOutSplit held_out_split(const Prep& pr, const Model& m, double rtol);
Compare compare_held_out(const Prep& pr, const std::vector<std::pair<std::size_t, std::size_t>>& wins, const std::vector<double>& cur,
                         const std::vector<double>& cand);
// Whether a change `cand` of model `cur` is better beyond the noise on held-out windows: a paired z >= 3 and
// a fall of the summed error by at least 2 % of its part above the sensor noise.
bool better_beyond_noise(const Prep& pr, const std::vector<std::pair<std::size_t, std::size_t>>& wins, const Compare& c);
// Whether an output-error refinement (`refined`) predicts the part of the record its fit did not use better
// than the equation-error values (`before`), by the shooting error over the judging windows (initial states
// fitted) after the samples the refinement was fitted to. A long free run of a chaotic record drifts onto
// another trajectory whatever the model, so the free-run error alone cannot say whether a refinement helped;
// a regular record is judged over long windows, where the equation error's bias at a few samples per period
// shows. No held-out part, no refinement.
bool refinement_predicts_better(const Prep& pr, const Model& refined, const Model& before, double rtol);
// Whether the fitted baseline predicts held-out data better than the parameters given (a record forced by
// the unbalance, whose given model is a physical one): each fold's windows simulated with the base
// parameters refitted on the other fold's equation error, against the given model, by the same test as an
// effect. A baseline fit that only matches the equation error (biased at a few samples per period, or
// fitting noise) must not replace the parameters it was given.
bool baseline_predicts_better(const Prep& pr, const Model& given, const Model& fitted, const std::vector<std::string>& names,
                              const FitOptions& o, std::string& why);

}  // namespace impactlab::identify::detail
