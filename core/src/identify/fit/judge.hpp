// The held-out judge of stage 6 (not installed): the record cut into two folds of windows within its
// predictability horizon, a model's error on each held-out window with its effects refitted on the other fold,
// and the model kept so far, which an effect joins only where it predicts held-out data better beyond the noise.
#pragma once

#include <map>

#include "identify/fit/session.hpp"

namespace impactlab::identify::detail {

// What the judge decided about one effect offered to the model kept so far.
enum class Verdict {
    Kept,                  // it predicts held-out data better beyond the noise: the model holds it now
    TooFewWindows,         // the record has too few judging windows to validate anything on
    Unphysical,            // the model with it is not physical
    ShiftNotSignificant,   // a bumper shift refitted against the model it joins no longer stands out
    NotBetter,             // the held-out error does not fall beyond the noise
};
const char* verdict_name(Verdict v);
// A fall too small may grow once another effect is kept: validated alone, a force's per-fold refit absorbs the
// error of a partner effect not yet in the model, and a bumper shift is refitted against the new model.
inline bool worth_retrying(Verdict v) { return v == Verdict::ShiftNotSignificant || v == Verdict::NotBetter; }

// A kept step's name in the chain, with the held-out fall that kept it.
std::string kept_name(const std::string& what, const Compare& c);

class HeldOutJudge {
public:
    // Cuts the record (the horizon of the best model at hand: the baseline with every effect found) and
    // judges the baseline; the report gets the windows' number and length.
    explicit HeldOutJudge(FitSession& fs);

    // Offers effect f to the model kept so far. It is refitted against that model first (an impact law on
    // every impact, an end stop on every reversal, a force on the whole record where the base is fitted
    // jointly): f's values, sentence and held-out gain are those of the model judged. Kept: the model holds it,
    // fs.rep.effects_found ends with it and the chain of kept steps with the new model.
    Verdict try_keep(FoundEffect& f);
    // The record of f turned down by the last try_keep with verdict v (the reason with its numbers).
    RejectedEffect rejection(const FoundEffect& f, Verdict v) const;

    // ---- the judgements themselves --------------------------------------------------------------------------
    bool can_judge() const { return !e_cur_.empty(); }
    // Held-out SSE of each window: fold f's windows simulated with model_for[f], its force effects refitted on
    // the other fold's rows (an impact-law effect comes refitted on the other fold's impacts).
    std::vector<double> errors_by_fold(const std::array<Model, 2>& model_for) const;
    std::vector<double> errors(const Model& m) const { return errors_by_fold({m, m}); }
    Compare compare(const std::vector<double>& cur, const std::vector<double>& cand) const;
    bool better(const Compare& c) const;
    double rms(const std::vector<double>& e) const;   // the held-out shooting RMS of an error set [m]

    // ---- the model kept so far --------------------------------------------------------------------------------
    const Model& model() const { return cur_; }
    const std::vector<double>& model_errors() const { return e_cur_; }
    const std::vector<double>& baseline_errors() const { return e_base_; }
    void set_model(Model m, std::vector<double> e) {
        cur_ = std::move(m);
        e_cur_ = std::move(e);
    }
    // A step of the chain: the model now, the effects found now, its held-out RMS.
    void record(const std::string& what) { kept_.push_back({what, cur_, fs_.rep.effects_found, rms(e_cur_), false}); }
    Chain& steps() { return kept_; }
    // Back to the baseline with no step kept (the model with every effect does not beat it).
    void reset_to_baseline() {
        cur_ = fs_.base;
        e_cur_ = e_base_;
        kept_.clear();
    }

    // ---- refits on the whole record -----------------------------------------------------------------------
    // Whether the base parameters are refitted with the effects (a fitted baseline of a record forced by the
    // unbalance), and whether an effect's values come from the joint fit that moved them (they are refitted).
    bool refit_base() const { return refit_base_; }
    bool joint_base() const { return joint_base_; }
    // m's force effects (and the base, where refitted) refitted on the whole record's equation error, with
    // the standard errors (HAC) each effect's values get there.
    void refit_whole_record(Model& m);
    // An effect's values in model m: a base change's parameter, or the last instance of its law.
    std::vector<std::pair<std::string, double>> values_in(const Model& m, const FoundEffect& f) const;
    // An effect's values and standard errors from the last whole-record refit, and its sentence with them.
    void take_whole(const Model& m, FoundEffect& f) const;

private:
    // The force effects of m (and the base, where refitted) refitted on the equation error of `on`'s rows; the
    // knobs, and the instance each belongs to (SIZE_MAX: a base parameter). Empty: nothing to refit there.
    std::vector<Knob> refit_effects(const Prep& on, Model& m, std::vector<std::size_t>& owner, Eigen::VectorXd& R,
                                    Eigen::MatrixXd& J) const;
    // f refitted against the model kept (cand: that model with f added): false for a bumper shift that no
    // longer stands out.
    bool refit_against_model(FoundEffect& f, Model& cand);
    // The held-out errors of cand, f's values refitted per fold as the whole record's were.
    std::vector<double> errors_with(const FoundEffect& f, const Model& cand) const;

    FitSession& fs_;
    const Prep& pr_;
    bool refit_base_ = false, joint_base_ = false;
    HeldOutSplit sp_;
    std::size_t samples_ = 0;                               // in the judging windows
    std::array<std::vector<char>, 2> impacts_in_;           // impacts by fold (of their entry sample)
    std::array<std::vector<char>, 2> strays_in_;            // reversals away from the bumper by fold
    std::map<std::string, std::vector<std::pair<std::string, double>>> whole_sigma_;   // by effect
    std::vector<double> e_base_;                            // the baseline's held-out errors (empty: cannot judge)
    Model cur_;
    std::vector<double> e_cur_;
    Chain kept_;                                            // the model after each step kept, in order
    // The last try_keep's numbers, for its rejection's reason.
    Compare last_;
    double last_dx_ = 0, last_se_ = 0;
    std::string last_why_;
};

}  // namespace impactlab::identify::detail
