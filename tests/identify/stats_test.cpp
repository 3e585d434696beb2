// The selection's statistics (core/src/identify/stats.cpp): block cross-validation from per-block Gram
// matrices against a direct refit per fold, batch-means (HAC) covariances, and the chi-square and F to z maps.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "identify/internal.hpp"

namespace dt = impactlab::identify::detail;

namespace {

// R = 2 x0 - x1 + noise over n rows, and a third column of pure noise.
void regression(int n, unsigned seed, Eigen::MatrixXd& X, Eigen::VectorXd& R) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> g(0.0, 1.0);
    X.resize(n, 3);
    R.resize(n);
    for (int i = 0; i < n; ++i) {
        X(i, 0) = std::sin(0.01 * i);
        X(i, 1) = g(rng);
        X(i, 2) = g(rng);
        R[i] = 2.0 * X(i, 0) - X(i, 1) + 0.1 * g(rng);
    }
}

}  // namespace

TEST_CASE("stats: cv_sse's in-sample fit is least squares; its cross-validated SSE is each fold's refit without it") {
    Eigen::MatrixXd X;
    Eigen::VectorXd R;
    regression(1000, 1, X, R);
    const dt::Folds f = dt::make_folds(X, R, 5);
    double cv = 0, in = 0;
    Eigen::VectorXd beta;
    dt::cv_sse(f, {0, 1}, cv, in, &beta);
    const Eigen::MatrixXd X01 = X.leftCols(2);
    const Eigen::VectorXd ols = X01.colPivHouseholderQr().solve(R);
    CHECK(beta[0] == doctest::Approx(ols[0]).epsilon(1e-8));
    CHECK(beta[1] == doctest::Approx(ols[1]).epsilon(1e-8));
    CHECK(beta[0] == doctest::Approx(2.0).epsilon(0.02));
    CHECK(in == doctest::Approx((R - X01 * ols).squaredNorm()).epsilon(1e-6));
    // The cross-validated SSE by hand: each block predicted by a fit to the other four.
    double cv_direct = 0;
    for (int k = 0; k < 5; ++k) {
        const Eigen::Index a = 1000 * k / 5, b = 1000 * (k + 1) / 5;
        Eigen::MatrixXd Xo(1000 - (b - a), 2);
        Eigen::VectorXd Ro(1000 - (b - a));
        Xo << X01.topRows(a), X01.bottomRows(1000 - b);
        Ro << R.head(a), R.tail(1000 - b);
        const Eigen::VectorXd bk = Xo.colPivHouseholderQr().solve(Ro);
        cv_direct += (R.segment(a, b - a) - X01.middleRows(a, b - a) * bk).squaredNorm();
    }
    CHECK(cv == doctest::Approx(cv_direct).epsilon(1e-6));
    CHECK(cv > in);
    // A column of noise lowers the in-sample SSE a little and raises the cross-validated one.
    double cv3 = 0, in3 = 0;
    dt::cv_sse(f, {0, 1, 2}, cv3, in3);
    CHECK(in3 <= in);
    CHECK(cv3 > cv - 1e-9 * cv);
    double cv0 = 0, in0 = 0;
    dt::cv_sse(f, {}, cv0, in0);
    CHECK(cv0 == doctest::Approx(R.squaredNorm()));
}

TEST_CASE("stats: hac_cov gives the OLS variance for white noise and a larger one for correlated noise") {
    std::mt19937 rng(3);
    std::normal_distribution<double> g(0.0, 1.0);
    const int n = 20000;
    Eigen::MatrixXd X(n, 1);
    Eigen::VectorXd white(n), red(n);
    double ar = 0;
    for (int i = 0; i < n; ++i) {
        X(i, 0) = 1.0;
        white[i] = g(rng);
        ar = 0.9 * ar + g(rng);   // AR(1): long-run variance (1 / (1 - 0.9))^2 = 100 per unit innovation
        red[i] = ar;
    }
    // White noise of unit variance: var(mean) = 1/n, with any block length.
    CHECK(dt::hac_cov(X, white, 0)(0, 0) * n == doctest::Approx(1.0).epsilon(0.05));
    CHECK(dt::hac_cov(X, white, 10)(0, 0) * n == doctest::Approx(1.0).epsilon(0.15));
    // AR(1) noise: blocks much longer than the correlation time see its long-run variance, 100.
    CHECK(dt::hac_cov(X, red, 100)(0, 0) * n == doctest::Approx(100.0).epsilon(0.3));
    CHECK(dt::hac_cov(X, red, 0)(0, 0) * n < 10.0);   // the white-noise formula underestimates it
}

