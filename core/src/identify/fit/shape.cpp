// Stage 6, its last pass: each named law kept is held against the generic terms of its variables (its law's
// fit.rivals), on held-out data. The law stands where the generic term beside it adds nothing. Where it adds:
// the generic term replaces the law if it does as well without it (an x^4 force read as an even stiffness),
// and joins it if both are needed. Two or more laws of one variable together are a polynomial in it: they
// stand only where they predict better than the generic term alone. A law beside its own generic term
// (which spans its shape) must still add to it. Where held-out shooting cannot tell shapes apart, the whole
// record's equation error does: a law is a finding only where its shape is resolved there (equation_z,
// sibling_alike: told from the other laws of its variable and, for a power law, from the next power of its
// symmetry); otherwise it gives way to the generic term, or stays marked as a force of its size (always so
// against the nameless next power, unless the generic term predicts held-out data better).
#include <cmath>
#include <optional>
#include <string>

#include "effects/law_helpers.hpp"
#include "identify/fit/judge.hpp"

namespace impactlab::identify::detail {

namespace {
// The least share of the law's remaining equation error a generic term beside it must take to show another shape.
constexpr double kOtherShapeShare = 0.02;
// The model's force effects fitted on the whole record's equation error (a generic term enters at zero).
Model fitted_whole(const FitSession& fs, const Model& m, bool refit_base) {
    Model out = m;
    std::vector<Knob> knobs = found_effect_knobs(out, fs.base, fs.screen.cands);
    if (refit_base)
        for (const Knob& k : base_knobs(out, fs.base_names, fs.prep)) knobs.push_back(k);
    if (!knobs.empty()) {
        Eigen::VectorXd R;
        Eigen::MatrixXd J;
        lm_residual(fs.prep, out, knobs, 20, R, J);
    }
    return out;
}

// How far each group of the model's added effects stands out of the whole record's equation error, all of
// them refitted together (the base too where the stage refits it): the z of the sum of squares a group's
// linear parameters remove, from their null values, with the others refitted (group_z_dss); with `sse`, the
// sum of squares of the equation error all of them leave.
std::vector<double> equation_z(const FitSession& fs, const Model& m, bool refit_base, const std::vector<std::vector<std::string>>& groups,
                               double* sse = nullptr, const std::vector<Candidate>* with = nullptr) {
    const std::vector<Candidate>& cands = with ? *with : fs.screen.cands;
    Model out = m;
    std::vector<std::size_t> owner;
    std::vector<Knob> knobs = found_effect_knobs(out, fs.base, cands, &owner);
    if (refit_base)
        for (const Knob& k : base_knobs(out, fs.base_names, fs.prep)) {
            knobs.push_back(k);
            owner.push_back(SIZE_MAX);
        }
    std::vector<double> z(groups.size(), 0.0);
    Eigen::VectorXd R;
    Eigen::MatrixXd J;
    lm_residual(fs.prep, out, knobs, 20, R, J);
    if (!R.allFinite() || !J.allFinite() || J.cols() != static_cast<Eigen::Index>(knobs.size())) return z;
    if (sse) *sse = R.squaredNorm();
    // Each effect's null instance, once (a start takes the data's quantiles).
    std::vector<std::optional<EffectInstance>> nulls(out.p.effects.size());
    for (std::size_t gi = 0; gi < groups.size(); ++gi) {
        std::vector<int> sub;
        std::vector<double> delta;
        for (std::size_t k = 0; k < knobs.size(); ++k) {
            if (owner[k] == SIZE_MAX) continue;
            const EffectInstance& e = out.p.effects[owner[k]];
            if (std::find(groups[gi].begin(), groups[gi].end(), e.law->id) == groups[gi].end()) continue;
            const auto c = std::find_if(cands.begin(), cands.end(), [&](const Candidate& q) { return q.law == e.law; });
            if (c == cands.end()) continue;
            const auto i = static_cast<int>(knobs[k].value - e.p.data());
            const bool linear = std::any_of(c->linear.begin(), c->linear.end(), [&](int li) { return c->free[static_cast<std::size_t>(li)] == i; });
            if (!linear) continue;
            sub.push_back(static_cast<int>(k));
            std::optional<EffectInstance>& null = nulls[owner[k]];
            if (!null) null = start_instance(*c, out, fs.prep, 0.0);
            delta.push_back(*knobs[k].value - null->p[static_cast<std::size_t>(i)]);
        }
        if (!sub.empty())
            z[gi] = group_z_dss(J, R, sub, Eigen::Map<const Eigen::VectorXd>(delta.data(), static_cast<Eigen::Index>(delta.size())),
                                2 * fs.hac_lag);
    }
    return z;
}

// The next power of a power law's variable, F = -c s|s|^(n-1) (odd) or -c |s|^n (even), s = x or v; p: c, n,
// odd (1/0), of v (1/0). Never in the registry: it lives only in the models shape.cpp tests a law beside.
EffectForce next_power(const double* p, const ForceContext& ctx) {
    const bool of_v = p[3] > 0.5, odd = p[2] > 0.5;
    const double s = of_v ? ctx.v : ctx.x, a = std::abs(s), sg = s >= 0 ? 1.0 : -1.0;
    const double an = std::pow(a, p[1]), dan = p[1] * std::pow(a, p[1] - 1.0);
    const double F = -p[0] * (odd ? sg * an : an), dF = -p[0] * (odd ? dan : sg * dan);
    return of_v ? EffectForce{F, 0.0, dF, 0.0} : EffectForce{F, dF, 0.0, 0.0};
}
const EffectLaw& next_power_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"next_power", "the next power of a power law's variable", {"c", "n", "odd", "of_v", nullptr},
                    {"", "", "", "", nullptr}, {0.0, 0.0, 0.0, 0.0}, next_power};
        l.fit = effects::hint({0}, {1.0});
        return l;
    }();
    return law;
}
// Its name as a shape: "v^3", "x^3 |x|", "|x|^3".
std::string power_name(int n, bool of_v, bool odd) {
    const std::string s = of_v ? "v" : "x";
    if (!odd) return n % 2 == 0 ? s + "^" + std::to_string(n) : "|" + s + "|^" + std::to_string(n);
    return n % 2 == 1 ? s + "^" + std::to_string(n) : s + "^" + std::to_string(n - 1) + " |" + s + "|";
}

