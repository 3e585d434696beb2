// What the equation error left after the fit depends on: its cross-validated share explained by smooth
// functions of each variable alone (x, v, the forcing phase, time, the time since the last impact). The
// verdict names them, so a remainder the library could not express is described rather than called noise.
#include <algorithm>
#include <cmath>

#include "identify/internal.hpp"

namespace impactlab::identify::detail {

namespace {

// Legendre polynomials P1..Pdeg of z in [-1, 1] into columns c0.. of X.
void legendre(Eigen::MatrixXd& X, Eigen::Index row, Eigen::Index c0, double z, int deg) {
    double p0 = 1, p1 = z;
    X(row, c0) = p1;
    for (int k = 2; k <= deg; ++k) {
        const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
        X(row, c0 + k - 1) = p2;
        p0 = p1;
        p1 = p2;
    }
}

double scaled(double v, double lo, double hi) { return hi > lo ? std::clamp(2.0 * (v - lo) / (hi - lo) - 1.0, -1.0, 1.0) : 0.0; }

}  // namespace

std::vector<std::pair<std::string, double>> remainder_dependence(const Prep& pr, const Eigen::VectorXd& R) {
    std::vector<std::pair<std::string, double>> out;
    const auto n = static_cast<Eigen::Index>(pr.rows.size());
    if (n < 50 || R.size() != n) return out;
    const MeasuredData& d = *pr.data;
    constexpr int kPoly = 8, kTime = 4, kHarm = 4, kImpactBins = 6;
    const bool phase = pr.phi_forced, impacts = pr.impacts.size() >= 3;
    // Column layout: a constant, then each variable's block.
    const Eigen::Index cx = 1, cv = cx + kPoly, cp = cv + kPoly, ct = cp + (phase ? 2 * kHarm : 0), ci = ct + kTime,
                       ncol = ci + (impacts ? kImpactBins : 0);
    double xlo = INFINITY, xhi = -INFINITY, vlo = INFINITY, vhi = -INFINITY;
    for (std::size_t i : pr.rows) {
        xlo = std::min(xlo, pr.xs[i]);
        xhi = std::max(xhi, pr.xs[i]);
        vlo = std::min(vlo, pr.vs[i]);
        vhi = std::max(vhi, pr.vs[i]);
    }
    const double t0 = d.t.front(), t1 = d.t.back();
    Eigen::MatrixXd X = Eigen::MatrixXd::Zero(n, ncol);
    std::size_t next_impact = 0;
    double last_impact = -INFINITY;
    for (Eigen::Index r = 0; r < n; ++r) {
        const std::size_t i = pr.rows[static_cast<std::size_t>(r)];
        X(r, 0) = 1.0;
        legendre(X, r, cx, scaled(pr.xs[i], xlo, xhi), kPoly);
        legendre(X, r, cv, scaled(pr.vs[i], vlo, vhi), kPoly);
        if (phase)
            for (int k = 1; k <= kHarm; ++k) {
                X(r, cp + 2 * (k - 1)) = std::cos(k * pr.phi[i]);
                X(r, cp + 2 * (k - 1) + 1) = std::sin(k * pr.phi[i]);
            }
        legendre(X, r, ct, scaled(d.t[i], t0, t1), kTime);
        if (impacts) {
            while (next_impact < pr.impacts.size() && pr.impacts[next_impact].t_out <= d.t[i]) last_impact = pr.impacts[next_impact++].t_out;
            const double since = (d.t[i] - last_impact) / pr.period;   // forcing periods since the last impact
            // Before the first impact `since` is infinite: it is tested before it becomes an index.
            if (since >= 0 && since < 0.25 * kImpactBins) X(r, ci + static_cast<Eigen::Index>(std::floor(since / 0.25))) = 1.0;
        }
    }
    const Folds f = make_folds(X, R, 5);
    double cv0 = 0, in0 = 0;
    cv_sse(f, {0}, cv0, in0);
    const double total = R.squaredNorm();
    if (!(total > 0)) return out;
    auto share = [&](Eigen::Index c0, Eigen::Index k) {
        std::vector<int> cols{0};
        for (Eigen::Index c = c0; c < c0 + k; ++c) cols.push_back(static_cast<int>(c));
        double cvk = 0, ink = 0;
        cv_sse(f, cols, cvk, ink);
        return std::max(0.0, (cv0 - cvk) / total);
    };
    out.emplace_back("a constant", std::max(0.0, (total - cv0) / total));
    out.emplace_back("x", share(cx, kPoly));
    out.emplace_back("v", share(cv, kPoly));
    if (phase) out.emplace_back("the forcing phase", share(cp, 2 * kHarm));
    out.emplace_back("time", share(ct, kTime));
    if (impacts) out.emplace_back("the time since an impact", share(ci, kImpactBins));
    std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
    return out;
}

}  // namespace impactlab::identify::detail
