// Stage 1 of the fit: the baseline.
#include "identify/fit/session.hpp"

namespace impactlab::identify::detail {

// Stage 1: the baseline. With fit_baseline, the base parameters `base_names` are fitted to the equation
// error (the input's polarity found, a bistable model kept bistable) and, for an input-forced record,
// refined on the free-run simulation error when that predicts the held-out part better. Throws ParamError
// for a fit that leaves the physical range.
void fit_baseline_stage(FitSession& fs) {
    const Prep& pr = fs.prep;
    const Model& model0 = fs.model0;
    const FitOptions& o = fs.o;
    const std::vector<std::string>& base_names = fs.base_names;
    FitReport& rep = fs.rep;
    Model& equation_error_base = fs.ee_base;
    Model& base = fs.base;
    base = model0;
    Eigen::VectorXd R0;
    Eigen::MatrixXd Jtmp;
    if (o.fit_baseline) {
        std::vector<Knob> knobs = base_knobs(base, base_names, pr);
        // A bistable starting model stays bistable: a fit that merges the wells into one is a fit to the
        // wrong attractor (a chaotic record's free run, say), and that stage is undone.
        // So does a model of a record that changes wells (a bistable rig's), whatever the model given.
        const std::size_t wells0 = well_report(base, {}, pr).wells.size();
        const WellBand band = well_band(pr.data->x);
        const bool record_bistable = band.found && well_changes(pr.data->x, band) >= 4;
        auto keeps_wells = [&](const Model& m, const char* stage) {
            const std::size_t w = well_report(m, {}, pr).wells.size();
            if ((wells0 == 2 || record_bistable) && w < 2) {
                rep.notes.push_back(std::string("the ") + stage + " fit of the baseline would " +
                                    (wells0 == 2 ? "merge its two wells into " + std::string(w ? "one" : "none")
                                                 : "give one well to a record that changes wells") +
                                    "; that stage is undone");
                return false;
            }
            return true;
        };
        // A first pass from the starting values (linear parameters converge in one step), then refine.
        const Model start = base;
        if (std::find(base_names.begin(), base_names.end(), "x0") != base_names.end()) {
            // A centred placeholder's origin waits for the linear parameters: beside the starting values' cubic
            // it would wander to wherever that cubic is centred.
            std::vector<std::string> linear = base_names;
            linear.erase(std::find(linear.begin(), linear.end(), "x0"));
            std::vector<Knob> lk = base_knobs(base, linear, pr);
            lm_residual(pr, base, lk, 40, R0, Jtmp);
            knobs = base_knobs(base, base_names, pr);
        }
        lm_residual(pr, base, knobs, 40, R0, Jtmp);
        // The input gain keeps its sign in a fit; which sign the record has (a voltage's polarity is a
        // convention) is decided here, once: if the gain ran into zero, the other sign is tried.
        const bool fits_gain = std::find(base_names.begin(), base_names.end(), "gain") != base_names.end();
        if (fits_gain && start.p.input_gain != 0.0 && std::abs(base.p.input_gain) < 1e-9 * std::abs(start.p.input_gain)) {
            Model flipped = start;
            flipped.p.input_gain = -start.p.input_gain;
            std::vector<Knob> kf = base_knobs(flipped, base_names, pr);
            Eigen::VectorXd Rf;
            lm_residual(pr, flipped, kf, 40, Rf, Jtmp);
            if (Rf.squaredNorm() < R0.squaredNorm()) {
                base = flipped;
                R0 = Rf;
                rep.notes.push_back("the input acts with the opposite sign to the starting gain's");
            }
            knobs = base_knobs(base, base_names, pr);
        }
        if (!keeps_wells(base, "equation-error")) base = start;
        equation_error_base = base;
        // Input-forced data: refine by the simulation error, which the equation error at a few samples per
        // period of the resonance cannot match.
        const Prep::Predictability& dh = pr.predictability;
        if (!pr.phi_forced && dh.measured && !dh.regular) {
            // A chaotic record's free run parts from any model's within the horizon: a fit to it pulls the model
            // toward the record's mean, not toward the rig. The equation error is the fit there.
            char buf[240];
            std::snprintf(buf, sizeof buf,
                          "the record is chaotic (its returns part within %.3g periods): the baseline is not refined on the "
                          "free-run error, which past the horizon measures no model",
                          dh.periods);
            rep.notes.push_back(buf);
        } else if (!pr.phi_forced) {
            const Model ee = base;
            knobs = base_knobs(base, base_names, pr);
            lm_simulation(pr, base, knobs, 30, o.rtol);
            if (!keeps_wells(base, "output-error")) {
                base = ee;
            } else if (!refinement_predicts_better(pr, base, ee, o.rtol)) {
                // A chaotic record's free run, or a fit of what the held-out tail does not show: not the rig.
                rep.notes.push_back("the output-error refinement of the baseline does not predict the tail of the record it was not "
                                    "fitted to better (a consistent fall over the judging windows, paired z >= 2); the "
                                    "equation-error baseline is kept");
                base = ee;
            } else {
                rep.notes.push_back("baseline refined on the free-run simulation error (output error)");
                fs.base_refined = true;
            }
        }
        // Never a physically impossible model: a baseline fit that leaves the physical range keeps the
        // parameters given, and says why.
        if (const std::string why = unphysical(base); !why.empty()) {
            rep.notes.push_back("the baseline fit leaves the physical range (" + why +
                                "); the parameters given are kept (try other starting values or --fit-params)");
            base = model0;
            equation_error_base = model0;
            fs.o.fit_baseline = false;
            fs.base_names.clear();
            rep.baseline = Baseline::Fixed;
        }
    }
}

}  // namespace impactlab::identify::detail