// What law `id` is not told from: a law of the library, or (nameless) the next power of its own shape.
struct Alike {
    std::string from;
    double z = 0.0;
    bool nameless = false;
};
// A law of the same variable (one sharing a rival) that law `id` is not told from in the whole record's
// equation error: fitted beside it, `id` adds nothing out of the noise. Among the three that explained most
// alone in the screening; empty when `id` stands beside each.
Alike sibling_alike(const FitSession& fs, const Model& cur, bool refit_base, const std::string& id) {
    const EffectLaw* law = find_effect(id);
    if (!law) return {};
    auto shares_rival = [&](const EffectLaw* other) {
        for (const char* a : law->fit.rivals)
            for (const char* b : other->fit.rivals)
                if (a && b && std::string(a) == b) return true;
        return false;
    };
    std::vector<std::pair<double, const Candidate*>> sib;
    for (const Candidate& c : fs.screen.cands) {
        if (!c.law || c.generic || c.law == law || !shares_rival(c.law)) continue;
        if (std::any_of(cur.p.effects.begin(), cur.p.effects.end(), [&](const EffectInstance& e) { return e.law == c.law; })) continue;
        const auto sc = std::find_if(fs.rep.candidates.begin(), fs.rep.candidates.end(), [&](const CandidateScore& q) { return q.id == c.id; });
        if (sc != fs.rep.candidates.end() && sc->cv_gain > 0) sib.push_back({sc->cv_gain, &c});
    }
    std::sort(sib.begin(), sib.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    if (sib.size() > 3) sib.resize(3);
    for (const auto& [gain, c] : sib) {
        Model m = cur;
        m.p.effects.push_back(start_instance(*c, cur, fs.prep, c->starts.empty() ? 0.0 : c->starts.front()));
        const double z = equation_z(fs, m, refit_base, {{id}})[0];
        if (z < fs.o.z_threshold) return {c->id, z, false};
    }
    // A power law is told from the next power of its symmetry too (v|v| from v^3, x^3 from x^3 |x|): over the
    // range one motion spans, a neighbouring power is the closest shape the library has no law for.
    const EffectFitHint& h = law->fit;
    if (h.power > 0) {
        std::vector<Candidate> cands = fs.screen.cands;
        cands.push_back(candidate_of(next_power_law()));
        Model m = cur;
        m.p.effects.push_back({&next_power_law(), {0.0, h.power + 1.0, h.power_odd ? 1.0 : 0.0, h.power_of_v ? 1.0 : 0.0}});
        const double z = equation_z(fs, m, refit_base, {{id}}, nullptr, &cands)[0];
        if (z < fs.o.z_threshold) return {"a force of " + power_name(h.power + 1, h.power_of_v, h.power_odd), z, true};
    }
    return {};
}
// Whether law `law` names `r` among its rivals (the generic terms of its variables).
bool has_rival(const EffectLaw* law, const std::string& r) {
    return law && std::any_of(law->fit.rivals.begin(), law->fit.rivals.end(), [&](const char* q) { return q && r == q; });
}

// The named laws the judge's model keeps that share one rival (a generic term), held against it.
class RivalCase {
public:
    RivalCase(FitSession& fs, HeldOutJudge& judge, const std::string& rival, const Candidate& cg, std::vector<std::string> ids)
        : fs_(fs), rep_(fs.rep), judge_(judge), cur_(judge.model()), e_cur_(judge.model_errors()), refit_base_(judge.refit_base()),
          rival_(rival), cg_(cg), ids_(std::move(ids)) {
        for (const std::string& id : ids_) names_ += (names_.empty() ? "" : " and ") + id;
    }

    void decide() {
        if (in_model(cur_, rival_)) {
            beside_generic();
            return;
        }
        const EffectInstance g0 = start_instance(cg_, cur_, fs_.prep, 1.0);
        Model both = cur_, alone = without_named(cur_);
        both.p.effects.push_back(g0);
        alone.p.effects.push_back(g0);
        const std::vector<double> e_both = judge_.errors(both);
        const Compare added = judge_.compare(e_cur_, e_both);
        if (!judge_.better(added) && ids_.size() < 2) by_equation_error(both, alone);
        else by_held_out(both, e_both, alone, added);
    }

    // Whether law `id` is among the effects the fit added to m.
    static bool in_model(const FitSession& fs, const Model& m, const std::string& id) {
        return std::any_of(m.p.effects.begin() + static_cast<std::ptrdiff_t>(fs.base.p.effects.size()), m.p.effects.end(),
                           [&](const EffectInstance& e) { return e.law->id == id; });
    }

private:
    bool in_model(const Model& m, const std::string& id) const { return in_model(fs_, m, id); }

    Model without_named(const Model& m) const {
        Model out = m;
        auto& fx = out.p.effects;
        fx.erase(std::remove_if(fx.begin() + static_cast<std::ptrdiff_t>(fs_.base.p.effects.size()), fx.end(),
                                [&](const EffectInstance& e) { return std::find(ids_.begin(), ids_.end(), e.law->id) != ids_.end(); }),
                 fx.end());
        return out;
    }
    // Model m, fitted on the whole record, becomes the current one with held-out errors e_m, unless unphysical.
    bool adopt(const Model& m, const std::vector<double>& e_m) {
        const Model fitted = fitted_whole(fs_, m, refit_base_);
        if (!unphysical(fitted).empty()) return false;
        judge_.set_model(fitted, e_m);
        return true;
    }
    FoundEffect generic_found(const Compare& c) const {
        FoundEffect g;
        g.id = rival_;
        g.evidence = Evidence::EquationError;
        g.validation_gain = c.gain;
        g.validation_z = c.z;
        return g;
    }
    // The named laws give way to the generic term: rejected with `why`, the generic term found (or kept) in
    // their place, the model `m` fitted on the whole record.
    void give_way(const Model& m, const std::vector<double>& e_m, const Compare& c, const std::string& why, const std::string& note) {
        // The generic term that would come in their place must itself lower the held-out error against the model
        // without either: a force of this variable admitted early may be needed no more beside a later effect of
        // another (a sensor's x^2 read as a force of x, then the v^2 it differentiates into found as a force of v).
        if (!in_model(cur_, rival_)) {
            const Model neither = without_named(cur_);
            const std::vector<double> e_neither = judge_.errors(neither);
            const Compare g = judge_.compare(e_neither, e_m);
            if (!(g.sum_new < g.sum_cur)) {
                char buf[200];
                std::snprintf(buf, sizeof buf,
                              "; nor does the generic %s in its place lower the held-out error of the model "
                              "without either (raised by %.2f %%, paired z = %.1f): no force of this variable is shown",
                              rival_.c_str(), 100.0 * std::abs(g.gain), g.z);
                drop(neither, e_neither, why + buf);
                return;
            }
        }
        if (!adopt(m, e_m)) return;
        FoundEffect g = generic_found(c);
        g.explained_fraction += reject_named(why);
        const auto old = std::find_if(rep_.effects_found.begin(), rep_.effects_found.end(), [&](const FoundEffect& f) { return f.id == rival_; });
        if (old != rep_.effects_found.end()) {   // already there: it stays, refitted
            g.explained_fraction += old->explained_fraction;
            g.z = old->z;
            rep_.effects_found.erase(old);
        }
        for (const EffectInstance& e : cur_.p.effects)
            if (e.law->id == rival_) g.parameters = named(e);
        g.sentence = sentence(g.id, fs_.base, g.parameters, g.sigma, fs_.sc);
        rep_.effects_found.push_back(g);
        rep_.notes.push_back(note);
        judge_.record(names_ + " replaced by " + rival_);
    }
    // The named laws move from the effects found to those turned down, with `why`; returns the share of the
    // residual they had explained.
    double reject_named(const std::string& why) {
        double explained = 0;
        for (const std::string& id : ids_) {
            const auto it =
                std::find_if(rep_.effects_found.begin(), rep_.effects_found.end(), [&](const FoundEffect& f) { return f.id == id; });
            explained += it->explained_fraction;
            rep_.effects_rejected.push_back({id, why, it->validation_gain, it->validation_z, it->parameters});
            rep_.effects_found.erase(it);
        }
        return explained;
    }
    // The named laws leave the model, and no generic term comes in their place.
    void drop(const Model& m, const std::vector<double>& e_m, const std::string& why) {
        if (!adopt(m, e_m)) return;
        reject_named(why);
        rep_.notes.push_back(names_ + ": neither it nor the generic " + rival_ +
                             " in its place predicts held-out data better than the model without them: removed, and no physics is named");
        judge_.record(names_ + " removed");
    }
    // A law that stays in the model although the data do not tell its shape from `from`: a force of its
    // size, no finding of its law (in the report and in every step the final gate may go back to).
    void mark_unresolved(const std::string& id, const std::string& from, const std::string& why) {
        auto mark = [&](std::vector<FoundEffect>& found) {
            for (FoundEffect& f : found)
                if (f.id == id) f.not_told_from = from;
        };
        mark(rep_.effects_found);
        for (ChainStep& st : judge_.steps()) mark(st.found);
        rep_.notes.push_back(id + " " + why + ", but the data do not tell its shape from " + from + ": it stays as a force of its size, and its law is no finding");
    }
    // Laws that stand (beside the generic term, or together) are still findings only where the data tell
    // each from the other laws of its variable.
    void siblings_resolved(const std::string& why) {
        for (const std::string& id : ids_) {
            const std::string sibling = sibling_alike(fs_, cur_, refit_base_, id).from;
            if (!sibling.empty()) mark_unresolved(id, sibling, why);
        }
    }

    // The generic term is in the model already: beside it, which spans their shapes, the named laws must still add.
    void beside_generic() {
        char buf[320];
        const Model alone = without_named(cur_);
        const std::vector<double> e_alone = judge_.errors(alone);
        const Compare c = judge_.compare(e_alone, e_cur_);
        if (judge_.better(c)) {
            siblings_resolved("adds to the generic " + rival_ + " on held-out data");
            return;
        }
        std::snprintf(buf, sizeof buf, "beside the generic %s it adds nothing on held-out data (error %s by %.2f %%, paired z = %.1f): "
                      "the data show a shape, not this law", rival_.c_str(), c.gain >= 0 ? "lowered" : "raised", 100.0 * std::abs(c.gain), c.z);
        give_way(alone, e_alone, judge_.compare(e_cur_, e_alone), buf,
                 names_ + " added nothing beside the generic " + rival_ + " on held-out data: the generic stands and no physics is named for it");
    }

    // The held-out shooting cannot tell one law from the generic term beside it; the whole record's equation
    // error, with the law refitted beside the generic term, can: the law stands unless the generic term stands
    // out there and the law adds nothing beside it (x^5 read as a cubic spring), and held-out data prefer it
    // no more.
    void by_equation_error(const Model& both, const Model& alone) {
        char buf[320];
        double sse_both = NAN;
        const std::vector<double> z = equation_z(fs_, both, refit_base_, {{rival_}, ids_}, &sse_both);
        // And by a share that matters: a long clean record puts a generic term out of the noise on the
        // smallest remainder (a sensor offset explaining 97 % leaves one), not only on another shape.
        auto share_taken = [&] {
            Eigen::VectorXd R_cur;
            std::vector<double> pw;
            residual(fs_.prep, cur_, R_cur, pw);
            return (R_cur.squaredNorm() - sse_both) / R_cur.squaredNorm();
        };
        const bool other_shape = z[0] >= fs_.o.z_threshold && z[1] < fs_.o.z_threshold && share_taken() >= kOtherShapeShare;
        // Nor is a shape resolved that a law of the same variable explains as well (v|v| against v on a
        // faint force of v): the data show a force of that variable, not this law.
        const Alike alike = other_shape ? Alike{} : sibling_alike(fs_, cur_, refit_base_, ids_[0]);
        const std::string& sibling = alike.from;
        const double z_sib = alike.z;
        if (!other_shape && sibling.empty()) return;
        const std::vector<double> e_alone = judge_.errors(alone);
        if (judge_.better(judge_.compare(e_alone, e_cur_))) {   // held-out data prefer the law: it stays, unresolved
            mark_unresolved(ids_[0], other_shape ? "the generic " + rival_ : sibling, "predicts held-out data better than the generic " + rival_);
            return;
        }
        // Against a shape with no name, a named law is preferred to a curve fit that does no better: it
        // stays, unresolved, unless the generic term predicts held-out data better. Against a named law it
        // cannot be told from, it stays where the generic term in its place would predict held-out data worse
        // (a linear spring's constant force and sensor offset): never a worse model for want of a name. (A
        // shape the whole record's equation error shows beyond the law is decided below.)
        const Compare in_place = judge_.compare(e_cur_, e_alone);
        if (!judge_.better(in_place) && (alike.nameless || (!other_shape && !(in_place.sum_new < in_place.sum_cur)))) {
            mark_unresolved(ids_[0], sibling,
                            alike.nameless ? "predicts held-out data as well as the generic " + rival_
                                           : "predicts held-out data better than the generic " + rival_ + " in its place");
            return;
        }
        if (other_shape) {
            std::snprintf(buf, sizeof buf, "beside it the generic %s stands out of the whole record's equation error (z = %.1f) and it adds "
                          "nothing beside the generic (z = %.1f): the data show a shape this law does not have", rival_.c_str(), z[0], z[1]);
            give_way(alone, e_alone, in_place, buf,
                     names_ + " left a shape in its variable that the generic " + rival_ + " follows in the whole record's equation error, where " +
                         names_ + " adds nothing beside it: the generic stands and no physics is named for it");
        } else {
            std::snprintf(buf, sizeof buf, "beside %s it adds nothing out of the noise of the whole record's equation error (z = %.1f): "
                          "the data do not resolve its shape", sibling.c_str(), z_sib);
            give_way(alone, e_alone, in_place, buf,
                     "the data do not tell " + names_ + " from " + sibling + ": a force of the same variable whose shape they do not resolve, "
                         "so the generic " + rival_ + " stands and no physics is named for it");
        }
    }

    // Held-out data decide: the generic term added beside the laws (both), or in their place (alone).
    void by_held_out(const Model& both, const std::vector<double>& e_both, const Model& alone, const Compare& added) {
        char buf[320];
        const std::vector<double> e_alone = judge_.errors(alone);
        const Compare replaced = judge_.compare(e_cur_, e_alone);
        if (judge_.better(added)) {
            if (judge_.better(judge_.compare(e_alone, e_both))) {
                // Both are needed: the named laws, and a shape of their variable beyond them.
                if (!adopt(both, e_both)) return;
                FoundEffect g = generic_found(added);
                g.parameters = named(cur_.p.effects.back());
                g.sentence = sentence(g.id, fs_.base, g.parameters, g.sigma, fs_.sc);
                rep_.effects_found.push_back(g);
                rep_.notes.push_back("a smooth force of the same variable beside " + names_ + " predicts held-out data better: " + rival_ +
                                     " added for the shape they leave");
                judge_.record("added " + rival_ + " beside " + names_);
                siblings_resolved("stands beside the generic " + rival_);
                return;
            }
            // The generic term alone does as well as both: the data do not single out the named laws.
            if (!(replaced.sum_new < replaced.sum_cur)) return;
            std::snprintf(buf, sizeof buf, "the generic %s beside it predicts held-out data better (error lowered by %.2f %%, paired z = %.1f) "
                          "and does as well without it: the data show a shape this law does not have", rival_.c_str(), 100.0 * added.gain, added.z);
            give_way(alone, e_alone, replaced, buf,
                     names_ + " left a shape in its variable that the generic " + rival_ +
                         " follows on held-out data, with or without it: the generic stands and no physics is named for it");
            return;
        }
        // Several laws of one variable fitted together are a polynomial in it: named only where they predict
        // held-out data better than one smooth force of that variable.
        if (!judge_.better(judge_.compare(e_alone, e_cur_))) {
            std::snprintf(buf, sizeof buf, "with the other laws of its variable it predicts held-out data no better than the generic %s alone "
                          "(error %s by %.2f %% in its place): the data show a shape, not these laws", rival_.c_str(),
                          replaced.gain >= 0 ? "lowered" : "raised", 100.0 * std::abs(replaced.gain));
            give_way(alone, e_alone, replaced, buf,
                     names_ + " together predict held-out data no better than the generic " + rival_ +
                         ": the generic stands and no physics is named for them");
        } else {
            siblings_resolved("predicts held-out data better, with " + names_ + ", than the generic " + rival_);
        }
    }

    FitSession& fs_;
    FitReport& rep_;
    HeldOutJudge& judge_;
    const Model& cur_;                     // the judge's model, which follows every change kept
    const std::vector<double>& e_cur_;
    const bool refit_base_;
    const std::string& rival_;
    const Candidate& cg_;
    const std::vector<std::string> ids_;   // the named laws of the rival's variable kept as instances
    std::string names_;                    // their ids, joined by "and"
};
}  // namespace

