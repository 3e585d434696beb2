// Stage 6 of the fit: the held-out validation of the effects found, and the output-error refit.
#include <map>

#include "identify/fit/session.hpp"

namespace impactlab::identify::detail {

// The held-out validation of the effects found (stage 6 of run_fit). The record is cut into blocks of about
// an eighth of its length, alternately in fold 0 and fold 1. For each fold, the force effects' parameters are
// refitted on the equation error of the other fold's rows (an impact-law effect on the other fold's impacts),
// and the model is simulated over the fold's windows, each as long as the record's
// predictability horizon (a chaotic record cannot be judged by a long free run). Effects are tried in the
// order they were found; each must lower the summed held-out error against the model without it, with a
// paired z >= 3 over the windows and by at least 2 % of the error above the sensor noise.
void validate_effects(FitSession& fs) {
    const Prep& pr = fs.prep;
    const Model& base = fs.base;
    const std::vector<Candidate>& cands = fs.screen.cands;
    const FitOptions& o = fs.o;
    const std::vector<std::string>& base_names = fs.base_names;
    const SentenceContext& sc = fs.sc;
    FitReport& rep = fs.rep;
    Model& after = fs.after;
    Chain& chain = fs.chain;
    // A fitted baseline of a record forced by the unbalance is refitted with the effects (per fold, and on the
    // whole record at the end): base parameters fitted without an effect have absorbed what they could of it
    // (a spring rate bent by a missing even stiffness), and those values beside the effect's make neither
    // model. An input-forced record keeps its output-error baseline (refined on the free-run error).
    const bool refit_base = o.fit_baseline && pr.phi_forced && !base_names.empty();
    // The horizon of the best model at hand (the baseline with every effect found): a wrong baseline's error
    // grows from its own fault, not from the record's instability. An unphysical candidate falls back to the
    // baseline.
    const HeldOutSplit sp = held_out_split(pr, unphysical(after).empty() ? after : base, o.rtol);
    rep.horizon_growth = sp.hz.growth;
    rep.horizon_periods = sp.periods;
    const auto& wins = sp.wins;
    rep.validation_windows = wins.size();
    const std::array<Prep, 2>& fold_pr = sp.fold_pr;
    const std::array<std::vector<std::size_t>, 2>& fold_wins = sp.fold_wins;
    auto fold_of = [&](std::size_t i) { return sp.fold_of(pr, i); };

    // The force effects of m (and the base, where refitted) refitted on the equation error of `on`'s rows; the
    // knobs, and the instance each belongs to (SIZE_MAX: a base parameter). Empty: nothing to refit there.
    auto refit_effects = [&](const Prep& on, Model& m, std::vector<std::size_t>& owner, Eigen::VectorXd& R, Eigen::MatrixXd& J) {
        owner.clear();
        std::vector<Knob> knobs = found_effect_knobs(m, base, cands, &owner);
        if (refit_base)
            for (const Knob& k : base_knobs(m, base_names, pr)) {
                knobs.push_back(k);
                owner.push_back(SIZE_MAX);
            }
        if (knobs.empty() || on.rows.size() < 20) return std::vector<Knob>{};
        lm_residual(on, m, knobs, 15, R, J);
        return knobs;
    };
    // Held-out SSE of each window: fold f's windows simulated with model_for[f], its force effects refitted
    // on the other fold's rows (the impact-law effects come refitted on the other fold's impacts).
    auto held_out_folds = [&](const std::array<Model, 2>& model_for) {
        std::vector<double> e(wins.size(), INFINITY);
        for (std::size_t f = 0; f < 2; ++f) {
            Model mf = model_for[f];
            std::vector<std::size_t> owner;
            Eigen::VectorXd R;
            Eigen::MatrixXd J;
            refit_effects(fold_pr[1 - f], mf, owner, R, J);
            std::vector<std::pair<std::size_t, std::size_t>> sub;
            for (std::size_t w : fold_wins[f]) sub.push_back(wins[w]);
            const std::vector<double> ef = window_sse(pr, mf, sub, o.refine_shooting, o.rtol);
            for (std::size_t k = 0; k < sub.size(); ++k) e[fold_wins[f][k]] = ef[k];
        }
        return e;
    };
    auto held_out = [&](const Model& m) { return held_out_folds({m, m}); };
    // The effects' values on the whole record's equation error, with the knobs each fold refits.
    const bool joint_base = o.fit_baseline && !base_names.empty() && !refit_base;
    // Their standard errors (HAC) by effect, from the same fit.
    std::map<std::string, std::vector<std::pair<std::string, double>>> whole_sigma;
    auto whole_record = [&](Model& m) {
        std::vector<std::size_t> owner;
        Eigen::VectorXd R;
        Eigen::MatrixXd J;
        const std::vector<Knob> knobs = refit_effects(pr, m, owner, R, J);
        if (knobs.empty()) return;
        const Eigen::MatrixXd V = hac_cov(-J, R, fs.hac_lag);
        whole_sigma.clear();
        for (std::size_t k = 0; k < knobs.size(); ++k)
            if (owner[k] != SIZE_MAX && V.allFinite())
                whole_sigma[m.p.effects[owner[k]].law->id].emplace_back(
                    knobs[k].name, std::sqrt(std::max(0.0, V(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(k)))));
    };
    auto values_in = [&](const Model& m, const FoundEffect& f) {
        for (const auto& c : cands)
            if (c.base && f.id == c.id) return std::vector<std::pair<std::string, double>>{{c.param, base_change(c, m, base)}};
        for (auto e = m.p.effects.rbegin(); e != m.p.effects.rend(); ++e)   // the last instance of its law
            if (f.id == e->law->id) return named(*e);
        return f.parameters;
    };
    // An effect's values and standard errors from the last whole-record refit, and its sentence with them.
    auto take_whole = [&](const Model& m, FoundEffect& f) {
        f.parameters = values_in(m, f);
        if (const auto it = whole_sigma.find(f.id); it != whole_sigma.end()) f.sigma = it->second;
        f.sentence = sentence(f.id, base, f.parameters, f.sigma, sc);
    };
    // Impacts by fold (of their entry sample), for refitting an impact-law effect on one fold only.
    std::array<std::vector<char>, 2> impacts_in;
    for (std::size_t f = 0; f < 2; ++f) {
        impacts_in[f].assign(pr.impacts.size(), 0);
        for (std::size_t k = 0; k < pr.impacts.size(); ++k) impacts_in[f][k] = fold_of(pr.impacts[k].i_first) == static_cast<int>(f);
    }
    // Reversals away from the bumper by fold, for refitting an end stop on one fold only.
    std::array<std::vector<char>, 2> strays_in;
    for (std::size_t f = 0; f < 2; ++f) {
        strays_in[f].assign(pr.stray.size(), 0);
        for (std::size_t k = 0; k < pr.stray.size(); ++k) strays_in[f][k] = fold_of(pr.stray[k].i_first) == static_cast<int>(f);
    }
    std::size_t samples = 0;
    for (const auto& [a, b] : wins) samples += b - a + 1;
    auto compare = [&](const std::vector<double>& cur, const std::vector<double>& cand) { return compare_held_out(pr, wins, cur, cand); };

    std::vector<FoundEffect> found = std::move(rep.effects_found);
    rep.effects_found.clear();
    Model cur = base;
    const std::vector<double> e_base = wins.size() >= 12 ? held_out(base) : std::vector<double>{};
    std::vector<double> e_cur = e_base;
    std::size_t tried = 0;
    // An effect turned down for too small a fall is tried again once another has been kept: validated alone, a
    // force's per-fold refit absorbs the error of a partner effect not yet in the model (an even stiffness
    // and a phase offset, say) and its fall looks small. It must pass the same test against the new model.
    std::vector<std::size_t> queue(found.size());
    std::iota(queue.begin(), queue.end(), std::size_t{0});
    struct TooSmall {
        std::size_t effect, kept_before;   // index into found; effects kept when it was tried
        RejectedEffect rej;
    };
    std::vector<TooSmall> too_small;
    // The held-out shooting RMS of a model's windows (their SSE summed).
    auto total = [&](const std::vector<double>& e) {
        double s = 0;
        for (double v : e) s += std::isfinite(v) ? v : 0.0;
        return samples ? std::sqrt(s / static_cast<double>(samples)) : 0.0;
    };
    Chain kept;   // the model after each effect kept, in order, with its held-out RMS
    // A kept step's name in the chain, with the held-out fall that kept it.
    auto step_name = [](const std::string& what, const Compare& c) {
        char buf[96];
        std::snprintf(buf, sizeof buf, " (held-out simulation error %s by %.2f %%)", c.gain >= 0 ? "lowered" : "raised", 100.0 * std::abs(c.gain));
        return what + buf;
    };
    // Effects finally turned down for too small a fall (index into found, into effects_rejected).
    constexpr std::size_t kTaken = static_cast<std::size_t>(-1);
    std::vector<std::pair<std::size_t, std::size_t>> small_final;
    auto f_ok_for_pair = [](const FoundEffect& f) { return f.evidence != Evidence::ImpactLaw && !generic_effect(f.id); };
    for (int pass = 0; pass < 3 && !queue.empty(); ++pass) {
        too_small.clear();
        for (std::size_t fi : queue) {
            FoundEffect& f = found[fi];
            ++tried;   // the validation's share of the fit, effect by effect
            fs.report_progress(FitStage::Validation, static_cast<double>(std::min(tried, found.size())) / static_cast<double>(found.size() + 1));
            RejectedEffect rej{f.id, "", 0, 0, f.parameters};
            if (e_cur.empty()) {
                rej.reason = "too few windows to validate it on held-out data";
                rep.effects_rejected.push_back(std::move(rej));
                continue;
            }
            Model cand = cur;
            if (f.evidence == Evidence::ImpactLaw && pr.impacts.size() >= 3) {
                // Refitted on every impact against the model it joins (the stage fitted it against the model
                // with every effect found, some of which may have gone): the model kept is the model validated.
                const std::vector<char> all(pr.impacts.size(), 1);
                if (f.id == "bumper_offset") f.parameters = {{"dx", fit_bumper_shift(pr, cand, all, o.rtol, 0.05 * pr.sigma_x)}};
                else apply_effect(cand, f.id, f.parameters = refit_impact_law(pr, cur, f, all));
                f.sentence = sentence(f.id, cur, f.parameters, f.sigma, sc);
                rej.parameters = f.parameters;
                // A shift of the flat tops must still stand out as the stage required.
                const double dx = f.parameters.front().second, se = f.sigma.empty() ? 0.0 : f.sigma.front().second;
                if (f.id == "bumper_offset" && !(std::abs(dx) >= o.z_threshold * se && std::abs(dx) > 2.0 * pr.sigma_x + 1e-7)) {
                    char buf[200];
                    std::snprintf(buf, sizeof buf, "refitted against the model it joins, the shift is %.3g +/- %.2g m: not significant", dx, se);
                    rej.reason = buf;
                    too_small.push_back({fi, rep.effects_found.size(), std::move(rej)});
                    continue;
                }
            } else if (f.evidence == Evidence::StrayImpacts) {
                // Refitted against the model it joins, as an impact law is.
                double se = 0;
                const auto values = end_stop_values(pr, cur, {}, o.rtol, &se);
                if (!values.empty()) {
                    f.parameters = values;
                    f.sigma.front().second = se;
                }
                f.sentence = end_stop_sentence(pr, cur, f, sc);
                rej.parameters = f.parameters;
                apply_effect(cand, f.id, f.parameters);
            } else {
                apply_effect(cand, f.id, f.parameters);
                // Its values came from the joint fit that moved the base parameters too, which this model does not
                // take: refitted here as the folds refit it, so the model kept is the model validated.
                if (joint_base && f.evidence == Evidence::EquationError) {
                    whole_record(cand);
                    take_whole(cand, f);
                    rej.parameters = f.parameters;
                }
            }
            const std::string why = unphysical(cand);
            if (!why.empty()) {
                rej.reason = "unphysical: " + why;
                rep.effects_rejected.push_back(std::move(rej));
                continue;
            }
            std::vector<double> e_new;
            if (f.evidence == Evidence::ImpactLaw) {
                // Refitted on the other fold's impacts, for each fold in turn.
                std::array<Model, 2> per_fold{cur, cur};
                for (std::size_t ff = 0; ff < 2; ++ff) {
                    const std::vector<char>& use = impacts_in[1 - ff];
                    // A fold with fewer than three impacts cannot refit the law: there the whole record's values
                    // stand (the windows are still held out).
                    if (std::count(use.begin(), use.end(), 1) < 3) per_fold[ff] = cand;
                    else if (f.id == "bumper_offset") fit_bumper_shift(pr, per_fold[ff], use, o.rtol, 0.05 * pr.sigma_x);
                    else apply_effect(per_fold[ff], f.id, refit_impact_law(pr, cur, f, use));
                }
                e_new = held_out_folds(per_fold);
            } else if (f.evidence == Evidence::StrayImpacts) {
                // The stop fitted to the other fold's reversals, for each fold in turn.
                std::array<Model, 2> per_fold{cand, cand};
                for (std::size_t ff = 0; ff < 2; ++ff) {
                    const auto values = end_stop_values(pr, cur, strays_in[1 - ff], o.rtol);
                    if (values.empty()) continue;   // too few there: the whole record's values stand
                    per_fold[ff] = cur;
                    apply_effect(per_fold[ff], f.id, values);
                }
                e_new = held_out_folds(per_fold);
            } else {
                e_new = held_out(cand);
            }
            const Compare c = compare(e_cur, e_new);
            f.validation_gain = rej.validation_gain = c.gain;
            f.validation_z = rej.validation_z = c.z;
            if (!better_beyond_noise(pr, wins, c)) {
                char buf[200];
                std::snprintf(buf, sizeof buf, "held-out simulation error %s by %.2f %% (paired z = %.1f over %zu windows): not better beyond the noise",
                              c.gain >= 0 ? "lowered" : "raised", 100.0 * std::abs(c.gain), c.z, wins.size());
                rej.reason = buf;
                too_small.push_back({fi, rep.effects_found.size(), std::move(rej)});
                continue;
            }
            cur = std::move(cand);
            e_cur = e_new;
            if (joint_base && f.evidence == Evidence::EquationError)   // the effects kept before were refitted beside it
                for (auto& g : rep.effects_found)
                    if (g.evidence == Evidence::EquationError) take_whole(cur, g);
            rep.effects_found.push_back(f);
            kept.push_back({step_name("added " + f.id, c), cur, rep.effects_found, total(e_cur), false});
        }
        // Again only those tried before the last effect kept (the others met the same model).
        queue.clear();
        for (const auto& t : too_small)
            if (t.kept_before < rep.effects_found.size()) queue.push_back(t.effect);
        for (auto& t : too_small)
            if (pass == 2 || t.kept_before == rep.effects_found.size()) {
                if (f_ok_for_pair(found[t.effect])) small_final.push_back({t.effect, rep.effects_rejected.size()});
                rep.effects_rejected.push_back(std::move(t.rej));
            }
    }
    // Two force effects that act together (a resistance stronger in one direction: a constant force and a
    // Coulomb friction) each look too small alone, since each one's per-fold refit absorbs what it can of
    // the other. Pairs of them are tried jointly: the pair must pass the same test, and each member must
    // add beyond the noise to the other alone.
    for (std::size_t a = 0; a < small_final.size() && !e_cur.empty(); ++a)
        for (std::size_t b = a + 1; b < small_final.size(); ++b) {
            FoundEffect& fa = found[small_final[a].first];
            FoundEffect& fb = found[small_final[b].first];
            if (small_final[a].second == kTaken || small_final[b].second == kTaken) continue;
            Model both = cur, only_a = cur, only_b = cur;
            apply_effect(both, fa.id, fa.parameters);
            apply_effect(both, fb.id, fb.parameters);
            apply_effect(only_a, fa.id, fa.parameters);
            apply_effect(only_b, fb.id, fb.parameters);
            if (joint_base) whole_record(both);
            if (!unphysical(both).empty()) continue;
            const std::vector<double> e_both = held_out(both);
            const Compare c = compare(e_cur, e_both);
            if (!better_beyond_noise(pr, wins, c)) continue;
            const Compare ca = compare(held_out(only_b), e_both), cb = compare(held_out(only_a), e_both);
            if (!better_beyond_noise(pr, wins, ca) || !better_beyond_noise(pr, wins, cb)) continue;
            cur = std::move(both);
            e_cur = e_both;
            for (const auto& [fi, ri] : {small_final[a], small_final[b]}) {
                FoundEffect& f = found[fi];
                if (joint_base) take_whole(cur, f);
                f.validation_gain = c.gain;
                f.validation_z = c.z;
                rep.effects_found.push_back(f);
                rep.effects_rejected[ri].id.clear();   // no longer turned down
            }
            small_final[a].second = small_final[b].second = kTaken;
            kept.push_back({step_name("added " + fa.id + " and " + fb.id + " together", c), cur, rep.effects_found, total(e_cur), false});
        }
    rep.effects_rejected.erase(std::remove_if(rep.effects_rejected.begin(), rep.effects_rejected.end(),
                                              [](const RejectedEffect& r) { return r.id.empty(); }),
                               rep.effects_rejected.end());
    // Named physics before curve fits, judged on held-out data too: a named force kept over a generic term
    // that explained about as much must also predict about as well. Where the generic in its place is better
    // beyond the noise, the data do not single out the named law (an x^3 spring read as an even stiffness):
    // the generic stands, and no physics is named for what it follows.
    const std::vector<Group>& groups = fs.screen.groups;
    for (const Rival& rv : fs.sel.rivals) {
        if (e_cur.empty()) break;
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
        Model alt = cur;
        auto& fx = alt.p.effects;
        fx.erase(std::remove_if(fx.begin(), fx.end(),
                                [&](const EffectInstance& e) { return std::find(ids.begin(), ids.end(), e.law->id) != ids.end(); }),
                 fx.end());
        fx.push_back(rv.generic_inst);
        if (!unphysical(alt).empty()) continue;
        const std::vector<double> e_alt = held_out(alt);
        const Compare c = compare(e_cur, e_alt);
        if (!better_beyond_noise(pr, wins, c)) continue;
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
        g.sentence = sentence(g.id, base, g.parameters, g.sigma, sc);
        rep.effects_found.push_back(g);
        rep.notes.push_back(names + " explained about as much of the equation error as the generic " + cg.id +
                            ", which predicts held-out data better: the generic stands and no physics is named for it");
        cur = std::move(alt);
        e_cur = e_alt;
        kept.push_back({step_name(names + " replaced by " + cg.id, c), cur, rep.effects_found, total(e_cur), false});
    }
    // Each named law kept against the generic term of its variable.
    named_against_generic(fs, HeldOutJudge{held_out, compare, [&](const Compare& c) { return better_beyond_noise(pr, wins, c); }, total},
                          refit_base, cur, e_cur, kept);
    if (!rep.effects_found.empty()) {
        const Compare c = compare(e_base, e_cur);
        if (!(c.sum_new < c.sum_cur)) {   // never a worse model than the baseline
            for (auto& f : rep.effects_found)
                rep.effects_rejected.push_back({f.id, "the model with every effect does not beat the baseline on held-out data", c.gain, c.z, f.parameters});
            rep.effects_found.clear();
            cur = base;
            e_cur = e_base;
            kept.clear();
        }
    }
    for (auto& k : kept) chain.push_back(std::move(k));
    bool refitted = false;
    // The kept force effects were fitted jointly with the rejected ones (and a fitted baseline of a record
    // forced by the unbalance without them): refit them on the whole record (equation error; an input-forced
    // record keeps its output-error values when nothing was dropped).
    if ((!rep.effects_rejected.empty() || refit_base) && !rep.effects_found.empty() && pr.phi_forced) {
        Model refit = cur;
        std::vector<Knob> knobs = found_effect_knobs(refit, base, cands);
        if (refit_base)
            for (const Knob& k : base_knobs(refit, base_names, pr)) knobs.push_back(k);
        if (!knobs.empty()) {
            Eigen::VectorXd R;
            Eigen::MatrixXd J;
            lm_residual(pr, refit, knobs, 20, R, J);
            if (unphysical(refit).empty()) {
                cur = refit;
                refitted = true;
            }
        }
        for (auto& f : rep.effects_found) {
            f.parameters = values_in(cur, f);
            if (std::any_of(cands.begin(), cands.end(), [&](const Candidate& c) { return c.base && f.id == c.id; }))
                f.sentence = sentence(f.id, base, f.parameters, f.sigma, sc);
        }
    }
    if (!rep.effects_found.empty() && refitted) {
        const double h = chain.empty() ? -1 : chain.back().held_out_rms_m;
        chain.push_back({"the effects refitted on the whole record", cur, rep.effects_found, h, false});
    }
    rep.validation_rms_before_m = total(e_base);
    rep.validation_rms_after_m = total(e_cur);
    after = cur;
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
