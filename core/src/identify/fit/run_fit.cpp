// The loop of impactlab fit: run_fit takes a FitSession through the stages (baseline, residual, effect
// selection, the model with the effects, errors before and after); evaluate_model gives one model's errors.
#include "identify/fit/session.hpp"

namespace impactlab::identify {

using namespace detail;

const char* fit_stage_name(FitStage s) {
    switch (s) {
        case FitStage::Prepare: return "preparing the data";
        case FitStage::Baseline: return "fitting the baseline";
        case FitStage::Candidates: return "screening the candidate effects";
        case FitStage::Selection: return "selecting effects";
        case FitStage::Refit: return "refitting the effects";
        case FitStage::ImpactLaw: return "comparing the impacts";
        case FitStage::Validation: return "validating on held-out data";
        case FitStage::Errors: return "errors before and after";
        case FitStage::Count: break;
    }
    return "?";
}

namespace {

// Runs one stage; a fault inside it (an exception other than a cancel) ends the stage, not the fit: the report
// says which stage and why, and `undo` puts back what the fit held before it.
template <class Stage, class Undo>
void guarded(FitSession& fs, FitStage stage, Stage&& run, Undo&& undo) {
    try {
        run();
    } catch (const FitCancelled&) {
        throw;
    } catch (const std::exception& e) {
        fs.rep.notes.push_back(std::string("the stage '") + fit_stage_name(stage) + "' failed (" + e.what() +
                               "); its result is left out and the fit goes on with the model before it");
        undo();
    }
}

// A model in the record's units is checked where the record lies (twice its largest true |x|), not on the rail.
void set_extent(Model& model0, const Model& given, const MeasuredData& d) {
    if (stiffness_kind(model0.p) != StiffnessKind::DataUnits || given.p.x_extent != 0.0) return;
    double xmax = 0;
    for (double x : d.x)
        if (std::isfinite(x)) xmax = std::max(xmax, std::abs(model0.true_x(x)));
    if (xmax > 0) model0.p.x_extent = 2.0 * xmax;
}

// Runs in different wells that the measurement chain centred on zero: each put back at its well first. Like any
// stage, a fault ends it with a note in `offsets`, never the fit. True: the record to fit is `shifted`.
bool runs_at_wells(const MeasuredData& data_given, const Model& given, const FitOptions& options, Model& model0, MeasuredData& shifted,
                   FitReport& offsets) {
    try {
        return run_offsets_stage(data_given, model0, options, shifted, offsets);
    } catch (const FitCancelled&) {
        throw;
    } catch (const std::exception& e) {
        model0 = given;
        set_extent(model0, given, data_given);
        offsets = FitReport{};
        offsets.notes.push_back(std::string("putting the runs back at their wells failed (") + e.what() + "); the runs are fitted as recorded");
    }
    return false;
}

// Stage 0: the record prepared for the fit, and what the report says of it.
void prepare_stage(FitSession& fs) {
    const MeasuredData& data = fs.data;
    const Model& model0 = fs.model0;
    FitOptions& o = fs.o;
    FitReport& rep = fs.rep;
    rep.data_source = data.source;
    rep.model_name = model0.p.name;
    rep.forcing = forcing_of(data);
    rep.baseline = o.fit_baseline ? Baseline::Fit : Baseline::Fixed;
    rep.x_highpass_hz = o.x_highpass_hz;
    if (stiffness_kind(model0.p) == StiffnessKind::DataUnits) rep.units = FitUnits::DataUnits;
    validate(model0.p, "model");
    check_plausible(data, model0, o);
    fs.prep = prepare(data, model0, o, rep.notes);
    Prep& prep = fs.prep;
    prep.progress = fs.progress;
    prep.predictability = data_horizon(prep);
    if (prep.unforced)
        rep.notes.push_back("a free run (no input): the rig's unforced motion, a flow in the plane (x, v), cannot be chaotic; it is "
                            "judged as a regular record, over whole periods");
    const Prep& pr = prep;
    rep.samples = pr.n;
    rep.rows_used = pr.rows.size();
    rep.dt = pr.dt;
    rep.duration = data.t.back() - data.t.front();
    rep.sigma_x = pr.sigma_x;
    rep.window_s = (pr.K.H + 1) * pr.dt;
    rep.period_s = pr.period;
    rep.drive_fit_rms_rad = pr.drive_rms;
    rep.data_horizon_measured = pr.predictability.measured;
    rep.data_regular = pr.predictability.regular;
    rep.data_free_run = pr.unforced;
    rep.data_horizon_periods = pr.predictability.periods;
    rep.data_lambda = pr.predictability.lambda;
    if (pr.phi_forced) {
        rep.omega_min = *std::min_element(pr.omega.begin(), pr.omega.end());
        rep.omega_max = *std::max_element(pr.omega.begin(), pr.omega.end());
    }
    fs.hac_lag = hac_lag_of(pr);
}

// Stage 1: the baseline, the chain's first steps, and the baseline's residual.
void baseline_stage(FitSession& fs) {
    const Model& model0 = fs.model0;
    FitOptions& o = fs.o;
    FitReport& rep = fs.rep;
    const Prep& pr = fs.prep;
    std::vector<std::string>& base_names = fs.base_names;
    base_names = fitted_base_names(model0, pr, o);
    // Runs put back at their wells: the tied cubic's even term is fitted with the baseline.
    if (o.fit_baseline && o.fit_params.empty() && !rep.run_offsets.empty()) base_names.push_back("k2");
    fit_baseline_stage(fs);
    Model& base = fs.base;
    const Model& ee_base = fs.ee_base;
    Chain& chain = fs.chain;
    chain = {{"the model given", model0, {}, -1, false}};
    // Never a worse model than the one given: on a record forced by the unbalance (the given model is the rig's
    // physical one, not a starting guess) the fitted baseline must predict held-out data better.
    if (o.fit_baseline && pr.phi_forced) {
        std::string why;
        if (!baseline_predicts_better(pr, model0, base, base_names, o, why)) {
            rep.notes.push_back("the fitted baseline does not predict held-out data better than the parameters given (" + why +
                                "); the parameters given are kept, fixed");
            base = model0;
            o.fit_baseline = false;
            base_names.clear();
            rep.baseline = Baseline::Fixed;
        }
    }
    if (o.fit_baseline && model0.placeholder) {
        // Starting values are no model to be "not worse than": the baseline fitted to the equation error is the
        // reference of every later change and of the final gate.
        ChainStep head;
        head.what = "the base parameters fitted to the equation error (the model given holds starting values only)";
        head.model = ee_base;
        head.equation_error_fit = true;
        chain = {head};
        rep.notes.push_back("the model given (" + model0.p.name +
                            ") holds starting values only: the errors 'before' and the final gate's reference are those of the "
                            "baseline fitted to the equation error");
        if (!pr.phi_forced && fs.base_refined)
            chain.push_back({"the base parameters refined on the free-run simulation error", base, {}, -1, true});
    } else if (o.fit_baseline) {
        chain.push_back({"the base parameters fitted to the equation error", ee_base, {}, -1, true});
        if (!pr.phi_forced && fs.base_refined)
            chain.push_back({"the base parameters refined on the free-run simulation error", base, {}, -1, true});
    }
    std::vector<double> pw;
    Eigen::VectorXd& R0 = fs.R0;
    residual(pr, base, R0, pw);
    locate_features(fs.prep, base, R0);
    rep.before = model0;
    fs.in0 = R0.squaredNorm();
    rep.noise_floor_N = base.p.m * pr.sigma_x * pr.K.noise_gain / base.sensor_gain();
}

// The typical speed (RMS) and position (90 % of |x|) of the rows fitted, for the effects' sentences.
SentenceContext sentence_context(const Prep& pr, const MeasuredData& data) {
    SentenceContext sc;
    std::vector<double> av, ax;
    for (std::size_t r : pr.rows) {
        av.push_back(std::abs(pr.vs[r]));
        ax.push_back(std::abs(data.x[r]));
    }
    double s = 0;
    for (double v : av) s += v * v;
    sc.v_typ = av.empty() ? 0.0 : std::sqrt(s / static_cast<double>(av.size()));
    sc.x_typ = quantile(ax, 0.9);
    return sc;
}

// Stages 2 to 6, each guarded: a stage that fails leaves the model before it (no effects, where the effects
// were its work).
void effect_stages(FitSession& fs) {
    auto no_effects = [&fs] {
        fs.sel = Selection{};
        fs.after = fs.base;
        fs.rep.effects_found.clear();
        while (fs.chain.size() > 1 && !fs.chain.back().baseline) fs.chain.pop_back();
    };
    fs.enter(FitStage::Candidates);
    // ---- 2. candidate columns -----------------------------------------------------------------------------
    guarded(fs, FitStage::Candidates, [&] { screen_candidates(fs); }, [&] { fs.screen = Screen{}; });

    fs.enter(FitStage::Selection);
    // ---- 3. greedy selection ------------------------------------------------------------------------------
    guarded(fs, FitStage::Selection, [&] { select_effects(fs); }, no_effects);

    fs.enter(FitStage::Refit);
    // ---- 4. the model with the effects: linear estimates, then joint nonlinear refinement; an effect whose
    //         significance does not survive the joint fit is dropped and the rest refitted ------------------
    fs.sc = sentence_context(fs.prep, fs.data);
    guarded(fs, FitStage::Refit, [&] { refit_stage(fs); }, no_effects);

    fs.enter(FitStage::ImpactLaw);
    // ---- 5. the impact law: bumper position, impact duration, restitution ----------------------------------
    {
        const Model before_law = fs.after;
        const FitReport rep_before = fs.rep;
        guarded(
            fs, FitStage::ImpactLaw,
            [&] {
                impact_law_stage(fs);
                end_stop_stage(fs.prep, fs.o, fs.sc, fs.after, fs.rep);
            },
            [&] {
                std::vector<std::string> notes = std::move(fs.rep.notes);
                fs.rep = rep_before;
                fs.rep.notes = std::move(notes);
                fs.after = before_law;
            });
    }
    fs.enter(FitStage::Validation);
    // ---- 6. validation: an effect stays only if it lowers the short-horizon simulation error on data held
    //         out from its fit, by more than the windows' scatter; the final model must beat the baseline ----
    guarded(fs, FitStage::Validation, [&] { validate_effects(fs); }, no_effects);
    {
        const Model before_oe = fs.after;
        const Chain chain_before = fs.chain;
        guarded(fs, FitStage::Validation, [&] { output_error_stage(fs); }, [&] {
            fs.after = before_oe;
            fs.chain = chain_before;
        });
    }
}

// What the report says of the wells after the fit, from every fitted term of the force: the effects found, and
// the even stiffness the baseline fitted as k2 (runs put back at their wells).
void wells_after(FitSession& fs) {
    FitReport& rep = fs.rep;
    const Prep& pr = fs.prep;
    rep.runs = pr.run_start.size();
    rep.wells_before = well_report(fs.model0, {}, pr);
    rep.data_wells = data_wells(pr, fs.hac_lag);
    rep.wells_from_data = wells_asymmetry(rep.data_wells, rep.x_unit());
    std::vector<FoundEffect> terms = rep.effects_found;
    for (const BaseEstimate& b : rep.base_estimates)
        if (b.name == "k2") {
            FoundEffect k2;
            k2.id = "even_stiffness";
            k2.sigma = {{"k2", b.sigma}};
            terms.push_back(std::move(k2));
        }
    rep.wells_after = well_report(fs.after, terms, pr);
    rep.well_frequency = well_frequency_identifiability(rep.data_wells, rep.wells_after, rep.unseparated);
}

// Never a report whose headline numbers are not numbers: name the first and refuse to hand it over.
void check_finite(const FitReport& rep, const MeasuredData& data) {
    const std::pair<const char*, double> headline[] = {
        {"sensor noise", rep.sigma_x},
        {"noise floor", rep.noise_floor_N},
        {"residual RMS before", rep.error_before.residual_rms_N},
        {"residual RMS after", rep.error_after.residual_rms_N},
        {"1-period shooting RMS after", rep.error_after.shooting_rms_1_m},
    };
    for (const auto& [what, v] : headline)
        if (!std::isfinite(v))
            throw std::runtime_error(data.source + ": the fit's " + what + " came out " + std::to_string(v) +
                                     "; no report is written (check the data's columns and units)");
    for (const auto& e : rep.effects_found)
        for (const auto& [name, v] : e.parameters)
            if (!std::isfinite(v))
                throw std::runtime_error(data.source + ": effect " + e.id + "." + name + " came out " + std::to_string(v) +
                                         "; no report is written");
}

}  // namespace

FitReport run_fit(const MeasuredData& data_given, const Model& given, const FitOptions& options, const MeasuredData* test,
                  FitProgress* progress) {
    Model model0 = given;
    set_extent(model0, given, data_given);
    FitReport offsets;
    MeasuredData shifted;
    const bool moved = runs_at_wells(data_given, given, options, model0, shifted, offsets);
    if (!moved && centre_placeholder(data_given, model0, options, offsets)) set_extent(model0, given, data_given);
    const MeasuredData& data = moved ? shifted : data_given;
    if (moved) set_extent(model0, given, data);
    FitSession fs(data, model0, options, test, progress);
    fs.rep.run_offsets = offsets.run_offsets;
    fs.rep.notes = offsets.notes;
    fs.enter(FitStage::Prepare);
    const auto clock0 = std::chrono::steady_clock::now();
    FitReport& rep = fs.rep;
    prepare_stage(fs);

    fs.enter(FitStage::Baseline);
    // ---- 1. the baseline --------------------------------------------------------------------------------
    baseline_stage(fs);
    effect_stages(fs);   // ---- 2 to 6

    fs.enter(FitStage::Errors);
    // ---- 7. the final gate, errors before and after; 8. material for the plots; the verdict ------------------
    errors_stage(fs);
    Model& after = fs.after;
    std::stable_sort(rep.effects_found.begin(), rep.effects_found.end(),
                     [](const FoundEffect& a, const FoundEffect& b) { return a.explained_fraction > b.explained_fraction; });
    if (!rep.effects_found.empty()) after.p.name = fs.base.p.name + "+" + rep.effects_found.front().id;
    for (std::size_t k = 1; k < rep.effects_found.size(); ++k) after.p.name += "+" + rep.effects_found[k].id;
    rep.after = after;
    // ---- 9. what the data tell of the base parameters written (nothing changes them here) ------------------
    guarded(fs, FitStage::Errors, [&] { uncertainty_stage(fs); }, [&] {
        rep.base_estimates.clear();
        rep.unseparated.clear();
    });
    wells_after(fs);
    check_finite(rep, data);
    rep.runtime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock0).count();
    if (progress) progress->fraction.store(1.0, std::memory_order_relaxed);
    return std::move(rep);
}

ErrorSummary evaluate_model(const MeasuredData& data, const Model& model, const FitOptions& o) {
    std::vector<std::string> notes;
    validate(model.p, "model");
    check_plausible(data, model, o);
    const Prep pr = prepare(data, model, o, notes);
    ErrorSummary e;
    Eigen::VectorXd R;
    std::vector<double> pw;
    residual(pr, model, R, pw);
    e.residual_rms_N = rms_of(R);
    const ShootOut so = shooting(pr, model, o);
    e.shooting_rms_1_m = so.rms1;
    e.shooting_rms_10_m = so.rms10;
    e.impact = impact_error(pr, predict_impacts(pr, model, o.rtol));
    if (pr.phi_forced) {
        const auto [wmin, wmax] = std::minmax_element(pr.omega.begin(), pr.omega.end());
        if (*wmax - *wmin > 2 * o.omega_bin)
            e.diagram_distance_m = diagram_distance(measured_sections(pr), free_run_sections(pr, model, o.rtol), o.omega_bin,
                                                    e.diagram_bins, &e.diagram_per_bin);
    } else {
        e.simulation_rms_m = free_run_rms(free_run(pr, model, o.rtol), data.x);
    }
    return e;
}

}  // namespace impactlab::identify
