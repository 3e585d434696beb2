// Stage 6, its last pass: each named law kept is held against the generic terms of its variables (its law's
// fit.rivals), on held-out data. The law stands where the generic term beside it adds nothing. Where it adds:
// the generic term replaces the law if it does as well without it (an x^4 force read as an even stiffness),
// and joins it if both are needed. Two or more laws of one variable together are a polynomial in it: they
// stand only where they predict better than the generic term alone. A law beside its own generic term
// (which spans its shape) must still add to it.
#include "identify/fit/session.hpp"

namespace impactlab::identify::detail {

namespace {
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
}  // namespace

void named_against_generic(FitSession& fs, const HeldOutJudge& judge, bool refit_base, Model& cur, std::vector<double>& e_cur,
                           Chain& kept) {
    FitReport& rep = fs.rep;
    if (e_cur.empty()) return;
    // The rivals in the order their laws were kept, each once.
    std::vector<std::string> rivals;
    for (const FoundEffect& f : rep.effects_found)
        if (const EffectLaw* law = find_effect(f.id))
            for (const char* r : law->fit.rivals)
                if (r && std::find(rivals.begin(), rivals.end(), r) == rivals.end()) rivals.push_back(r);
    auto has_rival = [](const EffectLaw* law, const std::string& r) {
        return law && std::any_of(law->fit.rivals.begin(), law->fit.rivals.end(), [&](const char* q) { return q && r == q; });
    };
    auto in_model = [&](const Model& m, const std::string& id) {   // among the effects the fit added
        return std::any_of(m.p.effects.begin() + static_cast<std::ptrdiff_t>(fs.base.p.effects.size()), m.p.effects.end(),
                           [&](const EffectInstance& e) { return e.law->id == id; });
    };
    for (const std::string& rival : rivals) {
        const auto cg = std::find_if(fs.screen.cands.begin(), fs.screen.cands.end(),
                                     [&](const Candidate& c) { return c.law && c.id == rival; });
        if (cg == fs.screen.cands.end()) continue;   // not offered for this record (no phase, say)
        // The named laws of this variable that were kept as instances.
        std::vector<std::string> ids;
        for (const FoundEffect& f : rep.effects_found) {
            const EffectLaw* law = find_effect(f.id);
            if (has_rival(law, rival) && in_model(cur, f.id)) ids.push_back(f.id);
        }
        if (ids.empty()) continue;
        std::string names;
        for (const std::string& id : ids) names += (names.empty() ? "" : " and ") + id;
        auto without_named = [&](const Model& m) {
            Model out = m;
            auto& fx = out.p.effects;
            fx.erase(std::remove_if(fx.begin() + static_cast<std::ptrdiff_t>(fs.base.p.effects.size()), fx.end(),
                                    [&](const EffectInstance& e) { return std::find(ids.begin(), ids.end(), e.law->id) != ids.end(); }),
                     fx.end());
            return out;
        };
        // Model m, fitted on the whole record, becomes the current one with held-out errors e_m, unless unphysical.
        auto adopt = [&](const Model& m, const std::vector<double>& e_m) {
            const Model fitted = fitted_whole(fs, m, refit_base);
            if (!unphysical(fitted).empty()) return false;
            cur = fitted;
            e_cur = e_m;
            return true;
        };
        auto generic_found = [&](const Compare& c) {
            FoundEffect g;
            g.id = rival;
            g.evidence = Evidence::EquationError;
            g.validation_gain = c.gain;
            g.validation_z = c.z;
            return g;
        };
        // The named laws give way to the generic term: rejected with `why`, the generic term found (or kept) in
        // their place, the model `m` fitted on the whole record.
        auto give_way = [&](const Model& m, const std::vector<double>& e_m, const Compare& c, const std::string& why, const std::string& note) {
            if (!adopt(m, e_m)) return;
            FoundEffect g = generic_found(c);
            for (const std::string& id : ids) {
                const auto it = std::find_if(rep.effects_found.begin(), rep.effects_found.end(), [&](const FoundEffect& f) { return f.id == id; });
                g.explained_fraction += it->explained_fraction;
                rep.effects_rejected.push_back({id, why, it->validation_gain, it->validation_z, it->parameters});
                rep.effects_found.erase(it);
            }
            const auto old = std::find_if(rep.effects_found.begin(), rep.effects_found.end(), [&](const FoundEffect& f) { return f.id == rival; });
            if (old != rep.effects_found.end()) {   // already there: it stays, refitted
                g.explained_fraction += old->explained_fraction;
                g.z = old->z;
                rep.effects_found.erase(old);
            }
            for (const EffectInstance& e : cur.p.effects)
                if (e.law->id == rival) g.parameters = named(e);
            g.sentence = sentence(g.id, fs.base, g.parameters, g.sigma, fs.sc);
            rep.effects_found.push_back(g);
            rep.notes.push_back(note);
            kept.push_back({names + " replaced by " + rival, cur, rep.effects_found, judge.rms(e_cur), false});
        };
        char buf[320];
        if (in_model(cur, rival)) {
            // Beside the generic term of their variable, which spans their shapes, the named laws must still add.
            const Model alone = without_named(cur);
            const std::vector<double> e_alone = judge.errors(alone);
            const Compare c = judge.compare(e_alone, e_cur);
            if (judge.better(c)) continue;
            std::snprintf(buf, sizeof buf, "beside the generic %s it adds nothing on held-out data (error %s by %.2f %%, paired z = %.1f): "
                          "the data show a shape, not this law", rival.c_str(), c.gain >= 0 ? "lowered" : "raised", 100.0 * std::abs(c.gain), c.z);
            give_way(alone, e_alone, judge.compare(e_cur, e_alone), buf,
                     names + " added nothing beside the generic " + rival + " on held-out data: the generic stands and no physics is named for it");
            continue;
        }
        const EffectInstance g0 = start_instance(*cg, cur, fs.prep, 1.0);
        Model both = cur, alone = without_named(cur);
        both.p.effects.push_back(g0);
        alone.p.effects.push_back(g0);
        const std::vector<double> e_both = judge.errors(both);
        const Compare added = judge.compare(e_cur, e_both);
        // One law whose rival adds nothing beside it stands; only otherwise is the rival alone worth judging.
        if (!judge.better(added) && ids.size() < 2) continue;
        const std::vector<double> e_alone = judge.errors(alone);
        const Compare replaced = judge.compare(e_cur, e_alone);
        if (judge.better(added)) {
            if (judge.better(judge.compare(e_alone, e_both))) {
                // Both are needed: the named laws, and a shape of their variable beyond them.
                if (!adopt(both, e_both)) continue;
                FoundEffect g = generic_found(added);
                g.parameters = named(cur.p.effects.back());
                g.sentence = sentence(g.id, fs.base, g.parameters, g.sigma, fs.sc);
                rep.effects_found.push_back(g);
                rep.notes.push_back("a smooth force of the same variable beside " + names + " predicts held-out data better: " + rival +
                                    " added for the shape they leave");
                kept.push_back({"added " + rival + " beside " + names, cur, rep.effects_found, judge.rms(e_cur), false});
                continue;
            }
            // The generic term alone does as well as both: the data do not single out the named laws.
            if (!(replaced.sum_new < replaced.sum_cur)) continue;
            std::snprintf(buf, sizeof buf, "the generic %s beside it predicts held-out data better (error lowered by %.2f %%, paired z = %.1f) "
                          "and does as well without it: the data show a shape this law does not have", rival.c_str(), 100.0 * added.gain, added.z);
            give_way(alone, e_alone, replaced, buf,
                     names + " left a shape in its variable that the generic " + rival +
                         " follows on held-out data, with or without it: the generic stands and no physics is named for it");
            continue;
        }
        // Several laws of one variable fitted together are a polynomial in it: named only where they predict
        // held-out data better than one smooth force of that variable.
        if (!judge.better(judge.compare(e_alone, e_cur))) {
            std::snprintf(buf, sizeof buf, "with the other laws of its variable it predicts held-out data no better than the generic %s alone "
                          "(error %s by %.2f %% in its place): the data show a shape, not these laws", rival.c_str(),
                          replaced.gain >= 0 ? "lowered" : "raised", 100.0 * std::abs(replaced.gain));
            give_way(alone, e_alone, replaced, buf,
                     names + " together predict held-out data no better than the generic " + rival +
                         ": the generic stands and no physics is named for them");
        }
    }
}

}  // namespace impactlab::identify::detail
