// Stage 4 of the fit: the model with the chosen effects.
#include "identify/fit/session.hpp"

namespace impactlab::identify::detail {

// Stage 4: the model with the chosen effects. Linear estimates from the screening, then a joint nonlinear
// refinement of their parameters (and the fitted base parameters) on the equation error, with HAC
// uncertainties; an effect whose significance does not survive the joint fit is dropped and the rest
// refitted. An input-forced record then refines them on the free-run simulation error where that predicts
// the held-out part better; a sensor effect the impacts' flat tops contradict goes. The effects found are
// appended to rep.effects_found; returns the model with them.
void refit_stage(FitSession& fs) {
    const Prep& pr = fs.prep;
    const Model& base = fs.base;
    const Screen& screen = fs.screen;
    Selection sel = fs.sel;
    const std::vector<std::string>& base_names = fs.base_names;
    const FitOptions& o = fs.o;
    const int hac_lag = fs.hac_lag;
    const double in0 = fs.in0;
    const SentenceContext& sc = fs.sc;
    FitReport& rep = fs.rep;
    const std::vector<Candidate>& cands = screen.cands;
    const std::vector<Group>& groups = screen.groups;
    const std::vector<int>& base_cols = screen.base_cols;
    const Folds& folds = screen.folds;
    std::vector<std::size_t>& chosen = sel.chosen;
    std::vector<double>& step_gain = sel.step_gain;
    const double in_base = sel.in_base;
    std::vector<double> pw;
    Model& after = fs.after;
    after = base;
    std::vector<FoundEffect> force_found;
    constexpr std::size_t kNone = static_cast<std::size_t>(-1);
    std::vector<std::size_t> inst_of;   // per chosen effect: its instance in after.p.effects (kNone: base-changing)
    for (;;) {
        after = base;
        {
            std::vector<int> cols = base_cols;
            for (std::size_t gi : chosen) cols.insert(cols.end(), groups[gi].cols.begin(), groups[gi].cols.end());
            double cv, in;
            Eigen::VectorXd beta;
            cv_sse(folds, cols, cv, in, &beta);
            std::size_t pos = base_cols.size();   // base parameters: refitted below
            inst_of.clear();
            for (std::size_t gi : chosen) {
                const Group& g = groups[gi];
                const Candidate& c = cands[g.cand];
                if (c.base) {   // a base-changing candidate moves its base parameter
                    apply_effect(after, c.id, {{c.param, std::clamp(beta[static_cast<Eigen::Index>(pos++)], c.lo, c.hi)}});
                    inst_of.push_back(kNone);
                    continue;
                }
                EffectInstance inst = g.inst;
                for (int li : c.linear)
                    inst.p[static_cast<std::size_t>(c.free[static_cast<std::size_t>(li)])] += beta[static_cast<Eigen::Index>(pos++)];
                inst_of.push_back(after.p.effects.size());
                after.p.effects.push_back(inst);
            }
        }
        std::vector<Knob> knobs;
        if (o.fit_baseline) knobs = base_knobs(after, base_names, pr);
        const std::size_t n_base_knobs = knobs.size();
        for (std::size_t k = 0; k < chosen.size(); ++k) {
            const Candidate& c = cands[groups[chosen[k]].cand];
            if (c.base) knobs.push_back(base_change_knob(c, after, base));
            else effect_knobs(c, after.p.effects[inst_of[k]], knobs);
        }
        Eigen::VectorXd R1;
        Eigen::MatrixXd J1;
        if (knobs.empty()) residual(pr, after, R1, pw);
        else lm_residual(pr, after, knobs, 30, R1, J1);

        // Uncertainties (HAC) and significance of each found effect at the joint fit.
        std::vector<double> knob_sigma(knobs.size(), 0.0);
        Eigen::MatrixXd V;
        if (!knobs.empty()) {
            V = hac_cov(-J1, R1, hac_lag);
            for (std::size_t k = 0; k < knobs.size(); ++k)
                knob_sigma[k] = std::sqrt(std::max(0.0, V(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(k))));
        }
        force_found.clear();
        std::size_t kk = n_base_knobs;
        for (std::size_t k = 0; k < chosen.size(); ++k) {
            const Candidate& c = cands[groups[chosen[k]].cand];
            FoundEffect f;
            f.id = c.id;
            f.evidence = Evidence::EquationError;
            f.explained_fraction = step_gain[k] * in_base / std::max(in0, 1e-300);
            if (c.base) {   // one parameter, its null value the base model's
                const double d = base_change(c, after, base);
                f.parameters = {{c.param, d}};
                f.sigma = {{c.param, knob_sigma[kk]}};
                f.z = std::min(std::abs(d) / std::max(knob_sigma[kk], 1e-300),
                               group_z_dss(J1, R1, {static_cast<int>(kk)}, Eigen::VectorXd::Constant(1, d), 2 * hac_lag));
                ++kk;
                f.sentence = sentence(c.id, base, f.parameters, f.sigma, sc);
                force_found.push_back(std::move(f));
                continue;
            }
            const EffectInstance& inst = after.p.effects[inst_of[k]];
            f.parameters = named(inst);
            std::vector<int> sub;
            for (std::size_t li = 0; li < c.free.size(); ++li, ++kk) {
                f.sigma.emplace_back(c.law->names[static_cast<std::size_t>(c.free[li])], knob_sigma[kk]);
                sub.push_back(static_cast<int>(kk));
            }
            // Wald z over the effect's parameters, against their null values.
            const auto q = static_cast<Eigen::Index>(sub.size());
            Eigen::MatrixXd Vs(q, q);
            Eigen::VectorXd d(q);
            const EffectInstance null_inst = start_instance(c, base, pr, c.starts.empty() ? 0.0 : inst.p[1]);
            for (Eigen::Index i = 0; i < q; ++i) {
                const auto pi = static_cast<std::size_t>(c.free[static_cast<std::size_t>(i)]);
                d[i] = inst.p[pi] - null_inst.p[pi];
                for (Eigen::Index j = 0; j < q; ++j) Vs(i, j) = V(sub[static_cast<std::size_t>(i)], sub[static_cast<std::size_t>(j)]);
            }
            if (c.law->fit.test_first_only) {   // a shape parameter (a speed scale) has no null value: test the first alone
                f.z = std::abs(inst.p[0]) / std::max(knob_sigma[static_cast<std::size_t>(sub[0])], 1e-300);
                f.z = std::min(f.z, group_z_dss(J1, R1, {sub[0]}, d.head(1), 2 * hac_lag));
            } else {
                for (Eigen::Index i = 0; i < q; ++i) Vs(i, i) += 1e-12 * Vs(i, i) + 1e-300;
                const double W = d.dot(Vs.ldlt().solve(d));
                f.z = std::min(std::isfinite(W) ? chi2_to_z(W, static_cast<int>(q)) : 0.0, group_z_dss(J1, R1, sub, d, 2 * hac_lag));
            }
            f.sentence = sentence(c.id, base, f.parameters, f.sigma, sc);
            force_found.push_back(std::move(f));
        }
        // Backward elimination: the weakest effect below the threshold goes, the rest are refitted.
        std::size_t weakest = chosen.size();
        for (std::size_t k = 0; k < force_found.size(); ++k)
            if (force_found[k].z < o.z_threshold && (weakest == chosen.size() || force_found[k].z < force_found[weakest].z)) weakest = k;
        if (weakest == chosen.size()) break;
        for (auto& cs : rep.candidates)
            if (cs.id == force_found[weakest].id) cs.selected = false;
        rep.notes.push_back("dropped " + force_found[weakest].id + ": its significance fell to z = " +
                            std::to_string(force_found[weakest].z) + " in the joint fit");
        chosen.erase(chosen.begin() + static_cast<long>(weakest));
        step_gain.erase(step_gain.begin() + static_cast<long>(weakest));
        // The shares the rest explain, in the order chosen, without the one gone: a share measured beside it
        // would leave what it took unclaimed (or claimed twice where two terms shared it).
        std::vector<int> cols = base_cols;
        double cv = 0, prev = 0;
        cv_sse(folds, cols, cv, prev);
        for (std::size_t k = 0; k < chosen.size(); ++k) {
            cols.insert(cols.end(), groups[chosen[k]].cols.begin(), groups[chosen[k]].cols.end());
            double in = 0;
            cv_sse(folds, cols, cv, in);
            step_gain[k] = (prev - in) / in_base;
            prev = in;
        }
    }
    // A sensor effect moves the measured bumper level too: if the impacts' flat tops contradict it, it is an
    // artefact of the free-flight fit and goes (the impact stage then sees the level as it is).
    if (after.bumper() && pr.impacts.size() >= 3) {
        for (std::size_t k = 0; k < force_found.size(); ++k) {
            const EffectLaw* law = find_effect(force_found[k].id);
            if (!law || law->kind != EffectKind::Sensor) continue;
            // The flat tops measured against the same impacts simulated with the sensor effect in the model (so
            // a compliant bumper's apparent penetration is on both sides).
            const PredictedImpacts pred = predict_impacts(pr, after, o.rtol);
            std::vector<double> lev;
            for (std::size_t i = 0; i < pr.impacts.size(); ++i)
                if (pred.ok[i]) lev.push_back(pr.impacts[i].level - pred.obs[i].level);
            if (lev.size() < 3) continue;
            // The level's own uncertainty from the effect's: its first parameter moved by its standard error.
            const double s0 = force_found[k].sigma.empty() ? 0.0 : force_found[k].sigma[0].second;
            double level_sigma = 0;
            std::array<double, kMaxLawParams> moved{};
            for (const auto& e : after.p.effects)
                if (e.law == law) {
                    moved = e.p;
                    moved[0] += s0;
                    level_sigma = std::abs(law->measure(moved.data(), after.p.xI) - law->measure(e.p.data(), after.p.xI));
                }
            const double miss = median(lev);
            if (std::abs(miss) > std::max(5.0 * level_sigma, 5.0 * pr.sigma_x + 1e-6)) {
                rep.notes.push_back("dropped " + force_found[k].id + ": the impacts' flat tops put the bumper where the uncorrected sensor does");
                for (auto& cs : rep.candidates)
                    if (cs.id == force_found[k].id) cs.selected = false;
                for (auto it = after.p.effects.begin(); it != after.p.effects.end(); ++it)
                    if (it->law == law) {
                        after.p.effects.erase(it);
                        break;
                    }
                force_found.erase(force_found.begin() + static_cast<long>(k));
                break;
            }
        }
    }
    for (auto& f : force_found) rep.effects_found.push_back(std::move(f));
}

}  // namespace impactlab::identify::detail
