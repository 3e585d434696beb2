// Regression statistics for the effect selection: block cross-validation from per-block Gram matrices,
// Newey-West (HAC) covariances for serially correlated residuals, chi-square to z.
#include <algorithm>
#include <cmath>

#include "identify/internal.hpp"

namespace impactlab::identify::detail {

Folds make_folds(const Eigen::MatrixXd& X, const Eigen::VectorXd& R, int K) {
    Folds f;
    f.K = K;
    const Eigen::Index n = X.rows(), p = X.cols();
    f.Gt = Eigen::MatrixXd::Zero(p, p);
    f.bt = Eigen::VectorXd::Zero(p);
    for (int k = 0; k < K; ++k) {
        const Eigen::Index a = n * k / K, b = n * (k + 1) / K;
        const auto Xk = X.middleRows(a, b - a);
        const auto Rk = R.segment(a, b - a);
        f.G.push_back(Xk.transpose() * Xk);
        f.b.push_back(Xk.transpose() * Rk);
        f.rr.push_back(Rk.squaredNorm());
        f.Gt += f.G.back();
        f.bt += f.b.back();
        f.rrt += f.rr.back();
    }
    return f;
}

namespace {
Eigen::VectorXd solve_sub(const Eigen::MatrixXd& G, const Eigen::VectorXd& b, const std::vector<int>& cols) {
    const auto p = static_cast<Eigen::Index>(cols.size());
    Eigen::MatrixXd g(p, p);
    Eigen::VectorXd r(p);
    for (Eigen::Index i = 0; i < p; ++i) {
        r[i] = b[cols[static_cast<std::size_t>(i)]];
        for (Eigen::Index j = 0; j < p; ++j) g(i, j) = G(cols[static_cast<std::size_t>(i)], cols[static_cast<std::size_t>(j)]);
    }
    // Scale-free ridge: keeps nearly collinear sets solvable without moving well-posed ones.
    for (Eigen::Index i = 0; i < p; ++i) g(i, i) += 1e-10 * g(i, i) + 1e-300;
    return g.ldlt().solve(r);
}
double quad(const Eigen::MatrixXd& G, const Eigen::VectorXd& b, const std::vector<int>& cols, const Eigen::VectorXd& beta,
            double rr) {
    double s = rr;
    for (std::size_t i = 0; i < cols.size(); ++i) {
        const auto ii = static_cast<Eigen::Index>(i);
        s -= 2 * beta[ii] * b[cols[i]];
        for (std::size_t j = 0; j < cols.size(); ++j) s += beta[ii] * beta[static_cast<Eigen::Index>(j)] * G(cols[i], cols[j]);
    }
    return s;
}
}  // namespace

void cv_sse(const Folds& f, const std::vector<int>& cols, double& cv, double& in_sample, Eigen::VectorXd* beta) {
    if (cols.empty()) {
        cv = in_sample = f.rrt;
        if (beta) beta->resize(0);
        return;
    }
    cv = 0;
    for (int k = 0; k < f.K; ++k) {
        const auto kk = static_cast<std::size_t>(k);
        const Eigen::VectorXd b = solve_sub(f.Gt - f.G[kk], f.bt - f.b[kk], cols);
        cv += quad(f.G[kk], f.b[kk], cols, b, f.rr[kk]);
    }
    const Eigen::VectorXd bt = solve_sub(f.Gt, f.bt, cols);
    in_sample = quad(f.Gt, f.bt, cols, bt, f.rrt);
    if (beta) *beta = bt;
}

Eigen::MatrixXd hac_cov(const Eigen::MatrixXd& X, const Eigen::VectorXd& e, int L) {
    // Batch means: the scores X_t e_t summed over blocks of 2L rows are nearly independent when the
    // residual's correlation dies out within L rows; S = sum over blocks of s_b s_b'.
    const Eigen::Index n = X.rows(), p = X.cols();
    const Eigen::Index B = std::max<Eigen::Index>(1, 2 * L);
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(p, p);
    for (Eigen::Index a = 0; a < n; a += B) {
        const Eigen::Index len = std::min(B, n - a);
        const Eigen::VectorXd s = X.middleRows(a, len).transpose() * e.segment(a, len);
        S.noalias() += s * s.transpose();
    }
    Eigen::MatrixXd G = X.transpose() * X;
    for (Eigen::Index i = 0; i < p; ++i) G(i, i) += 1e-10 * G(i, i) + 1e-300;
    const Eigen::MatrixXd Gi = G.ldlt().solve(Eigen::MatrixXd::Identity(p, p));
    return Gi * S * Gi;
}

double chi2_to_z(double W, int p) {
    if (!(W > 0)) return 0.0;
    if (p == 1) return std::sqrt(W);
    const double k = 2.0 / (9.0 * p);
    return (std::cbrt(W / p) - (1.0 - k)) / std::sqrt(k);
}

double median_se(const std::vector<double>& x, double center, double floor) {
    std::vector<double> dev;
    for (double v : x)
        if (std::isfinite(v)) dev.push_back(std::abs(v - center));
    if (dev.empty()) return 0.0;
    return std::max(1.2533 * 1.4826 * median(dev), floor) / std::sqrt(static_cast<double>(dev.size()));
}

double f_to_z(double F, double d1, double d2) {
    if (!(F > 0) || !(d1 > 0) || !(d2 > 0)) return 0.0;
    const double a = 2.0 / (9.0 * d1), b = 2.0 / (9.0 * d2), f3 = std::cbrt(F);
    return ((1.0 - b) * f3 - (1.0 - a)) / std::sqrt(b * f3 * f3 + a);
}

}  // namespace impactlab::identify::detail
