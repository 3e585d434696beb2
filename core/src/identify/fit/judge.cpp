// The held-out judge of stage 6: the record cut into folds of judging windows, and each effect offered to the
// model kept so far, refitted against it and kept only where it predicts held-out data better beyond the noise.
#include "identify/fit/judge.hpp"

namespace impactlab::identify::detail {

const char* verdict_name(Verdict v) {
    switch (v) {
        case Verdict::Kept: return "kept";
        case Verdict::TooFewWindows: return "too few windows";
        case Verdict::Unphysical: return "unphysical";
        case Verdict::ShiftNotSignificant: return "shift not significant";
        case Verdict::NotBetter: return "not better beyond the noise";
    }
    return "?";
}

namespace {
// Flags, per fold, of the events (impacts, reversals) whose first sample lies in it.
template <class Event>
std::array<std::vector<char>, 2> by_fold(const HeldOutSplit& sp, const Prep& pr, const std::vector<Event>& events) {
    std::array<std::vector<char>, 2> in;
    for (std::size_t f = 0; f < 2; ++f) {
        in[f].assign(events.size(), 0);
        for (std::size_t k = 0; k < events.size(); ++k) in[f][k] = sp.fold_of(pr, events[k].i_first) == static_cast<int>(f);
    }
    return in;
}
}  // namespace

HeldOutJudge::HeldOutJudge(FitSession& fs)
    : fs_(fs),
      pr_(fs.prep),
      // A fitted baseline of a record forced by the unbalance, or of a free run not refined on its free-run
      // error, is refitted with the effects (per fold, and on the whole record at the end): base parameters
      // fitted without an effect have absorbed what they could of it (a spring rate bent by a missing even
      // stiffness, a cubic bent to a shifted equilibrium), and those values beside the effect's make neither
      // model. An input-forced record keeps its baseline: its equation error, a few samples per period of the
      // resonance, fits the base poorly, and the output-error stage refits it with the effects.
      refit_base_(fs.o.fit_baseline && !fs.base_names.empty() && (fs.prep.phi_forced || (fs.prep.unforced && !fs.base_refined))),
      joint_base_(fs.o.fit_baseline && !fs.base_names.empty() && !refit_base_),
      // The horizon of the best model at hand (the baseline with every effect found): a wrong baseline's error
      // grows from its own fault, not from the record's instability. An unphysical candidate falls back to the
      // baseline.
      sp_(held_out_split(fs.prep, unphysical(fs.after).empty() ? fs.after : fs.base, fs.o.rtol)),
      cur_(fs.base) {
    FitReport& rep = fs.rep;
    rep.horizon_growth = sp_.hz.growth;
    rep.horizon_periods = sp_.periods;
    rep.validation_windows = sp_.wins.size();
    impacts_in_ = by_fold(sp_, pr_, pr_.impacts);
    strays_in_ = by_fold(sp_, pr_, pr_.stray);
    for (const auto& [a, b] : sp_.wins) samples_ += b - a + 1;
    if (sp_.wins.size() >= 12) e_base_ = errors(fs.base);
    e_cur_ = e_base_;
}

std::vector<Knob> HeldOutJudge::refit_effects(const Prep& on, Model& m, std::vector<std::size_t>& owner, Eigen::VectorXd& R,
                                              Eigen::MatrixXd& J) const {
    owner.clear();
    std::vector<Knob> knobs = found_effect_knobs(m, fs_.base, fs_.screen.cands, &owner);
    if (refit_base_)
        for (const Knob& k : base_knobs(m, fs_.base_names, pr_)) {
            knobs.push_back(k);
            owner.push_back(SIZE_MAX);
        }
    if (knobs.empty() || on.rows.size() < 20) return std::vector<Knob>{};
    lm_residual(on, m, knobs, 15, R, J);
    return knobs;
}

std::vector<double> HeldOutJudge::errors_by_fold(const std::array<Model, 2>& model_for) const {
    const auto& wins = sp_.wins;
    std::vector<double> e(wins.size(), INFINITY);
    for (std::size_t f = 0; f < 2; ++f) {
        Model mf = model_for[f];
        std::vector<std::size_t> owner;
        Eigen::VectorXd R;
        Eigen::MatrixXd J;
        refit_effects(sp_.fold_pr[1 - f], mf, owner, R, J);
        std::vector<std::pair<std::size_t, std::size_t>> sub;
        for (std::size_t w : sp_.fold_wins[f]) sub.push_back(wins[w]);
        const std::vector<double> ef = window_sse(pr_, mf, sub, fs_.o.refine_shooting, fs_.o.rtol);
        for (std::size_t k = 0; k < sub.size(); ++k) e[sp_.fold_wins[f][k]] = ef[k];
    }
    return e;
}

Compare HeldOutJudge::compare(const std::vector<double>& cur, const std::vector<double>& cand) const {
    return compare_held_out(pr_, sp_.wins, cur, cand);
}

bool HeldOutJudge::better(const Compare& c) const { return better_beyond_noise(pr_, sp_.wins, c); }

double HeldOutJudge::rms(const std::vector<double>& e) const {
    double s = 0;
    for (double v : e) s += std::isfinite(v) ? v : 0.0;
    return samples_ ? std::sqrt(s / static_cast<double>(samples_)) : 0.0;
}

void HeldOutJudge::refit_whole_record(Model& m) {
    std::vector<std::size_t> owner;
    Eigen::VectorXd R;
    Eigen::MatrixXd J;
    const std::vector<Knob> knobs = refit_effects(pr_, m, owner, R, J);
    if (knobs.empty()) return;
    const Eigen::MatrixXd V = hac_cov(-J, R, fs_.hac_lag);
    whole_sigma_.clear();
    for (std::size_t k = 0; k < knobs.size(); ++k)
        if (owner[k] != SIZE_MAX && V.allFinite())
            whole_sigma_[m.p.effects[owner[k]].law->id].emplace_back(
                knobs[k].name, std::sqrt(std::max(0.0, V(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(k)))));
}

std::vector<std::pair<std::string, double>> HeldOutJudge::values_in(const Model& m, const FoundEffect& f) const {
    for (const auto& c : fs_.screen.cands)
        if (c.base && f.id == c.id) return std::vector<std::pair<std::string, double>>{{c.param, base_change(c, m, fs_.base)}};
    for (auto e = m.p.effects.rbegin(); e != m.p.effects.rend(); ++e)   // the last instance of its law
        if (f.id == e->law->id) return named(*e);
    return f.parameters;
}

void HeldOutJudge::take_whole(const Model& m, FoundEffect& f) const {
    f.parameters = values_in(m, f);
    if (const auto it = whole_sigma_.find(f.id); it != whole_sigma_.end()) f.sigma = it->second;
    f.sentence = sentence(f.id, fs_.base, f.parameters, f.sigma, fs_.sc);
}

bool HeldOutJudge::refit_against_model(FoundEffect& f, Model& cand) {
    const FitOptions& o = fs_.o;
    if (f.evidence == Evidence::ImpactLaw && pr_.impacts.size() >= 3) {
        // Refitted on every impact against the model it joins (the stage fitted it against the model with every
        // effect found, some of which may have gone): the model kept is the model validated.
        const std::vector<char> all(pr_.impacts.size(), 1);
        const bool shift = impact_trait(f.id) == ImpactTrait::Level;
        if (shift) f.parameters = {{"dx", fit_bumper_shift(pr_, cand, all, o.rtol, 0.05 * pr_.sigma_x)}};
        else apply_effect(cand, f.id, f.parameters = refit_impact_law(pr_, cur_, f, all));
        f.sentence = sentence(f.id, cur_, f.parameters, f.sigma, fs_.sc);
        // A shift of the flat tops must still stand out as the stage required.
        last_dx_ = f.parameters.front().second;
        last_se_ = f.sigma.empty() ? 0.0 : f.sigma.front().second;
        return !(shift && !(std::abs(last_dx_) >= o.z_threshold * last_se_ && std::abs(last_dx_) > 2.0 * pr_.sigma_x + 1e-7));
    }
    if (f.evidence == Evidence::StrayImpacts) {
        // Refitted against the model it joins, as an impact law is.
        double se = 0;
        const auto values = end_stop_values(pr_, cur_, {}, o.rtol, &se);
        if (!values.empty()) {
            f.parameters = values;
            f.sigma.front().second = se;
        }
        f.sentence = end_stop_sentence(pr_, cur_, f, fs_.sc);
        apply_effect(cand, f.id, f.parameters);
        return true;
    }
    apply_effect(cand, f.id, f.parameters);
    // Its values came from the joint fit that moved the base parameters too, which this model does not take:
    // refitted here as the folds refit it, so the model kept is the model validated.
    if (joint_base_ && f.evidence == Evidence::EquationError) {
        refit_whole_record(cand);
        take_whole(cand, f);
    }
    return true;
}

std::vector<double> HeldOutJudge::errors_with(const FoundEffect& f, const Model& cand) const {
    if (f.evidence == Evidence::ImpactLaw) {
        // Refitted on the other fold's impacts, for each fold in turn.
        std::array<Model, 2> per_fold{cur_, cur_};
        for (std::size_t ff = 0; ff < 2; ++ff) {
            const std::vector<char>& use = impacts_in_[1 - ff];
            // A fold with fewer than three impacts cannot refit the law: there the whole record's values stand
            // (the windows are still held out).
            if (std::count(use.begin(), use.end(), 1) < 3) per_fold[ff] = cand;
            else if (impact_trait(f.id) == ImpactTrait::Level) fit_bumper_shift(pr_, per_fold[ff], use, fs_.o.rtol, 0.05 * pr_.sigma_x);
            else apply_effect(per_fold[ff], f.id, refit_impact_law(pr_, cur_, f, use));
        }
        return errors_by_fold(per_fold);
    }
    if (f.evidence == Evidence::StrayImpacts) {
        // The stop fitted to the other fold's reversals, for each fold in turn.
        std::array<Model, 2> per_fold{cand, cand};
        for (std::size_t ff = 0; ff < 2; ++ff) {
            const auto values = end_stop_values(pr_, cur_, strays_in_[1 - ff], fs_.o.rtol);
            if (values.empty()) continue;   // too few there: the whole record's values stand
            per_fold[ff] = cur_;
            apply_effect(per_fold[ff], f.id, values);
        }
        return errors_by_fold(per_fold);
    }
    return errors(cand);
}

Verdict HeldOutJudge::try_keep(FoundEffect& f) {
    if (!can_judge()) return Verdict::TooFewWindows;
    Model cand = cur_;
    if (!refit_against_model(f, cand)) return Verdict::ShiftNotSignificant;
    last_why_ = unphysical(cand);
    if (!last_why_.empty()) return Verdict::Unphysical;
    std::vector<double> e_new = errors_with(f, cand);
    last_ = compare(e_cur_, e_new);
    f.validation_gain = last_.gain;
    f.validation_z = last_.z;
    if (!better(last_)) return Verdict::NotBetter;
    FitReport& rep = fs_.rep;
    if (joint_base_ && f.evidence == Evidence::EquationError)   // the effects kept before were refitted beside it
        for (auto& g : rep.effects_found)
            if (g.evidence == Evidence::EquationError) take_whole(cand, g);
    set_model(std::move(cand), std::move(e_new));
    rep.effects_found.push_back(f);
    record(kept_name("added " + f.id, last_));
    return Verdict::Kept;
}

RejectedEffect HeldOutJudge::rejection(const FoundEffect& f, Verdict v) const {
    RejectedEffect rej{f.id, "", 0, 0, f.parameters};
    char buf[200];
    switch (v) {
        case Verdict::Kept: break;
        case Verdict::TooFewWindows: rej.reason = "too few windows to validate it on held-out data"; break;
        case Verdict::Unphysical: rej.reason = "unphysical: " + last_why_; break;
        case Verdict::ShiftNotSignificant:
            std::snprintf(buf, sizeof buf, "refitted against the model it joins, the shift is %.3g +/- %.2g m: not significant", last_dx_,
                          last_se_);
            rej.reason = buf;
            break;
        case Verdict::NotBetter:
            std::snprintf(buf, sizeof buf, "held-out simulation error %s by %.2f %% (paired z = %.1f over %zu windows): not better beyond the noise",
                          last_.gain >= 0 ? "lowered" : "raised", 100.0 * std::abs(last_.gain), last_.z, sp_.wins.size());
            rej.reason = buf;
            rej.validation_gain = last_.gain;
            rej.validation_z = last_.z;
            break;
    }
    return rej;
}

std::string kept_name(const std::string& what, const Compare& c) {
    char buf[96];
    std::snprintf(buf, sizeof buf, " (held-out simulation error %s by %.2f %%)", c.gain >= 0 ? "lowered" : "raised", 100.0 * std::abs(c.gain));
    return what + buf;
}

}  // namespace impactlab::identify::detail
