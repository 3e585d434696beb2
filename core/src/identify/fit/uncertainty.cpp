// What the data tell of the base parameters written: each one's standard error from the equation error's
// Jacobian (the residual's variance and correlation time), and the pairs the data do not separate, reported
// as the one combination they pin (a ratio or a product), never as two findings.
#include "identify/fit/session.hpp"

namespace impactlab::identify::detail {

void uncertainty_stage(FitSession& fs) {
    const Prep& pr = fs.prep;
    FitReport& rep = fs.rep;
    rep.base_estimates.clear();
    rep.unseparated.clear();
    if (rep.baseline != Baseline::Fit || fs.base_names.empty() || pr.rows.size() < 20) return;
    Model m = rep.after;
    std::vector<double> pw;
    Eigen::VectorXd R, Rp;
    residual(pr, m, R, pw);
    const std::vector<BaseParam> params = base_params(m, fs.base_names);
    const auto p = static_cast<Eigen::Index>(params.size());
    // The found force effects' parameters beside them: a base parameter an effect can stand in for (k and a3
    // beside a generic force of x, which spans every cubic) is no finding, and its error must say so.
    std::vector<std::size_t> owner;
    std::vector<Knob> eff = found_effect_knobs(m, fs.base, fs.screen.cands, &owner);
    std::vector<double*> cols;
    for (const BaseParam& b : params) cols.push_back(b.value);
    for (std::size_t k = 0; k < eff.size(); ++k)
        if (owner[k] != SIZE_MAX) cols.push_back(eff[k].value);   // a base-changing effect's knob is a base parameter
    const auto pa = static_cast<Eigen::Index>(cols.size());
    Eigen::MatrixXd J(R.size(), pa);
    for (Eigen::Index k = 0; k < pa; ++k) {
        double* v = cols[static_cast<std::size_t>(k)];
        const double scale0 = k < p ? base_scale(params[static_cast<std::size_t>(k)].name, pr, m) : 0.0;
        const double v0 = *v, h = std::max({1e-4 * std::abs(v0), 1e-4 * scale0, 1e-12});
        *v = v0 + h;
        residual(pr, m, Rp, pw);
        *v = v0;
        J.col(k) = (Rp - R) / h;
    }
    const double s2 = R.squaredNorm() / static_cast<double>(std::max<Eigen::Index>(1, R.size() - pa));
    const double tau = corr_time(R, 2 * fs.hac_lag);
    // The covariance of the first q columns' parameters, the others held; `unseen` marks those along a direction
    // the data do not see at all (an eigenvalue below 1e-12 of the largest: the finite differences' noise),
    // which is left out of the inverse. Scaled to unit columns first, so that parameters of very different
    // sizes (k and a3 in strain) do not make the normal matrix singular in floating point.
    auto covariance = [&](Eigen::Index q, std::vector<char>& unseen) {
        const Eigen::MatrixXd Jq = J.leftCols(q);
        Eigen::VectorXd scale(q);
        for (Eigen::Index k = 0; k < q; ++k) scale[k] = std::max(Jq.col(k).norm(), 1e-300);
        const Eigen::MatrixXd Js = Jq * scale.cwiseInverse().asDiagonal();
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Js.transpose() * Js);
        const Eigen::VectorXd ev = es.eigenvalues();
        const double emax = ev.maxCoeff();
        Eigen::MatrixXd inv = Eigen::MatrixXd::Zero(q, q);
        unseen.assign(static_cast<std::size_t>(q), 0);
        for (Eigen::Index k = 0; k < q; ++k) {
            if (ev[k] > 1e-12 * emax) {
                inv += es.eigenvectors().col(k) * es.eigenvectors().col(k).transpose() / ev[k];
            } else {
                for (Eigen::Index i = 0; i < q; ++i)
                    if (std::abs(es.eigenvectors()(i, k)) > 1e-3) unseen[static_cast<std::size_t>(i)] = 1;
            }
        }
        return Eigen::MatrixXd(s2 * tau * (scale.cwiseInverse().asDiagonal() * inv * scale.cwiseInverse().asDiagonal()));
    };
    std::vector<char> unseen, unseen_held;
    const Eigen::MatrixXd cov = covariance(pa, unseen), cov_held = covariance(p, unseen_held);
    // A base parameter that an effect stands in for: unseen beside the effects, or ten times less certain than
    // with them held.
    std::string by;
    for (const FoundEffect& f : rep.effects_found)
        if (const EffectLaw* law = find_effect(f.id); law && law->kind != EffectKind::Sensor) by += (by.empty() ? "" : ", ") + f.id;
    auto stood_in = [&](Eigen::Index k) {
        const auto i = static_cast<std::size_t>(k);
        return pa > p && !unseen_held[i] && (unseen[i] || cov(k, k) > 100.0 * cov_held(k, k));
    };
    for (Eigen::Index k = 0; k < p; ++k) {
        const BaseParam& b = params[static_cast<std::size_t>(k)];
        rep.base_estimates.push_back({b.name, *b.value, unseen[static_cast<std::size_t>(k)] ? INFINITY : std::sqrt(std::max(0.0, cov(k, k))),
                                      stood_in(k) ? by : std::string()});
    }
    // Pairs the data do not separate: correlation beyond 0.98. Moving together they pin their ratio, against
    // each other their product; its relative error comes from the same covariance (in logs).
    for (Eigen::Index i = 0; i < p; ++i)
        for (Eigen::Index j = i + 1; j < p; ++j) {
            const double vi = *params[static_cast<std::size_t>(i)].value, vj = *params[static_cast<std::size_t>(j)].value;
            const double si = cov(i, i), sj = cov(j, j);
            if (!(vi != 0 && vj != 0) || !(si > 0) || !(sj > 0)) continue;
            const double rho = cov(i, j) / std::sqrt(si * sj);
            if (!(std::abs(rho) > 0.98)) continue;
            UnseparatedPair u;
            u.a = params[static_cast<std::size_t>(i)].name;
            u.b = params[static_cast<std::size_t>(j)].name;
            u.correlation = rho;
            u.ratio = rho > 0;
            u.value = u.ratio ? vi / vj : vi * vj;
            const double rel2 = si / (vi * vi) + sj / (vj * vj) + (u.ratio ? -2.0 : 2.0) * cov(i, j) / (vi * vj);
            u.sigma = std::abs(u.value) * std::sqrt(std::max(0.0, rel2));
            if (!(u.sigma < std::abs(u.value))) continue;   // the combination is not pinned either: no finding to report
            // A pair is unseparated where what it pins together is known far better than either alone. Two well-pinned
            // values can still correlate (k and a3 where the motion spans little of the travel trade additively, not
            // as a ratio or a product): their product, less certain than each, is no combination the data pin.
            const double rel_u = u.sigma / std::abs(u.value),
                         rel_min = std::min(std::sqrt(si) / std::abs(vi), std::sqrt(sj) / std::abs(vj));
            if (!(rel_u < 0.5 * rel_min)) continue;
            rep.unseparated.push_back(u);
        }
}

}  // namespace impactlab::identify::detail
