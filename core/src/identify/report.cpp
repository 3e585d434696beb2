// The report of impactlab fit: report.json, report.md, model_after.json and the PNG plots.
#include <functional>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "identify/internal.hpp"
#include "impactlab/json_text.hpp"
#include "impactlab/atomic_file.hpp"
#include "impactlab/params_json.hpp"
#include "impactlab/plot.hpp"

namespace impactlab::identify {

using nlohmann::json;

namespace {

json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json errors_json(const ErrorSummary& e) {
    json j;
    j["residual_rms_N"] = num(e.residual_rms_N);
    j["shooting_rms_1_m"] = num(e.shooting_rms_1_m);
    j["shooting_rms_10_m"] = num(e.shooting_rms_10_m);
    j["impact_law"] = {{"impacts", e.impact.impacts},
                       {"kappa_rms", num(e.impact.kappa_rms)},
                       {"duration_rms_s", num(e.impact.duration_rms_s)},
                       {"level_offset_m", num(e.impact.level_offset_m)}};
    j["diagram_distance_m"] = e.diagram_distance_m >= 0 ? num(e.diagram_distance_m) : json(nullptr);
    j["diagram_bins"] = e.diagram_bins;
    j["diagram_per_bin"] = json::array();
    for (const auto& [w, dist] : e.diagram_per_bin) j["diagram_per_bin"].push_back({{"omega", w}, {"distance_m", num(dist)}});
    if (e.simulation_rms_m >= 0) j["simulation_rms_m"] = num(e.simulation_rms_m);
    if (e.test_simulation_rms_m >= 0) j["test_simulation_rms_m"] = num(e.test_simulation_rms_m);
    if (e.test_shooting_rms_m >= 0) j["test_shooting_rms_m"] = num(e.test_shooting_rms_m);
    if (e.shooting_rms_judge_m >= 0) j["shooting_rms_judge_m"] = num(e.shooting_rms_judge_m);
    if (e.attractor_x_w1 >= 0)
        j["attractor"] = {{"x_wasserstein_per_std", num(e.attractor_x_w1)},
                          {"v_wasserstein_per_std", num(e.attractor_v_w1)},
                          {"well_changes_per_s", e.attractor_wells_per_s >= 0 ? num(e.attractor_wells_per_s) : json(nullptr)},
                          {"spectrum_rms_db", e.attractor_spectrum_db >= 0 ? num(e.attractor_spectrum_db) : json(nullptr)}};
    return j;
}

json model_json(const Model& m) {
    json j = json::parse(params_to_json_text(m.p));
    j["forcing"] = m.forcing == Forcing::Unbalance ? "unbalance" : "input";
    j["bumper"] = m.bumper();
    return j;
}

std::string g3(double v, const char* f = "%.3g") {
    if (!std::isfinite(v)) return "-";
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

plot::Series points(const std::vector<double>& x, const std::vector<double>& y, plot::Color c, double xs = 1.0, double ys = 1.0,
                    const std::string& label = "") {
    plot::Series s;
    s.kind = plot::Series::Kind::Points;
    s.x.reserve(x.size());
    s.y.reserve(y.size());
    for (std::size_t i = 0; i < x.size() && i < y.size(); ++i) {
        s.x.push_back(x[i] * xs);
        s.y.push_back(y[i] * ys);
    }
    s.color = c;
    s.size = 1.2f;
    s.label = label;
    return s;
}

plot::Series line(const std::vector<double>& x, const std::vector<double>& y, plot::Color c, float width, const std::string& label,
                  double ys = 1.0) {
    plot::Series s;
    s.kind = plot::Series::Kind::Line;
    s.x = x;
    for (double v : y) s.y.push_back(v * ys);
    s.y.resize(s.x.size(), std::nan(""));
    s.color = c;
    s.size = width;
    s.label = label;
    return s;
}

void residual_figure(const FitReport& r, const std::vector<double>& var, double scale, const std::string& xlabel,
                     const std::string& title, const std::string& path) {
    plot::Figure fig;
    fig.title = title;
    fig.width = 1100;
    fig.panel_height = 320;
    double lo = INFINITY, hi = -INFINITY;
    for (double v : r.residual.before)
        if (std::isfinite(v)) {
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
    for (int k = 0; k < 2; ++k) {
        plot::Panel p;
        p.title = k == 0 ? "before: " + r.before.p.name : "after: " + r.after.p.name;
        p.xlabel = xlabel;
        p.ylabel = "residual [N]";
        p.series.push_back(points(var, k == 0 ? r.residual.before : r.residual.after,
                                  k == 0 ? plot::Color{214, 39, 40, 90} : plot::Color{31, 119, 180, 90}, scale));
        if (std::isfinite(lo) && hi > lo) {
            p.ymin = lo - 0.03 * (hi - lo);
            p.ymax = hi + 0.03 * (hi - lo);
        }
        fig.panels.push_back(std::move(p));
    }
    plot::save_png(fig, path);
}

void plots(const FitReport& r, const std::string& dir) {
    namespace fs = std::filesystem;
    const std::string xl = r.forcing == Forcing::Unbalance ? "x [mm]" : "x (as measured) x 1000";
    residual_figure(r, r.residual.x, 1e3, xl, "Residual against the position", (fs::path(dir) / "residual_x.png").string());
    residual_figure(r, r.residual.v, 1.0, "v [m/s]", "Residual against the velocity", (fs::path(dir) / "residual_v.png").string());
    if (r.forcing == Forcing::Unbalance)
        residual_figure(r, r.residual.phi, 1.0, "phi mod 2 pi [rad]", "Residual against the unbalance angle",
                        (fs::path(dir) / "residual_phi.png").string());
    if (!r.trace.t.empty()) {
        plot::Figure fig;
        fig.title = "Measured and simulated x(t): one window of 10 forcing periods (multiple shooting)";
        fig.width = 1200;
        fig.panel_height = 300;
        for (int k = 0; k < 2; ++k) {
            plot::Panel p;
            p.title = k == 0 ? "before: " + r.before.p.name : "after: " + r.after.p.name;
            p.xlabel = "t [s]";
            p.ylabel = "x [mm]";
            p.series.push_back(line(r.trace.t, r.trace.measured, {20, 20, 20, 255}, 1.6f, "measured", 1e3));
            p.series.push_back(line(r.trace.t, k == 0 ? r.trace.before : r.trace.after,
                                    k == 0 ? plot::Color{214, 39, 40, 230} : plot::Color{31, 119, 180, 230}, 1.3f, "simulated", 1e3));
            fig.panels.push_back(std::move(p));
        }
        plot::save_png(fig, (fs::path(dir) / "x_t.png").string());
    }
    if (r.impacts.size() >= 3) {
        plot::Figure fig;
        fig.title = "Impact law: measured impacts against the same impacts simulated with the model";
        fig.width = 1000;
        fig.panel_height = 300;
        double vmax = 0;
        std::vector<double> vm, kap, dw;
        for (const auto& im : r.impacts) {
            vmax = std::max(vmax, im.v_minus);
            vm.push_back(im.v_minus);
            kap.push_back(im.v_minus > 0 ? -im.v_plus / im.v_minus : NAN);
            dw.push_back(im.dwell * 1e3);
        }
        // The model's side: each measured impact simulated with the model before and after, read by the
        // same detector (what the fit compared).
        std::vector<double> vb, kb, tb, va, ka, ta;
        for (const auto& im : r.impacts) {
            if (std::isfinite(im.kappa_before)) {
                vb.push_back(im.v_minus);
                kb.push_back(im.kappa_before);
                tb.push_back(im.dwell_before * 1e3);
            }
            if (std::isfinite(im.kappa_after)) {
                va.push_back(im.v_minus);
                ka.push_back(im.kappa_after);
                ta.push_back(im.dwell_after * 1e3);
            }
        }
        plot::Panel p1, p2;
        p1.title = "restitution -v+/v-";
        p1.xlabel = "v- [m/s]";
        p1.ylabel = "kappa";
        p1.series.push_back(points(vm, kap, {20, 20, 20, 255}, 1, 1, "measured"));
        p1.series.back().size = 2.5f;
        p1.series.push_back(points(vb, kb, {214, 39, 40, 200}, 1, 1, "model before"));
        p1.series.back().size = 2.0f;
        p1.series.push_back(points(va, ka, {31, 119, 180, 200}, 1, 1, "model after"));
        p1.series.back().size = 2.0f;
        p2.title = "time held at the bumper";
        p2.xlabel = "v- [m/s]";
        p2.ylabel = "dwell [ms]";
        p2.series.push_back(points(vm, dw, {20, 20, 20, 255}, 1, 1, "measured"));
        p2.series.back().size = 2.5f;
        p2.series.push_back(points(vb, tb, {214, 39, 40, 200}, 1, 1, "model before"));
        p2.series.back().size = 2.0f;
        p2.series.push_back(points(va, ta, {31, 119, 180, 200}, 1, 1, "model after"));
        p2.series.back().size = 2.0f;
        fig.panels.push_back(std::move(p1));
        fig.panels.push_back(std::move(p2));
        plot::save_png(fig, (fs::path(dir) / "impacts.png").string());
    }
    if (!r.diagram_measured.empty()) {
        plot::Figure fig;
        fig.title = "Bifurcation diagrams: x at phi = 2 pi k against omega";
        fig.width = 1100;
        fig.panel_height = 260;
        const std::vector<std::pair<double, double>>* d[3] = {&r.diagram_measured, &r.diagram_before, &r.diagram_after};
        const char* names[3] = {"measured", "simulated before", "simulated after"};
        for (int k = 0; k < 3; ++k) {
            plot::Panel p;
            p.title = names[k];
            p.xlabel = "omega [rad/s]";
            p.ylabel = "x [mm]";
            std::vector<double> w, x;
            for (const auto& [a, b] : *d[k]) {
                w.push_back(a);
                x.push_back(b);
            }
            p.series.push_back(points(w, x, {20, 20, 20, 120}, 1, 1e3));
            fig.panels.push_back(std::move(p));
        }
        plot::save_png(fig, (fs::path(dir) / "diagram.png").string());
    }
}

// The title, the record, the model and the equation error, and the verdict.
void md_header(std::ostream& md, const FitReport& r) {
    md << "# impactlab fit: " << r.data_source << "\n\n";
    md << "Model **" << r.before.p.name << "** (" << (r.baseline == Baseline::Fit ? "parameters fitted to the data" : "parameters fixed")
       << "), forcing " << forcing_name(r.forcing) << ". " << r.samples << " samples, " << g3(r.duration) << " s at " << g3(1.0 / r.dt)
       << " Hz; sensor noise about " << (r.metres() ? g3(r.sigma_x * 1e6) + " um" : g3(r.sigma_x) + " (" + r.x_unit() + ")") << ".\n\n";
    if (!r.run_offsets.empty()) {
        md << "The runs lie in different wells, but the measurement chain centred each run's x on zero. Each run's own local law, "
              "tied to one cubic, puts its well where it lies; the fit sees each run shifted by (a model written here simulates "
              "the runs in these coordinates):\n\n| run | offset [" << r.x_unit() << "] |\n|---|---|\n";
        for (const auto& o : r.run_offsets) md << "| " << o.run + 1 << " | " << g3(o.offset, "%.4g") << " +/- " << g3(o.sigma, "%.2g") << " |\n";
        md << "\n";
    }
    if (r.x_highpass_hz > 0)
        md << "The record's x went through a high-pass at " << g3(r.x_highpass_hz)
           << " Hz (declared): every free run of a model is filtered alike before it is compared with x.\n\n";
    md << "The equation error is the local average over a smooth window of half-width " << g3(r.window_s * 1e3)
       << " ms of m x'' + F_R + F_SA + F_I - forcing, on " << r.rows_used
       << " free-flight windows (impacts left out); its noise floor is about " << g3(r.noise_floor_N) << " " << r.force_unit() << ".\n\n";
    md << "**Verdict:** " << r.verdict << ".\n\n";
}

// The effects found, each with its sentence and the held-out check that kept it.
void md_effects(std::ostream& md, const FitReport& r) {
    md << "## Effects found\n\n";
    if (r.effects_found.empty()) {
        md << "None: no effect lowered the simulation error on held-out data beyond its noise.\n\n";
    } else {
        int k = 1;
        for (const auto& f : r.effects_found) {
            md << k++ << ". **" << f.id << "**" << (f.not_told_from.empty() ? "" : ", its shape not resolved,") << " (explains " << g3(100 * f.explained_fraction, "%.1f") << " % of the "
               << (f.evidence == Evidence::ImpactLaw ? "impact-law error" : f.evidence == Evidence::StrayImpacts ? "reversals" : "residual") << ", z = " << g3(f.z, "%.1f") << "): "
               << f.sentence << ". Held-out simulation error " << g3(-100 * f.validation_gain, "%+.1f") << " % (paired z = "
               << g3(f.validation_z, "%.1f") << ")."
               << (f.not_told_from.empty() ? "" : " The data do not tell its shape from " + f.not_told_from +
                                                      ": a force of this size, kept because it predicts held-out data at least as well as the alternatives, and no finding of this law.")
               << "\n";
        }
        md << "\n";
    }
}

// The held-out validation: its windows, the record's and the model's horizons, and the effects turned down.
void md_validation(std::ostream& md, const FitReport& r) {
    md << "## Validation on held-out data\n\n";
    md << "Every effect the residual points to must lower the short-horizon simulation error (multiple shooting) on the "
          "half of the record its parameters were not fitted to (alternate blocks of about an eighth of the record), "
          "by more than the windows' scatter (paired z >= 3) and by 2 % of the error above the noise. ";
    if (r.horizon_periods > 0) {
        md << "The windows are " << g3(r.horizon_periods) << " forcing periods long (" << r.validation_windows << " of them). ";
        if (r.data_free_run)
            md << "The record is a free run: nothing drives it, and the rig's unforced motion, a flow in the plane (x, v), "
                  "has no chaos, so it is judged over whole periods of its own oscillation.\n\n";
        else if (r.data_horizon_measured && r.data_regular)
            md << "The record itself is regular: nearby returns of the measured trajectory stay together for 10 forcing periods "
                  "(no separation doubling), so it is judged over whole periods; a model whose error grows faster is wrong, "
                  "not unlucky.\n\n";
        else if (r.data_horizon_measured)
            md << "The record's own predictability horizon: nearby returns of the measured trajectory (delay embedding with "
                  "the forcing, Rosenstein's method) double their separation in "
               << g3(r.data_horizon_periods) << " forcing periods (largest Lyapunov exponent about " << g3(r.data_lambda, "%.3g")
               << " 1/s); the windows lie within it, where a chaotic record's own instability does not yet set the error.\n\n";
        else
            md << "The record is too short to measure its own predictability, so the windows are the longest within which the "
                  "model's shooting error has at most doubled from the shortest windows'.\n\n";
        md << "The model's own error growth (the model given or fitted, by window length):\n\n";
        md << "| window [periods] | shooting RMS [" << (r.metres() ? "mm" : r.x_unit()) << "] |\n|---|---|\n";
        for (const auto& [L, e] : r.horizon_growth) md << "| " << g3(L) << " | " << g3(r.metres() ? e * 1e3 : e, "%.4g") << " |\n";
        md << "\nHeld-out shooting RMS: " << g3(r.validation_rms_before_m * (r.metres() ? 1e3 : 1), "%.4g") << " before, "
           << g3(r.validation_rms_after_m * (r.metres() ? 1e3 : 1), "%.4g") << " after.\n\n";
    } else {
        md << "The record is too short for held-out windows: nothing can be validated, so nothing is reported.\n\n";
    }
    if (!r.effects_rejected.empty()) {
        md << "Turned down:\n\n";
        for (const auto& f : r.effects_rejected) md << "- **" << f.id << "**: " << f.reason << ".\n";
        md << "\n";
    }
}

// The base parameters written, with their standard errors and the pairs the data do not separate.
void md_base_parameters(std::ostream& md, const FitReport& r) {
    if (!r.base_estimates.empty()) {
        md << "## The base parameters written, with what the data tell of them\n\nStandard errors from the equation error (its "
              "variance and correlation time); inf: the data do not see the parameter.\n\n| parameter | value | standard error |\n|---|---|---|\n";
        for (const auto& b : r.base_estimates)
            md << "| " << b.name << " | " << g3(b.value, "%.6g") << " | " << g3(b.sigma, "%.2g")
               << (b.stood_in_by.empty() ? "" : " (not separated from " + b.stood_in_by + ": the model's total force is what the data pin; no finding)")
               << " |\n";
        for (const auto& u : r.unseparated)
            md << "\nThe data do not separate " << u.a << " and " << u.b << " (correlation " << g3(u.correlation, "%.4f")
               << "): what they pin is " << u.a << (u.ratio ? " / " : " * ") << u.b << " = " << g3(u.value, "%.6g") << " +/- "
               << g3(u.sigma, "%.2g") << "; neither value alone is a finding.\n";
        md << "\n";
    }
}

// Each run's well, measured from its data.
void md_data_wells(std::ostream& md, const FitReport& r) {
    if (!r.data_wells.empty()) {
        const bool m = r.metres();
        md << "## Each run's well, measured from its data\n\nA local force law per unit mass, a + c v + k x + k2 x^2 + k3 x^3 - F0 = "
              "g u, fitted on each run's free-flight samples (never the model's): its linear frequency, its local even term "
              "(softer toward the barrier: which well) and, by its barrier, the well's depth.\n\n"
           << "| run | side | x0 [" << (m ? "mm" : r.x_unit()) << "] | frequency [Hz] | k2 per unit mass | depth per unit mass |\n|---|---|---|---|---|---|\n";
        for (const auto& w : r.data_wells)
            md << "| " << w.run + 1 << " | " << (w.side.empty() ? "unclear" : w.side) << " | " << g3(w.x0 * (m ? 1e3 : 1.0), "%.4g") << " | "
               << g3(w.omega / (2 * 3.141592653589793), "%.4g") << " +/- " << g3(w.somega / (2 * 3.141592653589793), "%.2g") << " | "
               << g3(w.k2, "%.3g") << " +/- " << g3(w.sk2, "%.2g") << " | " << (std::isfinite(w.depth) ? g3(w.depth, "%.3g") : std::string("-"))
               << " |\n";
        if (!r.wells_from_data.empty()) md << "\n" << r.wells_from_data << ".\n";
        if (!r.well_frequency.empty()) md << "\n" << r.well_frequency << ".\n";
        md << "\n";
    }
}

// The two wells of the model after, with their asymmetry.
void md_model_wells(std::ostream& md, const FitReport& r) {
    const auto& wa = r.wells_after;
    if (wa.wells.size() == 2 && std::isfinite(wa.hill_x)) {
        const double xs_ = r.metres() ? 1e3 : 1.0;
        const std::string xu_ = r.metres() ? "mm" : r.x_unit();
        const std::string du_ = r.metres() ? "J" : "(data units/s)^2 per unit mass";
        md << "## The two wells (model after)\n\n| well | x [" << xu_ << "] | depth below the hilltop [" << du_
           << "] | linearised omega [rad/s] |\n|---|---|---|---|\n";
        const char* side[2] = {"left", "right"};
        for (int k = 0; k < 2; ++k) {
            const Well& w = wa.wells[static_cast<std::size_t>(k)];
            md << "| " << side[k] << (w.beyond_bumper ? " (beyond the bumper)" : "") << " | " << g3(w.x * xs_, "%.4g") << " +/- "
               << g3(w.sx * xs_, "%.2g") << " | " << g3(w.depth, "%.4g") << " +/- " << g3(w.sdepth, "%.2g") << " | " << g3(w.omega, "%.4g")
               << " +/- " << g3(w.somega, "%.2g") << " |\n";
        }
        md << "\nRight minus left: depth " << g3(wa.depth_asym, "%.3g") << " +/- " << g3(wa.sdepth_asym, "%.2g") << " " << du_ << ", omega "
           << g3(wa.omega_asym, "%.3g") << " +/- " << g3(wa.somega_asym, "%.2g") << " rad/s (uncertainties from the effects found and a fitted "
           << "k2; the other base parameters are taken as given). ";
        std::string visited;
        for (std::size_t k = 0; k < wa.run_wells.size(); ++k)
            visited += (k ? ", " : "") + std::string("run ") + std::to_string(k + 1) + ": " + wa.run_wells[k];
        md << "Runs: " << visited << ". "
           << (r.runs > 1 ? "The runs together constrain both wells."
                          : "One run constrains the well it stays in; an asymmetry between the wells is identifiable only from runs "
                            "in both (fit them together: impactlab fit a.csv b.csv).")
           << "\n\n";
    }
}

// The final gate: what it undid, and the model written.
void md_gate(std::ostream& md, const FitReport& r) {
    md << "## The final gate\n\nThe model written is compared with the model given on every error below, unit by unit (blocks of "
          "rows and samples, shooting windows, impacts, omega bins); a change that makes any of them worse beyond its scatter "
          "is undone, the last change first. ";
    if (r.gate.empty()) md << "Passed: " << r.gate_passed << ".\n\n";
    else {
        md << "It undid:\n\n";
        for (const auto& g : r.gate) md << "- " << g << "\n";
        md << "\nThe model written: " << r.gate_passed << ".\n\n";
    }
}

// The error table: the model given, the fitted baseline where it is a column, and the model written.
void md_errors(std::ostream& md, const FitReport& r) {
    const bool bc = r.baseline_column;
    if (bc)
        md << "## Error of the model given, the fitted baseline (" << r.baseline_step << ") and the model written\n\n"
           << "| measure | given | baseline | written |\n|---|---|---|---|\n";
    else
        md << "## Error before (the model given) and after (the model written)\n\n| measure | before | after |\n|---|---|---|\n";
    using Get = std::function<double(const ErrorSummary&)>;
    auto row = [&](const std::string& name, const Get& get, double scale, const char* f) {
        md << "| " << name << " | " << g3(get(r.error_before) * scale, f) << " | ";
        if (bc) md << g3(get(r.error_baseline) * scale, f) << " | ";
        md << g3(get(r.error_after) * scale, f) << " |\n";
    };
    const auto& b = r.error_before;
    const bool metres = r.metres();
    const double xs = metres ? 1e3 : 1.0;
    const std::string xu = metres ? "mm" : r.x_unit();
    row(std::string("residual RMS [") + r.force_unit() + "]", [](const ErrorSummary& e) { return e.residual_rms_N; }, 1, "%.4g");
    const char* past = " (past the horizon: printed, not judged)";
    row("shooting RMS, 1 period [" + xu + "]" + (r.past_horizon(1.0) ? past : ""), [](const ErrorSummary& e) { return e.shooting_rms_1_m; },
        xs, "%.4g");
    row("shooting RMS, 10 periods [" + xu + "]" + (r.past_horizon(10.0) ? past : ""),
        [](const ErrorSummary& e) { return e.shooting_rms_10_m; }, xs, "%.4g");
    if (b.shooting_rms_judge_m >= 0 && r.horizon_periods != 1.0 && r.horizon_periods != 10.0)
        row("shooting RMS, " + g3(r.horizon_periods) + " periods (the judging horizon) [" + xu + "]",
            [](const ErrorSummary& e) { return e.shooting_rms_judge_m; }, xs, "%.4g");
    if (b.impact.impacts > 0) {
        row("impact law: kappa RMS error", [](const ErrorSummary& e) { return e.impact.kappa_rms; }, 1, "%.3g");
        row("impact law: dwell RMS error [ms]", [](const ErrorSummary& e) { return e.impact.duration_rms_s; }, 1e3, "%.3g");
        row("impact law: bumper level offset [mm]", [](const ErrorSummary& e) { return e.impact.level_offset_m; }, 1e3, "%.3g");
    }
    if (b.diagram_distance_m >= 0)
        row("diagram distance (mean per omega bin) [mm]", [](const ErrorSummary& e) { return e.diagram_distance_m; }, 1e3, "%.4g");
    if (b.simulation_rms_m >= 0)
        row(std::string("free-run simulation RMS (as measured)") + (r.past_horizon(INFINITY) ? past : ""),
            [](const ErrorSummary& e) { return e.simulation_rms_m; }, 1, "%.4g");
    if (b.attractor_x_w1 >= 0) {
        const char* judged = r.past_horizon(INFINITY) ? " (judged: the record is chaotic)" : " (printed: a regular record is judged by its free run)";
        row(std::string("attractor: x distribution, Wasserstein / std x") + judged, [](const ErrorSummary& e) { return e.attractor_x_w1; },
            1, "%.3g");
        row("attractor: v distribution, Wasserstein / std v", [](const ErrorSummary& e) { return e.attractor_v_w1; }, 1, "%.3g");
        if (r.data_well_changes_per_s >= 0)
            row("attractor: well changes per second (record: " + g3(r.data_well_changes_per_s) + ")",
                [](const ErrorSummary& e) { return e.attractor_wells_per_s; }, 1, "%.3g");
        if (b.attractor_spectrum_db >= 0)
            row("attractor: power spectrum, RMS difference [dB]", [](const ErrorSummary& e) { return e.attractor_spectrum_db; }, 1, "%.3g");
    }
    if (b.test_simulation_rms_m >= 0)
        row("free-run simulation RMS on the test rows (as measured)", [](const ErrorSummary& e) { return e.test_simulation_rms_m; }, 1,
            "%.4g");
    if (b.test_shooting_rms_m >= 0)
        row("shooting RMS on the test rows, validation windows [" + xu + "]", [](const ErrorSummary& e) { return e.test_shooting_rms_m; },
            xs, "%.4g");
    if (!r.gate_within.empty()) {
        md << "\nRose, but within the scatter of their units (two standard errors), so not counted as worse:\n\n";
        for (const auto& w : r.gate_within) md << "- " << w << "\n";
    }
    md << "\n" << b.impact.impacts << " impacts found in the data.\n\n";
}

// The first round's candidates, each alone on the baseline residual.
void md_candidates(std::ostream& md, const FitReport& r) {
    md << "## Candidates (first round: each alone on the baseline residual)\n\n"
          "| id | share of residual (in sample) | cross-validated gain | z | coefficients alone | selected |\n|---|---|---|---|---|---|\n";
    for (const auto& c : r.candidates) {
        std::string coef;
        for (const auto& [k, v] : c.coefficients) coef += (coef.empty() ? "" : ", ") + k + " = " + g3(v, "%.4g");
        md << "| " << c.id << " | " << g3(100 * c.gain, "%.2f") << " % | " << g3(100 * c.cv_gain, "%.2f") << " % | " << g3(c.z, "%.1f")
           << " | " << coef << " | " << (c.selected ? "yes" : "") << " |\n";
    }
    md << "\nA candidate is proposed when it lowers the 5-fold block cross-validated residual by at least the minimum share and "
          "its coefficient stands out of the noise (z from serially-correlation-robust standard errors); the held-out "
          "simulation error above then decides.\n\n";
}

// The report as Markdown, section by section.
std::string markdown(const FitReport& r, bool with_plots) {
    std::ostringstream md;
    md_header(md, r);
    md_effects(md, r);
    md_validation(md, r);
    md_base_parameters(md, r);
    md_data_wells(md, r);
    md_model_wells(md, r);
    md_gate(md, r);
    md_errors(md, r);
    md_candidates(md, r);
    if (!r.notes.empty()) {
        md << "## Notes\n\n";
        for (const auto& n : r.notes) md << "- " << n << "\n";
        md << "\n";
    }
    md << "The model with the effects: `model_after.json` (use it with `--model`). Runtime " << g3(r.runtime_s) << " s.\n\n";
    if (with_plots) {
        md << "![residual against x](residual_x.png)\n\n![residual against v](residual_v.png)\n\n";
        if (r.forcing == Forcing::Unbalance) md << "![residual against phi](residual_phi.png)\n\n";
        if (!r.trace.t.empty()) md << "![measured and simulated x(t)](x_t.png)\n\n";
        if (r.impacts.size() >= 3) md << "![impact law](impacts.png)\n\n";
        if (!r.diagram_measured.empty()) md << "![bifurcation diagrams](diagram.png)\n\n";
    }
    return utf8_escaped(md.str());   // a file name in any bytes shows them as \xNN
}

}  // namespace

const char* evidence_name(Evidence e) {
    switch (e) {
    case Evidence::ImpactLaw: return "impact law";
    case Evidence::StrayImpacts: return "stray impacts";
    case Evidence::EquationError: break;
    }
    return "equation error";
}

const char* baseline_name(Baseline b) { return b == Baseline::Fit ? "fit" : "fixed"; }

std::string report_json_text(const FitReport& r) {
    json j;
    j["data"] = {{"source", r.data_source},
                 {"samples", r.samples},
                 {"dt_s", r.dt},
                 {"duration_s", r.duration},
                 {"forcing", forcing_name(r.forcing)},
                 {"sigma_x_m", num(r.sigma_x)},
                 {"omega_min", num(r.omega_min)},
                 {"omega_max", num(r.omega_max)},
                 {"drive_fit_rms_rad", num(r.drive_fit_rms_rad)},
                 {"impacts", r.impacts.size()}};
    j["model"] = r.before.p.name;
    j["baseline"] = baseline_name(r.baseline);
    j["analysis"] = {{"window_s", r.window_s}, {"rows_used", r.rows_used}, {"noise_floor_N", num(r.noise_floor_N)},
                     {"period_s", num(r.period_s)}};
    j["effects_found"] = json::array();
    for (const auto& f : r.effects_found) {
        json e;
        e["id"] = f.id;
        e["explained_fraction"] = num(f.explained_fraction);
        e["parameters"] = json::object();
        for (const auto& [k, v] : f.parameters) e["parameters"][k] = num(v);
        e["uncertainty"] = json::object();
        for (const auto& [k, v] : f.sigma) e["uncertainty"][k] = num(v);
        e["z"] = num(f.z);
        e["evidence"] = evidence_name(f.evidence);
        e["sentence"] = f.sentence;
        e["validation_gain"] = num(f.validation_gain);
        e["validation_z"] = num(f.validation_z);
        e["shape_resolved"] = f.not_told_from.empty();
        if (!f.not_told_from.empty()) e["not_told_from"] = f.not_told_from;
        j["effects_found"].push_back(e);
    }
    j["candidates"] = json::array();
    for (const auto& c : r.candidates)
    {
        json cj{{"id", c.id}, {"explained_fraction_alone", num(c.gain)}, {"cv_gain", num(c.cv_gain)}, {"z", num(c.z)}, {"selected", c.selected}};
        cj["coefficients"] = json::object();
        for (const auto& [k, v] : c.coefficients) cj["coefficients"][k] = num(v);
        j["candidates"].push_back(cj);
    }
    j["effects_rejected"] = json::array();
    for (const auto& f : r.effects_rejected) {
        json e{{"id", f.id}, {"reason", f.reason}, {"validation_gain", num(f.validation_gain)}, {"validation_z", num(f.validation_z)}};
        e["parameters"] = json::object();
        for (const auto& [k, v] : f.parameters) e["parameters"][k] = num(v);
        j["effects_rejected"].push_back(e);
    }
    j["validation"] = {{"horizon_periods", num(r.horizon_periods)}, {"windows", r.validation_windows},
                       {"rms_before", num(r.validation_rms_before_m)}, {"rms_after", num(r.validation_rms_after_m)}};
    j["validation"]["data_horizon"] = {{"measured", r.data_horizon_measured},
                                       {"regular", r.data_regular},
                                       {"free_run", r.data_free_run},
                                       {"doubling_periods", r.data_regular ? json(nullptr) : num(r.data_horizon_periods)},
                                       {"lambda_per_s", num(r.data_lambda)}};
    j["validation"]["growth"] = json::array();
    for (const auto& [L, e] : r.horizon_growth) j["validation"]["growth"].push_back({{"periods", L}, {"shooting_rms", num(e)}});
    j["verdict"] = r.verdict;
    j["remainder"] = json::array();
    for (const auto& [what, share] : r.remainder) j["remainder"].push_back({{"variable", what}, {"share", num(share)}});
    j["runs"] = r.runs;
    auto wells_json = [](const WellReport& w) {
        json o;
        o["wells"] = json::array();
        for (const auto& e : w.wells)
            o["wells"].push_back({{"x", num(e.x)}, {"sx", num(e.sx)}, {"depth_J", num(e.depth)}, {"sdepth_J", num(e.sdepth)},
                                  {"omega", num(e.omega)}, {"somega", num(e.somega)}, {"beyond_bumper", e.beyond_bumper}});
        o["hill_x"] = num(w.hill_x);
        o["depth_asym_J"] = num(w.depth_asym);
        o["sdepth_asym_J"] = num(w.sdepth_asym);
        o["omega_asym"] = num(w.omega_asym);
        o["somega_asym"] = num(w.somega_asym);
        o["run_wells"] = w.run_wells;
        return o;
    };
    j["data_wells"] = json::array();
    for (const auto& w : r.data_wells)
        j["data_wells"].push_back({{"run", w.run + 1}, {"side", w.side}, {"x0", num(w.x0)}, {"omega", num(w.omega)}, {"omega_sigma", num(w.somega)},
                                   {"k2", num(w.k2)}, {"k2_sigma", num(w.sk2)}, {"depth", num(w.depth)}});
    j["wells_from_data"] = r.wells_from_data;
    j["well_frequency"] = r.well_frequency;
    j["base_parameters"] = json::array();
    for (const auto& b : r.base_estimates) {
        j["base_parameters"].push_back({{"name", b.name}, {"value", num(b.value)}, {"sigma", num(b.sigma)}});
        if (!b.stood_in_by.empty()) j["base_parameters"].back()["not_separated_from"] = b.stood_in_by;
    }
    j["unseparated"] = json::array();
    for (const auto& u : r.unseparated)
        j["unseparated"].push_back({{"a", u.a},
                                    {"b", u.b},
                                    {"correlation", num(u.correlation)},
                                    {"pinned", u.a + (u.ratio ? " / " : " * ") + u.b},
                                    {"value", num(u.value)},
                                    {"sigma", num(u.sigma)}});
    j["wells_before"] = wells_json(r.wells_before);
    j["wells_after"] = wells_json(r.wells_after);
    j["units"] = {{"x", r.x_unit()}, {"force", r.force_unit()}};
    j["error_before"] = errors_json(r.error_before);
    j["error_after"] = errors_json(r.error_after);
    if (r.baseline_column) {
        j["error_baseline"] = errors_json(r.error_baseline);
        j["baseline_step"] = r.baseline_step;
    }
    j["model_before"] = model_json(r.before);
    j["model_after"] = model_json(r.after);
    j["impacts"] = json::array();
    for (const auto& im : r.impacts)
        j["impacts"].push_back({{"t", im.t}, {"v_minus", im.v_minus}, {"v_plus", im.v_plus}, {"dwell_s", im.dwell}, {"level_m", im.level}});
    j["notes"] = r.notes;
    j["gate"] = {{"undone", r.gate}, {"passed", r.gate_passed}, {"rose_within_scatter", r.gate_within}};
    j["runtime_s"] = r.runtime_s;
    j["run_offsets"] = json::array();
    for (const auto& o : r.run_offsets) j["run_offsets"].push_back({{"run", o.run + 1}, {"offset", num(o.offset)}, {"sigma", num(o.sigma)}});
    j["x_highpass_hz"] = r.x_highpass_hz;
    return json_dump(std::move(j), 2) + "\n";   // a file name in any bytes
}

void write_report(const FitReport& r, const std::string& dir, bool with_plots) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir)) throw std::runtime_error(dir + ": cannot create the report directory");
    // The report's files are one unit: all written beside their names, then renamed into place together, so a
    // failure (a full disk) leaves an old report whole instead of a new JSON beside an old Markdown.
    OutputGroup group;
    auto write = [&](const std::string& name, const std::string& text) { write_file_whole((fs::path(dir) / name).string(), text); };
    write("report.json", report_json_text(r));
    write("model_after.json", params_to_json_text(r.after.p));
    if (with_plots) plots(r, dir);
    write("report.md", markdown(r, with_plots));
    group.commit();
}

}  // namespace impactlab::identify
