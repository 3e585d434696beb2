// Each run's own well, measured from the data (never from the model): a local polynomial force law per unit
// mass, a'' + c v + k x + k2 x^2 + k3 x^3 - F0 = g u, fitted in the weak form on the run's free-flight rows.
// Its linear frequency, its local even term (softer toward the barrier: the side of the well) and, by the
// local law's barrier, an estimate of its depth. Runs in two wells whose frequencies differ beyond their
// uncertainty show an asymmetry that a symmetric model cannot produce, and which well is deeper and stiffer.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "identify/internal.hpp"

namespace impactlab::identify::detail {

std::vector<RunWell> data_wells(const Prep& pr, int hac_lag) {
    std::vector<RunWell> out;
    if (pr.phi_forced || pr.u.empty()) return out;   // the unbalance's forcing is the model's; only a measured input is data
    const MeasuredData& d = *pr.data;
    const int H = pr.K.H;
    constexpr int kCols = 7;   // v, x, x^2, x^3, 1, u  (and the averaged acceleration as the target)
    for (std::size_t run = 0; run < pr.run_start.size(); ++run) {
        std::vector<std::size_t> rows;
        for (std::size_t i : pr.rows)
            if (pr.run_of(i) == run) rows.push_back(i);
        if (rows.size() < 200) continue;
        // Centre x on the run's mean so the polynomial is local and well conditioned.
        double xm = 0;
        for (std::size_t i : rows) xm += d.x[i];
        xm /= static_cast<double>(rows.size());
        const auto n = static_cast<Eigen::Index>(rows.size());
        Eigen::MatrixXd X(n, kCols - 1);
        Eigen::VectorXd y(n);
        for (Eigen::Index r = 0; r < n; ++r) {
            const std::size_t c = rows[static_cast<std::size_t>(r)];
            double a = 0, v = 0, x1 = 0, x2 = 0, x3 = 0, u = 0;
            for (int k = 0; k <= 2 * H; ++k) {
                const std::size_t j = c + static_cast<std::size_t>(k) - static_cast<std::size_t>(H);
                const double xj = d.x[j] - xm;
                a += pr.K.w2[static_cast<std::size_t>(k)] * xj;
                v += pr.K.w1[static_cast<std::size_t>(k)] * xj;
                x1 += pr.K.w[static_cast<std::size_t>(k)] * xj;
                x2 += pr.K.w[static_cast<std::size_t>(k)] * xj * xj;
                x3 += pr.K.w[static_cast<std::size_t>(k)] * xj * xj * xj;
                u += pr.K.w[static_cast<std::size_t>(k)] * pr.u[j];
            }
            y[r] = a;
            X.row(r) << -v, -x1, -x2, -x3, 1.0, u;
        }
        const Eigen::VectorXd beta = X.colPivHouseholderQr().solve(y);
        const Eigen::VectorXd e = y - X * beta;
        const Eigen::MatrixXd V = hac_cov(X, e, hac_lag);
        if (!beta.allFinite() || !V.allFinite()) continue;
        const double k = beta[1], k2 = beta[2], k3 = beta[3], F0 = beta[4];
        // The equilibrium near the run's mean: k x + k2 x^2 + k3 x^3 = F0, by Newton from F0/k.
        double x0 = k != 0 ? F0 / k : 0.0;
        for (int it = 0; it < 30; ++it) {
            const double f = k * x0 + k2 * x0 * x0 + k3 * x0 * x0 * x0 - F0, df = k + 2 * k2 * x0 + 3 * k3 * x0 * x0;
            if (df == 0) break;
            x0 -= f / df;
        }
        RunWell w;
        w.run = run;
        w.x0 = x0 + xm;
        const double keff = k + 2 * k2 * x0 + 3 * k3 * x0 * x0, k2eff = k2 + 3 * k3 * x0;
        // Uncertainties by the delta method over (k, k2, k3, F0) through x0.
        Eigen::Vector4d gk, g2;
        gk << 1.0, 2 * x0, 3 * x0 * x0, 0.0;
        g2 << 0.0, 1.0, 3 * x0, 0.0;
        const Eigen::Matrix4d Vs = V.block(1, 1, 4, 4);
        const double sk = std::sqrt(std::max(0.0, gk.dot(Vs * gk))), s2 = std::sqrt(std::max(0.0, g2.dot(Vs * g2)));
        if (!(keff > 0)) continue;   // not a well
        w.omega = std::sqrt(keff);
        w.somega = 0.5 * sk / w.omega;
        w.k2 = k2eff;
        w.sk2 = s2;
        // The side: the local law is softer toward the barrier (k2 < 0: barrier at +x, the left well).
        w.side = std::abs(k2eff) > 3.0 * s2 ? (k2eff < 0 ? "left" : "right") : "";
        // The barrier by the local law: the nearest zero of the restoring force toward the softer side, and the
        // depth per unit mass as the work to reach it. None where the local law does not turn over there.
        const double dir = k2eff < 0 ? 1.0 : -1.0;
        const double span = 10.0 * std::max(pr.x_span, 1e-300);
        double yb = kNaN, prev = 0;
        for (int i = 1; i <= 4000; ++i) {
            const double yy = dir * span * i / 4000.0, f = keff * yy + k2eff * yy * yy + k3 * yy * yy * yy;
            if (i > 1 && (f > 0) != (prev > 0)) {
                yb = yy;
                break;
            }
            prev = f;
        }
        if (std::isfinite(yb)) {
            // The potential per unit mass at the barrier: the well's depth.
            w.depth = keff * yb * yb / 2.0 + k2eff * yb * yb * yb / 3.0 + k3 * yb * yb * yb * yb / 4.0;
            w.barrier = std::abs(yb);
            if (!(w.depth > 0)) w.depth = kNaN;
        }
        out.push_back(w);
    }
    return out;
}

std::string wells_asymmetry(const std::vector<RunWell>& wells, const std::string& x_unit) {
    const RunWell* left = nullptr;
    const RunWell* right = nullptr;
    for (const auto& w : wells) {
        if (w.side == "left" && (!left || w.somega < left->somega)) left = &w;
        if (w.side == "right" && (!right || w.somega < right->somega)) right = &w;
    }
    if (wells.size() < 2) return "";
    char buf[600];
    if (!left || !right) {
        // Runs all in one well (or with no clear side): compare their frequencies only.
        double lo = INFINITY, hi = -INFINITY, s = 0;
        for (const auto& w : wells) {
            lo = std::min(lo, w.omega);
            hi = std::max(hi, w.omega);
            s = std::max(s, w.somega);
        }
        std::snprintf(buf, sizeof buf,
                      "the runs' wells cannot be told apart by side from the data (no run shows a clear local even term); "
                      "their linear frequencies span %.4g to %.4g Hz (+/- %.2g)",
                      lo / (2 * kPi), hi / (2 * kPi), s / (2 * kPi));
        return buf;
    }
    const double dw = left->omega - right->omega, sw = std::hypot(left->somega, right->somega);
    const double fl = left->omega / (2 * kPi), fr = right->omega / (2 * kPi);
    const bool differ = std::abs(dw) > 3.0 * sw && std::abs(dw) > 0.03 * std::max(left->omega, right->omega);
    if (!differ) {
        std::snprintf(buf, sizeof buf,
                      "no asymmetry: the left and right wells have the same linear frequency within the scatter "
                      "(%.4g +/- %.2g Hz and %.4g +/- %.2g Hz, measured from each run's data)",
                      fl, left->somega / (2 * kPi), fr, right->somega / (2 * kPi));
        return buf;
    }
    const bool left_stiffer = dw > 0;
    std::string depth;
    if (std::isfinite(left->depth) && std::isfinite(right->depth)) {
        char b[200];
        std::snprintf(b, sizeof b, "; by the local force laws' barriers the %s well is deeper (%.3g vs %.3g %s^2/s^2 per unit mass)",
                      left->depth > right->depth ? "left" : "right", std::max(left->depth, right->depth),
                      std::min(left->depth, right->depth), x_unit.c_str());
        depth = b;
    }
    std::snprintf(buf, sizeof buf,
                  "an asymmetry between the wells, which a symmetric model cannot produce: the %s well is stiffer "
                  "(%.4g +/- %.2g Hz against %.4g +/- %.2g Hz, measured from each run's data)%s; with the origin at the "
                  "hilltop that is an even stiffness k2 %s 0 (or a constant force F0 %s 0) in m y'' + ... + k2 y^2 = F0",
                  left_stiffer ? "left" : "right", left_stiffer ? fl : fr, (left_stiffer ? left : right)->somega / (2 * kPi),
                  left_stiffer ? fr : fl, (left_stiffer ? right : left)->somega / (2 * kPi), depth.c_str(), left_stiffer ? ">" : "<",
                  left_stiffer ? "<" : ">");
    return buf;
}

}  // namespace impactlab::identify::detail
