// The continuation's corrector period by period (multiple shooting). On a branch whose period map P^k expands
// strongly (a cascade's period 8 pressing the bumper: mu = 2.5e4) the whole map is nonlinear on the scale of
// the predictor's error, and Newton on it crawls. Each one-period map expands only by about |mu|^(1/k), so
// Newton on the k maps together converges quadratically from the same predictor, and the k maps are
// independent evaluations, spread over the cores.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "analysis/continuer.hpp"
#include "impactlab/analysis.hpp"

namespace impactlab::analysis::detail {

namespace {

// The k one-period maps taken together as the whole orbit's: y, sections and monodromy of P^k, its
// impacts and extremes.
MapResult whole_orbit(const std::vector<MapResult>& rs, int k) {
    MapResult w;
    w.M = Mat2::Identity();
    for (int i = 0; i < k; ++i) {
        const MapResult& ri = rs[static_cast<std::size_t>(2 * i)];
        w.M = ri.M * w.M;
        w.sections.push_back(ri.y);
        w.impacts += ri.impacts;
        w.max_x = std::max(w.max_x, ri.max_x);
        w.min_impact_speed = std::min(w.min_impact_speed, ri.min_impact_speed);
        w.contact = w.contact || ri.contact;
        w.steps += ri.steps;
    }
    const MapResult& last = rs[static_cast<std::size_t>(2 * (k - 1))];
    w.y = last.y;
    w.held = last.held;
    return w;
}

}  // namespace

bool Continuer::correct_by_periods(const Vec3& u_pred, const Vec3& n, int k, const Vec3& u, const Vec3& du,
                                   const MapResult& r, const MapResult& rq, const std::vector<Mat2>& phis, Sol& out) {
    const auto K = static_cast<std::size_t>(k);
    if (phis.size() != K || r.sections.size() != K || rq.sections.size() != K) return false;
    const int N = 2 * k + 1;
    // The first step: z_0 moved by du, each later section point by the whole map's linearisation along the
    // orbit (its monodromy up to that section, and the sections' shift in q).
    Eigen::VectorXd Z(N);
    const Vec2 dy0 = du.head<2>();
    Z.segment<2>(0) = u.head<2>() + dy0;
    for (int i = 1; i < k; ++i) {
        const auto s = static_cast<std::size_t>(i - 1);
        const Vec2 si = scaled(r.sections[s]);
        const Vec2 Di = (scaled(rq.sections[s]) - si) / kDq;
        Z.segment<2>(2 * i) = si + scaled(phis[s]) * dy0 + Di * du[2];
    }
    Z[2 * k] = u[2] + du[2];
    for (int it = 1; it <= kMaxCorrector; ++it) {
        const Vec3 u0(Z[0], Z[1], Z[2 * k]);
        if (spec_.param == ContParam::Omega && !(q_of(u0) > 0)) return false;
        std::vector<MapAt> at;
        at.reserve(2 * K);
        for (int i = 0; i < k; ++i) {
            const Vec3 ui(Z[2 * i], Z[2 * i + 1], Z[2 * k]);
            at.push_back({ui, true});
            at.push_back({shifted_q(ui), false});
        }
        std::vector<MapResult> rs = maps(at, 1);
        // Defects P(z_i) - z_{i+1} and their derivatives (q's by a forward difference, as in jacobian()).
        Eigen::VectorXd F(N);
        Eigen::MatrixXd A = Eigen::MatrixXd::Zero(N, N);
        Vec2 dq_whole = Vec2::Zero();   // d P^k(z_0) / d q along the orbit
        Mat2 M_whole = Mat2::Identity();
        for (int i = 0; i < k; ++i) {
            const auto s = static_cast<std::size_t>(2 * i);
            const Vec2 Pz = scaled(rs[s].y);
            const int next = 2 * ((i + 1) % k);
            F.segment<2>(2 * i) = Pz - Z.segment<2>(next);
            const Mat2 Mi = scaled(rs[s].M);
            const Vec2 bi = (scaled(rs[s + 1].y) - Pz) / kDq;
            A.block<2, 2>(2 * i, 2 * i) = Mi;
            A.block<2, 2>(2 * i, next) -= Mat2::Identity();
            A.block<2, 1>(2 * i, 2 * k) = bi;
            dq_whole = Mi * dq_whole + bi;
            M_whole = Mi * M_whole;
        }
        const double h = n.dot(u0 - u_pred);
        F[2 * k] = h;
        A(2 * k, 0) = n[0];
        A(2 * k, 1) = n[1];
        A(2 * k, 2 * k) = n[2];
        if (!F.allFinite() || !A.allFinite()) return false;
        const double defect = F.head(2 * k).cwiseAbs().maxCoeff();
        auto converged = [&] {
            MapResult w = whole_orbit(rs, k);
            return take(out, u0, w, jacobian(M_whole, dq_whole), it);
        };
        if (defect < res_tol_ && std::abs(h) < 1e-9) return converged();
        if (it == kMaxCorrector) break;
        const Eigen::VectorXd dZ = A.fullPivLu().solve(-F);
        if (!dZ.allFinite() || dZ.norm() > 1.0) return false;   // left the neighbourhood of the branch
        // At the maps' noise floor, as in correct().
        if (it >= 2 && dZ.cwiseAbs().maxCoeff() < res_tol_ && defect < 100 * res_tol_ && std::abs(h) < 1e-9)
            return converged();
        Z += dZ;
    }
    return false;
}

}  // namespace impactlab::analysis::detail
