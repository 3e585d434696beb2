// Stage 6 of the fit: the held-out validation of the effects found, and the output-error refit.
#include "identify/fit/judge.hpp"

namespace impactlab::identify::detail {

namespace {

// Offers the effects found to the judge in the order they were found, in up to three passes: an effect turned
// down for too small a fall is offered again once another has been kept (validated alone, a force's per-fold
// refit absorbs the error of a partner effect not yet in the model: an even stiffness and a phase offset, say),
// and must pass the same test against the new model. Returns the force effects finally turned down for too
// small a fall, each with its index in fs.rep.effects_rejected, for the pairs.
std::vector<std::pair<std::size_t, std::size_t>> offer_in_passes(FitSession& fs, HeldOutJudge& judge, std::vector<FoundEffect>& found) {
    FitReport& rep = fs.rep;
    std::vector<std::size_t> queue(found.size());
    std::iota(queue.begin(), queue.end(), std::size_t{0});
    struct TooSmall {
        std::size_t effect, kept_before;   // index into found; effects kept when it was tried
        RejectedEffect rej;
    };
    std::vector<TooSmall> too_small;
    std::vector<std::pair<std::size_t, std::size_t>> small_final;
    std::size_t tried = 0;
    for (int pass = 0; pass < 3 && !queue.empty(); ++pass) {
        too_small.clear();
        for (std::size_t fi : queue) {
            FoundEffect& f = found[fi];
            ++tried;   // the validation's share of the fit, effect by effect
            fs.report_progress(FitStage::Validation, static_cast<double>(std::min(tried, found.size())) / static_cast<double>(found.size() + 1));
            const Verdict v = judge.try_keep(f);
            if (v == Verdict::Kept) continue;
            if (worth_retrying(v)) too_small.push_back({fi, rep.effects_found.size(), judge.rejection(f, v)});
            else rep.effects_rejected.push_back(judge.rejection(f, v));
        }
        // Again only those tried before the last effect kept (the others met the same model).
        queue.clear();
        for (const auto& t : too_small)
            if (t.kept_before < rep.effects_found.size()) queue.push_back(t.effect);
        for (auto& t : too_small)
            if (pass == 2 || t.kept_before == rep.effects_found.size()) {
                const FoundEffect& f = found[t.effect];
                if (f.evidence != Evidence::ImpactLaw && !generic_effect(f.id)) small_final.push_back({t.effect, rep.effects_rejected.size()});
                rep.effects_rejected.push_back(std::move(t.rej));
            }
    }
    return small_final;
}

// Two force effects that act together (a resistance stronger in one direction: a constant force and a Coulomb
// friction) each look too small alone, since each one's per-fold refit absorbs what it can of the other. Pairs
// of them are tried jointly: the pair must pass the same test, and each member must add beyond the noise to the
// other alone. A pair kept leaves the rejected list.
void offer_pairs(FitSession& fs, HeldOutJudge& judge, std::vector<FoundEffect>& found, std::vector<std::pair<std::size_t, std::size_t>>& small_final) {
    FitReport& rep = fs.rep;
    constexpr std::size_t kTaken = static_cast<std::size_t>(-1);
    for (std::size_t a = 0; a < small_final.size() && judge.can_judge(); ++a)
        for (std::size_t b = a + 1; b < small_final.size(); ++b) {
            FoundEffect& fa = found[small_final[a].first];
            FoundEffect& fb = found[small_final[b].first];
            if (small_final[a].second == kTaken || small_final[b].second == kTaken) continue;
            const Model& cur = judge.model();
            Model both = cur, only_a = cur, only_b = cur;
            apply_effect(both, fa.id, fa.parameters);
            apply_effect(both, fb.id, fb.parameters);
            apply_effect(only_a, fa.id, fa.parameters);
            apply_effect(only_b, fb.id, fb.parameters);
            if (judge.joint_base()) judge.refit_whole_record(both);
            if (!unphysical(both).empty()) continue;
            std::vector<double> e_both = judge.errors(both);
            const Compare c = judge.compare(judge.model_errors(), e_both);
            if (!judge.better(c)) continue;
            const Compare ca = judge.compare(judge.errors(only_b), e_both), cb = judge.compare(judge.errors(only_a), e_both);
            if (!judge.better(ca) || !judge.better(cb)) continue;
            for (const auto& [fi, ri] : {small_final[a], small_final[b]}) {
                FoundEffect& f = found[fi];
                if (judge.joint_base()) judge.take_whole(both, f);
                f.validation_gain = c.gain;
                f.validation_z = c.z;
                rep.effects_found.push_back(f);
                rep.effects_rejected[ri].id.clear();   // no longer turned down
            }
            small_final[a].second = small_final[b].second = kTaken;
            judge.set_model(std::move(both), std::move(e_both));
            judge.record(kept_name("added " + fa.id + " and " + fb.id + " together", c));
        }
    rep.effects_rejected.erase(std::remove_if(rep.effects_rejected.begin(), rep.effects_rejected.end(),
                                              [](const RejectedEffect& r) { return r.id.empty(); }),
                               rep.effects_rejected.end());
}

// Named physics before curve fits, judged on held-out data too: a named force kept over a generic term that
// explained about as much (the selection's rivals) must also predict about as well. Where the generic in its
// place is better beyond the noise, the data do not single out the named law (an x^3 spring read as an even
// stiffness): the generic stands, and no physics is named for what it follows.
void generic_for_named(FitSession& fs, HeldOutJudge& judge) {
    FitReport& rep = fs.rep;
    const std::vector<Candidate>& cands = fs.screen.cands;
    const std::vector<Group>& groups = fs.screen.groups;
    for (const Rival& rv : fs.sel.rivals) {
        if (!judge.can_judge()) break;
        const Candidate& cg = cands[groups[rv.generic].cand];
        auto found_at = [&](const std::string& id) {
            return std::find_if(rep.effects_found.begin(), rep.effects_found.end(), [&](const FoundEffect& f) { return f.id == id; });
        };
        if (found_at(cg.id) != rep.effects_found.end()) continue;
        std::vector<std::string> ids;
        bool swappable = true;
        for (std::size_t gi : rv.named) {
            const Candidate& c = cands[groups[gi].cand];
            // Only force effects kept as instances can give way (a base change or a sensor calibration is
            // no curve fit's rival in the model).
            swappable = swappable && !c.base && !c.sensor && found_at(c.id) != rep.effects_found.end();
            ids.push_back(c.id);
        }
        if (!swappable) continue;
        Model alt = judge.model();
        auto& fx = alt.p.effects;
        fx.erase(std::remove_if(fx.begin(), fx.end(),
                                [&](const EffectInstance& e) { return std::find(ids.begin(), ids.end(), e.law->id) != ids.end(); }),
                 fx.end());
        fx.push_back(rv.generic_inst);
        if (!unphysical(alt).empty()) continue;
        std::vector<double> e_alt = judge.errors(alt);
        const Compare c = judge.compare(judge.model_errors(), e_alt);
        if (!judge.better(c)) continue;
        FoundEffect g;
        g.id = cg.id;
        g.evidence = Evidence::EquationError;
        g.parameters = named(rv.generic_inst);
        g.z = rv.z;
        g.validation_gain = c.gain;
        g.validation_z = c.z;
        std::string names;
        for (const std::string& id : ids) {
            const auto it = found_at(id);
            g.explained_fraction += it->explained_fraction;
            char buf[240];
            std::snprintf(buf, sizeof buf, "the generic %s in its place predicts held-out data better (error lowered by %.2f %%, paired z = %.1f): "
                          "the data do not single out this law", cg.id.c_str(), 100.0 * c.gain, c.z);
            rep.effects_rejected.push_back({id, buf, it->validation_gain, it->validation_z, it->parameters});
            rep.effects_found.erase(it);
            names += (names.empty() ? "" : " and ") + id;
        }
        g.sentence = sentence(g.id, fs.base, g.parameters, g.sigma, fs.sc);
        rep.effects_found.push_back(g);
        rep.notes.push_back(names + " explained about as much of the equation error as the generic " + cg.id +
                            ", which predicts held-out data better: the generic stands and no physics is named for it");
        judge.set_model(std::move(alt), std::move(e_alt));
        judge.record(kept_name(names + " replaced by " + cg.id, c));
    }
}

// The judge's model becomes fs.after: never a worse model than the baseline on held-out data, its steps on the
// chain, and its kept force effects refitted on the whole record where they were fitted jointly with rejected
// ones (or a fitted baseline of a record forced by the unbalance was fitted without them).
void conclude(FitSession& fs, HeldOutJudge& judge) {
    FitReport& rep = fs.rep;
    Chain& chain = fs.chain;
    if (!rep.effects_found.empty()) {
        const Compare c = judge.compare(judge.baseline_errors(), judge.model_errors());
        if (!(c.sum_new < c.sum_cur)) {   // never a worse model than the baseline
            for (auto& f : rep.effects_found)
                rep.effects_rejected.push_back({f.id, "the model with every effect does not beat the baseline on held-out data", c.gain, c.z, f.parameters});
            rep.effects_found.clear();
            judge.reset_to_baseline();
        }
    }
    for (auto& k : judge.steps()) chain.push_back(std::move(k));
    Model cur = judge.model();
    bool refitted = false;
    // Equation error; an input-forced record keeps its output-error values when nothing was dropped.
    if ((!rep.effects_rejected.empty() || judge.refit_base()) && !rep.effects_found.empty() && (fs.prep.phi_forced || judge.refit_base())) {
        Model refit = cur;
        std::vector<Knob> knobs = found_effect_knobs(refit, fs.base, fs.screen.cands);
        if (judge.refit_base())
            for (const Knob& k : base_knobs(refit, fs.base_names, fs.prep)) knobs.push_back(k);
        if (!knobs.empty()) {
            Eigen::VectorXd R;
            Eigen::MatrixXd J;
            lm_residual(fs.prep, refit, knobs, 20, R, J);
            if (unphysical(refit).empty()) {
                cur = refit;
                refitted = true;
            }
        }
        for (auto& f : rep.effects_found) {
            f.parameters = judge.values_in(cur, f);
            if (std::any_of(fs.screen.cands.begin(), fs.screen.cands.end(), [&](const Candidate& c) { return c.base && f.id == c.id; }))
                f.sentence = sentence(f.id, fs.base, f.parameters, f.sigma, fs.sc);
        }
    }
    if (!rep.effects_found.empty() && refitted) {
        const double h = chain.empty() ? -1 : chain.back().held_out_rms_m;
        chain.push_back({"the effects refitted on the whole record", cur, rep.effects_found, h, false});
    }
    rep.validation_rms_before_m = judge.rms(judge.baseline_errors());
    rep.validation_rms_after_m = judge.rms(judge.model_errors());
    fs.after = cur;
}

}  // namespace

// The held-out validation of the effects found (stage 6 of run_fit). The record is cut into blocks of about
// an eighth of its length, alternately in fold 0 and fold 1. For each fold, the force effects' parameters are
// refitted on the equation error of the other fold's rows (an impact-law effect on the other fold's impacts),
// and the model is simulated over the fold's windows, each as long as the record's
// predictability horizon (a chaotic record cannot be judged by a long free run). Effects are tried in the
// order they were found; each must lower the summed held-out error against the model without it, with a
// paired z >= 3 over the windows and by at least 2 % of the error above the sensor noise.
void validate_effects(FitSession& fs) {
    HeldOutJudge judge(fs);
    std::vector<FoundEffect> found = std::move(fs.rep.effects_found);
    fs.rep.effects_found.clear();
    std::vector<std::pair<std::size_t, std::size_t>> small_final = offer_in_passes(fs, judge, found);
    offer_pairs(fs, judge, found, small_final);
    generic_for_named(fs, judge);
    named_against_generic(fs, judge);   // each named law kept against the generic term of its variable
    conclude(fs, judge);
}

// Stage 6b, input-forced records with a fitted baseline: the effects that passed the validation, refitted
// together with the base parameters on the free-run simulation error (which weighs the resonance the way an
// equation error at a few samples per period cannot), kept only if that predicts the held-out part better.
void output_error_stage(FitSession& fs) {
    const Prep& pr = fs.prep;
    const Model& base = fs.base;
    const std::vector<Candidate>& cands = fs.screen.cands;
    const std::vector<std::string>& base_names = fs.base_names;
    const FitOptions& o = fs.o;
    const SentenceContext& sc = fs.sc;
    FitReport& rep = fs.rep;
    Model& after = fs.after;
    Chain& chain = fs.chain;
    if (pr.phi_forced || !o.fit_baseline || rep.effects_found.empty()) return;
    // Past a chaotic record's horizon the free-run error measures no model (see the baseline stage).
    if (pr.predictability.measured && !pr.predictability.regular) return;
    Model refined = after;
    std::vector<Knob> knobs = base_knobs(refined, base_names, pr);
    for (const Knob& k : found_effect_knobs(refined, base, cands)) knobs.push_back(k);
    lm_simulation(pr, refined, knobs, 20, o.rtol);
    if (!unphysical(refined).empty() || !refinement_predicts_better(pr, refined, after, o.rtol)) {
        rep.notes.push_back("the output-error refit of the effects does not predict the tail of the record it was not fitted "
                            "to better (paired z >= 2 over the judging windows); their equation-error values are kept");
        return;
    }
    after = refined;
    rep.notes.push_back("effects refitted on the free-run simulation error (output error)");
    // The reported values are the simulation-error fit's; their uncertainties stay the equation error's.
    for (auto& f : rep.effects_found)
        for (const auto& e : after.p.effects)
            if (f.id == e.law->id) {
                f.parameters = named(e);
                f.sentence = sentence(f.id, base, f.parameters, f.sigma, sc);
            }
    chain.push_back({"the effects and the base parameters refitted on the free-run simulation error", after, rep.effects_found,
                     chain.empty() ? -1 : chain.back().held_out_rms_m, false});
}

}  // namespace impactlab::identify::detail