void named_against_generic(FitSession& fs, HeldOutJudge& judge) {
    FitReport& rep = fs.rep;
    if (!judge.can_judge()) return;
    // The rivals in the order their laws were kept, each once.
    std::vector<std::string> rivals;
    for (const FoundEffect& f : rep.effects_found)
        if (const EffectLaw* law = find_effect(f.id))
            for (const char* r : law->fit.rivals)
                if (r && std::find(rivals.begin(), rivals.end(), r) == rivals.end()) rivals.push_back(r);
    for (const std::string& rival : rivals) {
        const auto cg = std::find_if(fs.screen.cands.begin(), fs.screen.cands.end(),
                                     [&](const Candidate& c) { return c.law && c.id == rival; });
        if (cg == fs.screen.cands.end()) continue;   // not offered for this record (no phase, say)
        // The named laws of this variable that were kept as instances.
        std::vector<std::string> ids;
        for (const FoundEffect& f : rep.effects_found) {
            const EffectLaw* law = find_effect(f.id);
            if (has_rival(law, rival) && RivalCase::in_model(fs, judge.model(), f.id)) ids.push_back(f.id);
        }
        if (ids.empty()) continue;
        RivalCase(fs, judge, rival, *cg, std::move(ids)).decide();
    }
}

}  // namespace impactlab::identify::detail