TEST_CASE("stats: chi2_to_z and f_to_z map their distributions' quantiles onto the normal's") {
    CHECK(dt::chi2_to_z(9.0, 1) == doctest::Approx(3.0));
    CHECK(dt::chi2_to_z(0.0, 3) == 0.0);
    // chi-square(5) at its 97.5 % quantile 12.8325 is z = 1.96 (Wilson-Hilferty is good to ~0.01 there).
    CHECK(dt::chi2_to_z(12.8325, 5) == doctest::Approx(1.96).epsilon(0.01));
    // F(5, 30) and F(3, 100) at their 97.5 % quantiles (3.0265, 3.2496) are z = 1.96.
    CHECK(dt::f_to_z(3.0265, 5, 30) == doctest::Approx(1.96).epsilon(0.01));
    CHECK(dt::f_to_z(3.2496, 3, 100) == doctest::Approx(1.96).epsilon(0.01));
    CHECK(dt::f_to_z(3.5, 5, 30) > dt::f_to_z(3.0265, 5, 30));
    // Large d2: F(d1, inf) = chi2(d1) / d1.
    CHECK(dt::f_to_z(12.8325 / 5.0, 5, 1e9) == doctest::Approx(dt::chi2_to_z(12.8325, 5)).epsilon(0.01));
    CHECK(dt::f_to_z(-1.0, 1, 10) == 0.0);
}

// Expected to fail today: for d1 = 1 (t_test_z's t^2) Paulson's cube root reads F as a one-sided 1-df
// chi-square tail, so t = 1.96 becomes z = 1.66 at any sample size, unlike chi2_to_z(W, 1) = sqrt(W). The
// degrees of freedom are counted right (d2 = n - 1); the mapping is the conservative part. Wallace's t-to-z
// approximation passes this test but moves the shared data's fit reports (golden s1, s2), so it waits for
// a recovery matrix and null check; when it lands, should_fail goes.
TEST_CASE("stats: f_to_z with one numerator degree of freedom is t's normal equivalent (t_test_z)" * doctest::should_fail()) {
    // Student's t quantiles: t(0.975; 4) = 2.776445 and t(0.975; 29) = 2.045230 have two-sided p = 0.05,
    // z = 1.959964; t(0.995; 9) = 3.249836 has p = 0.01, z = 2.575829.
    CHECK(dt::f_to_z(2.776445 * 2.776445, 1, 4) == doctest::Approx(1.959964).epsilon(0.005));
    CHECK(dt::f_to_z(2.045230 * 2.045230, 1, 29) == doctest::Approx(1.959964).epsilon(0.002));
    CHECK(dt::f_to_z(3.249836 * 3.249836, 1, 9) == doctest::Approx(2.575829).epsilon(0.005));
    // Many degrees of freedom: t is normal, as chi2_to_z(t^2, 1) = |t| says.
    CHECK(dt::f_to_z(9.0, 1, 1e9) == doctest::Approx(dt::chi2_to_z(9.0, 1)).epsilon(1e-6));
}

TEST_CASE("stats: median_se is 1.2533 x 1.4826 MAD / sqrt(n), its scale floored, non-finite values left out") {
    const std::vector<double> x{1, 2, 3, 4, 100};   // |x - 3| = 2, 1, 0, 1, 97: MAD 1, the outlier costs nothing
    CHECK(dt::median_se(x, 3.0) == 1.2533 * 1.4826 / std::sqrt(5.0));
    CHECK(dt::median_se(x, 3.0, 2.0) == 2.0 / std::sqrt(5.0));
    CHECK(dt::median_se(x, 3.0, 1.0) == 1.2533 * 1.4826 / std::sqrt(5.0));   // the floor only from below
    const double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK(dt::median_se({1, 2, nan, 3, 4, 100}, 3.0) == dt::median_se(x, 3.0));
    CHECK(dt::median_se({}, 0.0, 1.0) == 0.0);
    CHECK(dt::median_se({nan}, 0.0) == 0.0);
}
