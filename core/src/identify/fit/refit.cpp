// Stage 4 of the fit: the model with the chosen effects.
#include "identify/fit/session.hpp"

namespace impactlab::identify::detail {

namespace {

constexpr std::size_t kNone = static_cast<std::size_t>(-1);

// The model with the chosen effects at their linear estimates from the screening's columns; per chosen
// effect, its instance in after.p.effects (kNone: a base-changing one).
std::vector<std::size_t> linear_estimates(const FitSession& fs, const std::vector<std::size_t>& chosen, Model& after) {
    const Screen& screen = fs.screen;
    const std::vector<Group>& groups = screen.groups;
    std::vector<std::size_t> inst_of;
    std::vector<int> cols = screen.base_cols;
    for (std::size_t gi : chosen) cols.insert(cols.end(), groups[gi].cols.begin(), groups[gi].cols.end());
    double cv, in;
    Eigen::VectorXd beta;
    cv_sse(screen.folds, cols, cv, in, &beta);
    std::size_t pos = screen.base_cols.size();   // base parameters: refitted below
    for (std::size_t gi : chosen) {
        const Group& g = groups[gi];
        const Candidate& c = screen.cands[g.cand];
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
    return inst_of;
}

// The joint nonlinear fit of the effects (and the fitted base parameters, whose knobs come first) on the
// equation error: its residual, Jacobian, and the knobs' HAC covariance and standard errors.
struct JointFit {
    std::size_t n_base_knobs = 0;
    Eigen::VectorXd R1;
    Eigen::MatrixXd J1, V;
    std::vector<double> knob_sigma;
};
JointFit joint_fit(const FitSession& fs, const std::vector<std::size_t>& chosen, const std::vector<std::size_t>& inst_of, Model& after,
                   std::vector<double>& pw) {
    const std::vector<Candidate>& cands = fs.screen.cands;
    const std::vector<Group>& groups = fs.screen.groups;
    JointFit jf;
    std::vector<Knob> knobs;
    if (fs.o.fit_baseline) knobs = base_knobs(after, fs.base_names, fs.prep);
    jf.n_base_knobs = knobs.size();
    for (std::size_t k = 0; k < chosen.size(); ++k) {
        const Candidate& c = cands[groups[chosen[k]].cand];
        if (c.base) knobs.push_back(base_change_knob(c, after, fs.base));
        else effect_knobs(c, after.p.effects[inst_of[k]], knobs);
    }
    if (knobs.empty()) residual(fs.prep, after, jf.R1, pw);
    else lm_residual(fs.prep, after, knobs, 30, jf.R1, jf.J1);
    // Uncertainties (HAC) and significance of each found effect at the joint fit.
    jf.knob_sigma.assign(knobs.size(), 0.0);
    if (!knobs.empty()) {
        jf.V = hac_cov(-jf.J1, jf.R1, fs.hac_lag);
        for (std::size_t k = 0; k < knobs.size(); ++k)
            jf.knob_sigma[k] = std::sqrt(std::max(0.0, jf.V(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(k))));
    }
    return jf;
}

// Each chosen effect at the joint fit: its values, standard errors and significance (a Wald z over its
// parameters against their null values, bounded by the rise of the sum of squares without them).
std::vector<FoundEffect> effects_at(const FitSession& fs, const Selection& sel, const Model& after, const std::vector<std::size_t>& inst_of,
                                    const JointFit& jf) {
    const std::vector<Candidate>& cands = fs.screen.cands;
    const std::vector<Group>& groups = fs.screen.groups;
    const Model& base = fs.base;
    const int hac_lag = fs.hac_lag;
    const std::vector<double>& knob_sigma = jf.knob_sigma;
    std::vector<FoundEffect> force_found;
    std::size_t kk = jf.n_base_knobs;
    for (std::size_t k = 0; k < sel.chosen.size(); ++k) {
        const Candidate& c = cands[groups[sel.chosen[k]].cand];
        FoundEffect f;
        f.id = c.id;
        f.evidence = Evidence::EquationError;
        f.explained_fraction = sel.step_gain[k] * sel.in_base / std::max(fs.in0, 1e-300);
        if (c.base) {   // one parameter, its null value the base model's
            const double d = base_change(c, after, base);
            f.parameters = {{c.param, d}};
            f.sigma = {{c.param, knob_sigma[kk]}};
            f.z = std::min(std::abs(d) / std::max(knob_sigma[kk], 1e-300),
                           group_z_dss(jf.J1, jf.R1, {static_cast<int>(kk)}, Eigen::VectorXd::Constant(1, d), 2 * hac_lag));
            ++kk;
            f.sentence = sentence(c.id, base, f.parameters, f.sigma, fs.sc);
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
        const EffectInstance null_inst = start_instance(c, base, fs.prep, c.starts.empty() ? 0.0 : inst.p[1]);
        for (Eigen::Index i = 0; i < q; ++i) {
            const auto pi = static_cast<std::size_t>(c.free[static_cast<std::size_t>(i)]);
            d[i] = inst.p[pi] - null_inst.p[pi];
            for (Eigen::Index j = 0; j < q; ++j) Vs(i, j) = jf.V(sub[static_cast<std::size_t>(i)], sub[static_cast<std::size_t>(j)]);
        }
        if (c.law->fit.test_first_only) {   // a shape parameter (a speed scale) has no null value: test the first alone
            f.z = std::abs(inst.p[0]) / std::max(knob_sigma[static_cast<std::size_t>(sub[0])], 1e-300);
            f.z = std::min(f.z, group_z_dss(jf.J1, jf.R1, {sub[0]}, d.head(1), 2 * hac_lag));
        } else {
            for (Eigen::Index i = 0; i < q; ++i) Vs(i, i) += 1e-12 * Vs(i, i) + 1e-300;
            const double W = d.dot(Vs.ldlt().solve(d));
            f.z = std::min(std::isfinite(W) ? chi2_to_z(W, static_cast<int>(q)) : 0.0, group_z_dss(jf.J1, jf.R1, sub, d, 2 * hac_lag));
        }
        f.sentence = sentence(c.id, base, f.parameters, f.sigma, fs.sc);
        force_found.push_back(std::move(f));
    }
    return force_found;
}

// Backward elimination: the weakest effect below the threshold goes from sel (true), the rest to be refitted;
// false where every one stands.
bool drop_weakest(FitSession& fs, Selection& sel, const std::vector<FoundEffect>& force_found) {
    const Screen& screen = fs.screen;
    const std::vector<Group>& groups = screen.groups;
    FitReport& rep = fs.rep;
    std::vector<std::size_t>& chosen = sel.chosen;
    std::vector<double>& step_gain = sel.step_gain;
    std::size_t weakest = chosen.size();
    for (std::size_t k = 0; k < force_found.size(); ++k)
        if (force_found[k].z < fs.o.z_threshold && (weakest == chosen.size() || force_found[k].z < force_found[weakest].z)) weakest = k;
    if (weakest == chosen.size()) return false;
    for (auto& cs : rep.candidates)
        if (cs.id == force_found[weakest].id) cs.selected = false;
    rep.notes.push_back("dropped " + force_found[weakest].id + ": its significance fell to z = " +
                        std::to_string(force_found[weakest].z) + " in the joint fit");
    chosen.erase(chosen.begin() + static_cast<long>(weakest));
    step_gain.erase(step_gain.begin() + static_cast<long>(weakest));
    // The shares the rest explain, in the order chosen, without the one gone: a share measured beside it
    // would leave what it took unclaimed (or claimed twice where two terms shared it).
    std::vector<int> cols = screen.base_cols;
    double cv = 0, prev = 0;
    cv_sse(screen.folds, cols, cv, prev);
    for (std::size_t k = 0; k < chosen.size(); ++k) {
        cols.insert(cols.end(), groups[chosen[k]].cols.begin(), groups[chosen[k]].cols.end());
        double in = 0;
        cv_sse(screen.folds, cols, cv, in);
        step_gain[k] = (prev - in) / sel.in_base;
        prev = in;
    }
    return true;
}

// A sensor effect moves the measured bumper level too: if the impacts' flat tops contradict it, it is an
// artefact of the free-flight fit and goes (the impact stage then sees the level as it is).
void drop_contradicted_sensor(FitSession& fs, Model& after, std::vector<FoundEffect>& force_found) {
    const Prep& pr = fs.prep;
    FitReport& rep = fs.rep;
    if (!after.bumper() || pr.impacts.size() < 3) return;
    for (std::size_t k = 0; k < force_found.size(); ++k) {
        const EffectLaw* law = find_effect(force_found[k].id);
        if (!law || law->kind != EffectKind::Sensor) continue;
        // The flat tops measured against the same impacts simulated with the sensor effect in the model (so
        // a compliant bumper's apparent penetration is on both sides).
        const PredictedImpacts pred = predict_impacts(pr, after, fs.o.rtol);
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

}  // namespace

// Stage 4: the model with the chosen effects. Linear estimates from the screening, then a joint nonlinear
// refinement of their parameters (and the fitted base parameters) on the equation error, with HAC
// uncertainties; an effect whose significance does not survive the joint fit is dropped and the rest
// refitted. (An input-forced record then refines them on the free-run simulation error where that predicts
// the held-out part better: stage 6b.) A sensor effect the impacts' flat tops contradict goes. The effects found
// are appended to rep.effects_found; fs.after gets the model with them.
void refit_stage(FitSession& fs) {
    Selection sel = fs.sel;
    std::vector<double> pw;
    Model& after = fs.after;
    after = fs.base;
    std::vector<FoundEffect> force_found;
    for (;;) {
        after = fs.base;
        const std::vector<std::size_t> inst_of = linear_estimates(fs, sel.chosen, after);
        const JointFit jf = joint_fit(fs, sel.chosen, inst_of, after, pw);
        force_found = effects_at(fs, sel, after, inst_of, jf);
        if (!drop_weakest(fs, sel, force_found)) break;
    }
    drop_contradicted_sensor(fs, after, force_found);
    for (auto& f : force_found) fs.rep.effects_found.push_back(std::move(f));
}

}  // namespace impactlab::identify::detail
