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
    Eigen::MatrixXd J(R.size(), p);
    for (Eigen::Index k = 0; k < p; ++k) {
        double* v = params[static_cast<std::size_t>(k)].value;
        const double v0 = *v, h = std::max(1e-4 * std::abs(v0), 1e-4 * base_scale(params[static_cast<std::size_t>(k)].name, pr, m));
        *v = v0 + h;
        residual(pr, m, Rp, pw);
        *v = v0;
        J.col(k) = (Rp - R) / h;
    }
    const double s2 = R.squaredNorm() / static_cast<double>(std::max<Eigen::Index>(1, R.size() - p));
    const double tau = corr_time(R, 2 * fs.hac_lag);
    // Scaled to unit columns first, so that parameters of very different sizes (k and a3 in strain) do not
    // make the normal matrix singular in floating point.
    Eigen::VectorXd scale(p);
    for (Eigen::Index k = 0; k < p; ++k) scale[k] = std::max(J.col(k).norm(), 1e-300);
    const Eigen::MatrixXd Js = J * scale.cwiseInverse().asDiagonal();
    const Eigen::MatrixXd A = Js.transpose() * Js;
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(A);
    // A direction the data do not see at all (an eigenvalue below 1e-14 of the largest: floating-point noise) is
    // left out of the inverse, and the parameters along it get no finite uncertainty of their own.
    const Eigen::VectorXd ev = es.eigenvalues();
    const double emax = ev.maxCoeff();
    Eigen::MatrixXd inv = Eigen::MatrixXd::Zero(p, p);
    std::vector<char> unseen(static_cast<std::size_t>(p), 0);
    for (Eigen::Index k = 0; k < p; ++k) {
        if (ev[k] > 1e-14 * emax) {
            inv += es.eigenvectors().col(k) * es.eigenvectors().col(k).transpose() / ev[k];
        } else {
            for (Eigen::Index i = 0; i < p; ++i)
                if (std::abs(es.eigenvectors()(i, k)) > 1e-3) unseen[static_cast<std::size_t>(i)] = 1;
        }
    }
    const Eigen::MatrixXd cov = s2 * tau * (scale.cwiseInverse().asDiagonal() * inv * scale.cwiseInverse().asDiagonal());
    for (Eigen::Index k = 0; k < p; ++k) {
        const BaseParam& b = params[static_cast<std::size_t>(k)];
        rep.base_estimates.push_back({b.name, *b.value, unseen[static_cast<std::size_t>(k)] ? INFINITY : std::sqrt(std::max(0.0, cov(k, k)))});
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
            rep.unseparated.push_back(u);
        }
}

}  // namespace impactlab::identify::detail
