// Stage 5 of the fit: the impact law.
#include "identify/fit/session.hpp"

namespace impactlab::identify::detail {

namespace {

// A bumper offset: the measured flat tops against the same impacts simulated with the model (pred), their
// median shift standing out of its scatter. Found: the shift that puts the simulated flat tops on the measured
// ones is applied to fs.after, and pred is its impacts then.
void bumper_offset_stage(FitSession& fs, PredictedImpacts& pred) {
    const Prep& pr = fs.prep;
    const FitOptions& o = fs.o;
    Model& after = fs.after;
    const double g = after.sensor_gain();
    std::vector<double> dlev;
    for (std::size_t k = 0; k < pr.impacts.size(); ++k)
        if (pred.ok[k]) dlev.push_back((pr.impacts[k].level - pred.obs[k].level) / g);
    const std::size_t ni = dlev.size();
    if (ni < 3) return;
    const double med = median(dlev);
    const double se = median_se(dlev, med, 0.3 * pr.sigma_x);
    const double delta = med;
    if (!(std::abs(delta) / se >= o.z_threshold && std::abs(delta) > 2.0 * pr.sigma_x + 1e-7)) return;
    double sb = 0, sa = 0;
    for (double l : dlev) {
        sb += l * l;
        sa += (l - med) * (l - med);
    }
    FoundEffect f;
    f.id = "bumper_offset";
    f.evidence = Evidence::ImpactLaw;
    f.explained_fraction = sb > 0 ? 1.0 - sa / sb : 0.0;
    f.parameters = {{"dx", delta}};
    f.sigma = {{"dx", se}};
    f.z = std::abs(delta) / se;
    // The shift that puts the simulated flat tops on the measured ones: the forces at the moved
    // bumper differ, and a compliant contact's apparent penetration with them.
    const Model at_nominal = after;
    const double dx = fit_bumper_shift(pr, after, std::vector<char>(pr.impacts.size(), 1), o.rtol, 0.05 * se);
    pred = predict_impacts(pr, after, o.rtol);
    f.parameters = {{"dx", dx}};
    f.z = std::abs(dx) / se;
    f.sentence = sentence("bumper_offset", at_nominal, f.parameters, f.sigma, fs.sc);
    fs.rep.effects_found.push_back(std::move(f));
}

// An impact law (the row's: the dwell at the bumper, or the restitution) against the model's, impact by impact
// (pred: the impacts simulated with the model). Found: applied to fs.after.
void impact_law_row(FitSession& fs, const BaseEffect& row, const PredictedImpacts& pred) {
    const Prep& pr = fs.prep;
    const FitOptions& o = fs.o;
    const SentenceContext& sc = fs.sc;
    Model& after = fs.after;
    FitReport& rep = fs.rep;
    const std::string& which = row.info.id;
    const bool dur = row.impacts == ImpactTrait::Dwell;
    // The impacts the model also makes, measured and simulated.
    const ImpactLawData data = impact_law_data(pr, after, dur, pred.ok);
    const ImpactLawData simulated_data = [&] {
        ImpactLawData s;
        for (std::size_t k = 0; k < pr.impacts.size(); ++k)
            if (pred.ok[k] && (dur || pr.impacts[k].v_minus >= 0.02))
                s.obs.push_back(dur ? pred.obs[k].t_out - pred.obs[k].t_in : apparent_kappa(pred.obs[k]));
        return s;
    }();
    const std::vector<double>& vm = data.vm;
    const std::vector<double>& obs = data.obs;
    const auto n = static_cast<Eigen::Index>(vm.size());
    if (n < 3) return;
    const Eigen::VectorXd model_pred = Eigen::Map<const Eigen::VectorXd>(simulated_data.obs.data(), n);
    auto law = [&](const Eigen::VectorXd& th) { return impact_law_residual(data, th); };
    double mean = 0;
    for (double v : obs) mean += v;
    mean /= static_cast<double>(n);
    // A constant first; the full law (value at low speed, at high speed, decay rate) only if the data
    // clearly ask for it.
    Eigen::VectorXd th(3), lo(3), hi(3);
    th << mean, mean, 0.0;
    double ss_const = 0;
    for (double v : obs) ss_const += (v - mean) * (v - mean);
    Eigen::MatrixXd C = Eigen::MatrixXd::Zero(3, 3);
    C(0, 0) = C(1, 1) = C(0, 1) = C(1, 0) = 1.0 / static_cast<double>(n);
    double sa = ss_const;
    if (n >= 8) {
        Eigen::VectorXd full(3);
        full << mean, mean, 1.0;
        lo << 0, 0, 0;
        hi << 1.0, 1.0, 50.0;
        const Eigen::MatrixXd Cf = lm_small(law, full, lo, hi);
        const double sf = law(full).squaredNorm();
        const double s2f = std::max(sf / (static_cast<double>(n) - 3.0), dur ? std::pow(0.05 * pr.dt, 2) : 1e-4);
        if (chi2_to_z((ss_const - sf) / s2f, 2) >= 3.0) {
            th = full;
            C = Cf;
            sa = sf;
        }
    }
    // The paired differences measured - simulated: an effect shifts them (a constant) or tilts them
    // with the approach speed; under the model they scatter around zero. Wald test on both.
    double sb = 0, vbar = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
        sb += std::pow(obs[static_cast<std::size_t>(i)] - model_pred[i], 2);
        vbar += vm[static_cast<std::size_t>(i)];
    }
    vbar /= static_cast<double>(n);
    Eigen::MatrixXd Xd(n, 2);
    Eigen::VectorXd dd(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        Xd(i, 0) = 1.0;
        Xd(i, 1) = vm[static_cast<std::size_t>(i)] - vbar;
        dd[i] = obs[static_cast<std::size_t>(i)] - model_pred[i];
    }
    Eigen::Matrix2d XtX = Xd.transpose() * Xd;
    XtX(1, 1) += 1e-12 * XtX(0, 0) + 1e-300;
    const Eigen::Vector2d bd = XtX.ldlt().solve(Xd.transpose() * dd);
    const double rss_d = (dd - Xd * bd).squaredNorm();
    const double floor_var = dur ? std::pow(0.05 * pr.dt, 2) : 1e-4;
    const double s2d = std::max(rss_d / std::max(1.0, static_cast<double>(n) - 2.0), 2.0 * floor_var);
    const double W = bd.dot(XtX * bd) / s2d;
    const double z = f_to_z(W / 2.0, 2.0, std::max(1.0, static_cast<double>(n) - 2.0));
    const double s2 = std::max(sa / std::max<double>(1.0, static_cast<double>(n) - 3.0), floor_var);
    // Practical size: the systematic part of the differences, not their scatter.
    const double shift_rms = std::sqrt((Xd * bd).squaredNorm() / static_cast<double>(n));
    const bool practical = dur ? shift_rms > 0.2 * pr.dt : shift_rms > 0.02;
    // A handful of impacts cannot reach the equation error's z; the held-out validation decides.
    if (z >= std::min(o.z_threshold, 3.0) && practical && sb > 0) {
        FoundEffect f;
        f.id = which;
        f.evidence = Evidence::ImpactLaw;
        f.explained_fraction = 1.0 - sa / sb;
        const auto nm = impact_law_names(dur);
        for (int k = 0; k < 3; ++k) {
            f.parameters.emplace_back(nm[k], th[k]);
            f.sigma.emplace_back(nm[k], std::sqrt(std::max(0.0, C(k, k) * s2)));
        }
        f.z = z;
        f.sentence = sentence(which, after, f.parameters, f.sigma, sc);
        apply_effect(after, which, f.parameters);
        rep.effects_found.push_back(std::move(f));
    }
}

}  // namespace

// Stage 5: the impact law. Each measured impact is compared with the same impact simulated with the model
// (predict_impacts): a bumper offset moves the flat tops, a finite impact duration or another restitution
// shifts or tilts the paired differences with the approach speed. What is found is applied to `after`.
void impact_law_stage(FitSession& fs) {
    // So a compliant bumper's apparent penetration or a sampled flat top is never mistaken for an effect.
    if (!fs.after.bumper() || fs.prep.impacts.size() < 3) return;
    PredictedImpacts pred = predict_impacts(fs.prep, fs.after, fs.o.rtol);
    bumper_offset_stage(fs, pred);
    // The dwell time and the restitution against the model's, impact by impact.
    for (const BaseEffect& row : base_effects())
        if (row.impacts == ImpactTrait::Dwell || row.impacts == ImpactTrait::Rebound) impact_law_row(fs, row, pred);
}

}  // namespace impactlab::identify::detail
