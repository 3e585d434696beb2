// Stages 7 and 8 of the fit: the final gate, the errors before and after, the plots' material and the verdict.
#include "identify/fit/session.hpp"

namespace impactlab::identify::detail {

namespace {

// The gate's outcome: the printed errors of the model given (pg), of the baseline the effects are judged against
// (pb, where ref_base > 0) and of the model written (pa).
struct Gated {
    PrintedErrors pg, pb, pa;
    std::size_t ref_base = 0;
};

// Stage 7, the final gate: walks the chain back from its last step until the model is not worse than the
// model given (and the baseline kept) on any printed error beyond its scatter; fs.after gets that step's model,
// the report its effects (those undone turned down, with the reason).
Gated final_gate(FitSession& fs, const Prep* ptp) {
    const Prep& pr = fs.prep;
    const Chain& chain = fs.chain;
    const FitOptions& o = fs.o;
    FitReport& rep = fs.rep;
    const double judge = rep.horizon_periods;
    Gated gd;
    gd.pg = printed_errors(pr, chain.front().model, o, judge, ptp);   // the model given, or the baseline for mere starting values
    const PrintedErrors& pg = gd.pg;
    PrintedErrors& pb = gd.pb;
    PrintedErrors& pa = gd.pa;
    // The baseline the effects are judged against too: the last baseline step not worse than the model given
    // (a fitted baseline is a change like any other). An effect must not make the model worse than either.
    std::size_t last_base = 0;
    while (last_base + 1 < chain.size() && chain[last_base + 1].baseline) ++last_base;
    std::size_t& ref_base = gd.ref_base;
    // A reference fitted to this record's equation error is judged there in-sample: any other base parameters
    // read worse on it, by a margin the smoother's bias sets, not the model (a free decay's k, biased 0.2 % by
    // the smoothed acceleration, undid the refinement that brought its 10-period shooting error to the noise).
    // Between baseline steps, each already preferred on held-out trajectories, the trajectories judge.
    PrintedErrors pg_base = pg;
    if (chain.front().equation_error_fit)
        for (PrintedError& e : pg_base.e)
            if (e.name == kErrResidual) e.decides = false;
    for (std::size_t j = last_base; j > 0; --j) {
        pb = printed_errors(pr, chain[j].model, o, judge, ptp);
        const GateCheck g = gate_check(pg_base, pb);
        if (!g.worse) {
            ref_base = j;
            break;
        }
        rep.gate.push_back("undone: " + chain[j].what + ", since against the model given the " + g.why);
    }
    std::size_t kept_step = chain.size() - 1;
    // Effects fitted on a baseline the gate undid go with it.
    if (ref_base != last_base && kept_step > last_base) {
        rep.gate.push_back("undone: every effect, since they were fitted on top of the baseline undone");
        kept_step = last_base;
    }
    for (; kept_step > last_base; --kept_step) {
        pa = printed_errors(pr, chain[kept_step].model, o, judge, ptp);
        GateCheck g = gate_check(pg, pa);
        std::string against = "the model given";
        if (!g.worse && ref_base > 0) {
            g = gate_check(pb, pa);
            against = "the fitted baseline";
        }
        if (!g.worse) {
            rep.gate_within = g.within;
            if (ref_base > 0)
                for (const auto& w : gate_check(pg, pa).within) rep.gate_within.push_back(w + " (against the model given)");
            break;
        }
        rep.gate.push_back("undone: " + chain[kept_step].what + ", since against " + against + " the " + g.why);
    }
    if (kept_step <= last_base) {
        kept_step = ref_base;
        pa = ref_base > 0 ? pb : pg;
    }
    if (ref_base > 0) {
        rep.baseline_column = true;
        rep.baseline_step = chain[ref_base].what;
    }
    const ChainStep& chosen = chain[kept_step];
    fs.after = chosen.model;
    // Effects the gate undid are reported as turned down, with the reason.
    for (const FoundEffect& f : chain.back().found) {
        const bool kept = std::any_of(chosen.found.begin(), chosen.found.end(), [&](const FoundEffect& c) { return c.id == f.id; });
        if (!kept)
            rep.effects_rejected.push_back({f.id, "undone by the final gate: the model with it is worse than the model given (" +
                                                      (rep.gate.empty() ? std::string("?") : rep.gate.back()) + ")",
                                            f.validation_gain, f.validation_z, f.parameters});
    }
    rep.effects_found = chosen.found;
    // The held-out RMS of the model written: the baseline's where no effect stays, else its step's.
    if (kept_step <= last_base) rep.validation_rms_after_m = rep.validation_rms_before_m;
    else if (chosen.held_out_rms_m >= 0) rep.validation_rms_after_m = chosen.held_out_rms_m;
    if (kept_step == 0 && rep.baseline == Baseline::Fit && !fs.model0.placeholder) rep.baseline = Baseline::Fixed;
    rep.gate_passed = chosen.what;
    return gd;
}

// One model's printed errors as the report's summary.
void fill_errors(FitReport& rep, const Prep& pr, const PrintedErrors& p, ErrorSummary& e) {
    const double judge = rep.horizon_periods;
    e.residual_rms_N = p.value(kErrResidual);
    e.shooting_rms_1_m = p.value(kErrShoot1);
    e.shooting_rms_10_m = p.value(kErrShoot10);
    e.shooting_rms_judge_m = judge == 1.0 ? e.shooting_rms_1_m : judge == 10.0 ? e.shooting_rms_10_m : p.value(kErrShootJudge);
    e.impact = impact_error(pr, p.pred);
    if (const PrintedError* d = p.find(kErrDiagram)) {   // its units are the omega bins
        e.diagram_bins = d->num.size();
        e.diagram_per_bin.clear();
        for (std::size_t k = 0; k < d->num.size(); ++k) e.diagram_per_bin.emplace_back(d->keys[k], d->num[k]);
        e.diagram_distance_m = d->num.empty() ? -1.0 : d->value();
    }
    e.simulation_rms_m = p.find(kErrFree) ? p.value(kErrFree) : -1;
    e.test_simulation_rms_m = p.find(kErrTestFree) ? p.value(kErrTestFree) : -1;
    e.test_shooting_rms_m = p.find(kErrTestShoot) ? p.value(kErrTestShoot) : -1;
    if (p.attractor.ok) {
        e.attractor_x_w1 = AttractorStats::mean(p.attractor.hist_x);
        e.attractor_v_w1 = AttractorStats::mean(p.attractor.hist_v);
        e.attractor_spectrum_db = p.attractor.spectrum_db.empty() ? -1.0 : AttractorStats::mean(p.attractor.spectrum_db);
        if (p.attractor.wells_found) {
            e.attractor_wells_per_s = p.attractor.rate_sim;
            rep.data_well_changes_per_s = p.attractor.rate_data;
        }
    }
}

// Stage 8, the material for the plots: the residual before and after (thinned to about 20000 rows), the given
// model's worst 10-period window simulated with both models, and each impact measured and simulated.
void plot_material(FitSession& fs, const PrintedErrors& pg, const PrintedErrors& pa) {
    const Prep& pr = fs.prep;
    const MeasuredData& data = *pr.data;
    const FitOptions& o = fs.o;
    FitReport& rep = fs.rep;
    const Eigen::VectorXd& R0 = pg.R;
    const Eigen::VectorXd& R1 = pa.R;
    const PredictedImpacts& pred_before = pg.pred;
    const PredictedImpacts& pred_after = pa.pred;
    const Model& base = fs.chain.front().model;
    const std::size_t step = std::max<std::size_t>(1, pr.rows.size() / 20000);
    for (std::size_t r = 0; r < pr.rows.size(); r += step) {
        const std::size_t i = pr.rows[r];
        rep.residual.x.push_back(data.x[i]);
        rep.residual.v.push_back(pr.vs[i]);
        rep.residual.phi.push_back(pr.phi_forced ? std::fmod(pr.phi[i], kTwoPi) : 0.0);
        rep.residual.before.push_back(R0[static_cast<Eigen::Index>(r)]);
        rep.residual.after.push_back(R1[static_cast<Eigen::Index>(r)]);
    }
    // The given model's worst 10-period window (the gate's own units: one per window of windows(pr, 10)).
    const PrintedError* s10 = pg.find(kErrShoot10);
    const auto wins10 = windows(pr, 10);
    std::size_t worst = wins10.size();
    for (std::size_t w = 0; s10 && w < wins10.size() && w < s10->num.size(); ++w)
        if (std::isfinite(s10->num[w]) && (worst == wins10.size() || s10->num[w] / s10->den[w] > s10->num[worst] / s10->den[worst]))
            worst = w;
    if (worst < wins10.size()) {
        const auto [a, b] = wins10[worst];
        rep.trace.before = simulate_window(pr, base, a, b, o.refine_shooting, o.rtol);
        rep.trace.after = simulate_window(pr, fs.after, a, b, o.refine_shooting, o.rtol);
        for (std::size_t i = a; i <= b; ++i) {
            rep.trace.t.push_back(data.t[i]);
            rep.trace.measured.push_back(data.x[i]);
        }
    }
    for (std::size_t k = 0; k < pr.impacts.size(); ++k) {
        const ImpactObs& im = pr.impacts[k];
        const bool b = k < pred_before.ok.size() && pred_before.ok[k], a = k < pred_after.ok.size() && pred_after.ok[k];
        rep.impacts.push_back({im.t_in, im.v_minus, im.v_plus, im.t_out - im.t_in, im.level,
                               b ? apparent_kappa(pred_before.obs[k]) : kNaN, b ? pred_before.obs[k].t_out - pred_before.obs[k].t_in : kNaN,
                               a ? apparent_kappa(pred_after.obs[k]) : kNaN, a ? pred_after.obs[k].t_out - pred_after.obs[k].t_in : kNaN});
    }
}

// The verdict says what the numbers say: at the noise floor only when the equation error is there and the
// shooting error within the judging horizon is at the sensor noise, with nothing left that a smooth function
// of one variable explains; otherwise how far off, and what the remainder (R1, the model written's residual)
// depends on.
void write_verdict(FitReport& rep, const Prep& pr, const Eigen::VectorXd& R1) {
    const double ratio = rep.noise_floor_N > 0 ? rep.error_after.residual_rms_N / rep.noise_floor_N : INFINITY;
    // The shooting error a right model leaves: the sensor noise over one period (its initial state fitted
    // to the window, it does not drift within one). A record whose returns double their separation within
    // a period is judged on its shorter windows, where the error may have grown to twice the noise.
    const Prep::Predictability& dh = pr.predictability;
    const bool short_horizon = dh.measured && !dh.regular && dh.periods < 1.0 && rep.error_after.shooting_rms_judge_m >= 0;
    const double shoot = short_horizon ? rep.error_after.shooting_rms_judge_m : rep.error_after.shooting_rms_1_m;
    const double shoot_limit = short_horizon ? 2.0 : 1.25;
    const double sratio = pr.sigma_x > 0 ? shoot / pr.sigma_x : INFINITY;
    rep.remainder = remainder_dependence(pr, R1);
    std::string depends;
    // A share counts only where it stands above the noise floor's own: the measured x's noise enters the
    // equation error through every x term, so at the floor a function of x seems to explain a part of it.
    for (const auto& [what, share] : rep.remainder)
        if (share >= 0.05 && share * ratio * ratio >= 0.25) {
            char b[80];
            std::snprintf(b, sizeof b, "%s%s (%.0f %%)", depends.empty() ? "" : ", ", what.c_str(), 100.0 * share);
            depends += b;
        }
    const bool at_floor = ratio <= 1.5 && sratio <= shoot_limit;
    char buf[700];
    if (at_floor) {
        std::snprintf(buf, sizeof buf,
                      "the residual (%.3g %s RMS) is at its noise floor (%.3g %s) and the shooting error (%.3g) at the "
                      "sensor noise (%.3g)%s",
                      rep.error_after.residual_rms_N, rep.force_unit(), rep.noise_floor_N, rep.force_unit(), shoot,
                      pr.sigma_x, rep.effects_found.empty() ? ": no missing effect" : " with the effects found");
    } else {
        std::snprintf(buf, sizeof buf,
                      "the model %s misses something: the residual (%.3g %s RMS) is %.3g times its noise floor (%.3g %s) and the "
                      "shooting error %.3g times the sensor noise; %s%s",
                      rep.effects_found.empty() ? "still" : "with the effects found still", rep.error_after.residual_rms_N,
                      rep.force_unit(), ratio, rep.noise_floor_N, rep.force_unit(), sratio,
                      depends.empty() ? "no smooth function of x, v, the phase, time or the impacts alone explains what is left"
                                      : "what is left depends on ",
                      depends.c_str());
    }
    rep.verdict = buf;
}

}  // namespace

// Stages 7 and 8: the final gate, the errors of the model given and of the model written (the equation
// error, multiple shooting at 1 and 10 periods and at the judging horizon, impacts, diagrams, free runs, the
// test rows), the plots' material, and the verdict. The gate walks the chain of changes back from the last
// until the model is not worse than the model given on any of those errors beyond its scatter; the printed
// numbers are the very ones it compared, so the report can never show the model written worse.
void errors_stage(FitSession& fs) {
    const Prep& pr = fs.prep;
    const MeasuredData* test = fs.test;
    FitReport& rep = fs.rep;
    std::vector<std::string> tnotes;
    Prep pt;
    if (test) pt = prepare(*test, fs.model0, fs.o, tnotes);
    const Gated gd = final_gate(fs, test ? &pt : nullptr);
    fill_errors(rep, pr, gd.pg, rep.error_before);
    fill_errors(rep, pr, gd.pa, rep.error_after);
    if (gd.ref_base > 0) fill_errors(rep, pr, gd.pb, rep.error_baseline);
    if (!gd.pg.diagram_measured.empty()) {
        rep.diagram_measured = gd.pg.diagram_measured;
        rep.diagram_before = gd.pg.diagram;
        rep.diagram_after = gd.pa.diagram;
    }
    if (test && rep.error_after.test_simulation_rms_m > rep.error_before.test_simulation_rms_m &&
        rep.error_after.test_shooting_rms_m <= rep.error_before.test_shooting_rms_m)
        rep.notes.push_back("the free run over the test rows ends further from them with the effects found, while the "
                            "shooting error within the predictability horizon falls: the free run drifts onto another "
                            "trajectory (a chaotic record), which no model avoids");
    plot_material(fs, gd.pg, gd.pa);
    write_verdict(rep, pr, gd.pa.R);
}

}  // namespace impactlab::identify::detail
