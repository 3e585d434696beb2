// Stage 0 of a joint fit: runs in different wells whose measurement chain removed each run's mean (x
// integrated from v with a high-pass), so that every run's x is centred on zero. A single force law cannot
// hold two wells at the same place; each run's own local law (data_wells.cpp: its stiffness and its even term,
// softer toward the barrier) is tied to one cubic with its hilltop at the origin,
//     F(y) = a3 y (y - yL) (y - yR),   F'(y_s) = omega_s^2,   F''(y_s) / 2 = k2_s,
// whose wells yL < 0 < yR put each run where its well lies. The offsets go into the record the fit sees; the
// cubic (its even term as the model's even stiffness, which the baseline then fits as `k2`), the runs' shared
// damping and gain into the starting values. (With the origin midway and a symmetric baseline, the
// asymmetric pair's model had equal wells, a gain of 0.27 and a 3.4 times larger 1-period shooting error.)
#include <algorithm>
#include <cmath>

#include "identify/fit/session.hpp"

namespace impactlab::identify::detail {

namespace {

struct Tied {
    double yL = 0, yR = 0, a3 = 0;
    double syL = 0, syR = 0;
    bool ok = false;
};

// The cubic through the runs' local laws: relative residuals of omega^2 and k2 per run, Gauss-Newton with a
// Levenberg damping, from the symmetric cubic of their means.
Tied tie_wells(const std::vector<RunWell>& wells) {
    Tied t;
    double w2 = 0, k2 = 0;
    for (const RunWell& w : wells) {
        w2 += w.omega * w.omega;
        k2 += std::abs(w.k2);
    }
    w2 /= static_cast<double>(wells.size());
    k2 /= static_cast<double>(wells.size());
    if (!(w2 > 0) || !(k2 > 0)) return t;
    // Symmetric start: F'(w) = 2 a3 w^2 and k2 = 3 a3 w.
    const double w0 = 1.5 * w2 / k2;
    Eigen::Vector3d p(-w0, w0, k2 / (3.0 * w0));
    const auto n = static_cast<Eigen::Index>(2 * wells.size());
    auto res = [&](const Eigen::Vector3d& q) {
        Eigen::VectorXd r(n);
        for (std::size_t i = 0; i < wells.size(); ++i) {
            const RunWell& w = wells[i];
            const double y = w.side == "left" ? q[0] : q[1];
            const double d1 = q[2] * (3 * y * y - 2 * (q[0] + q[1]) * y + q[0] * q[1]);
            const double d2 = q[2] * (3 * y - q[0] - q[1]);
            r[static_cast<Eigen::Index>(2 * i)] = (d1 - w.omega * w.omega) / (w.omega * w.omega);
            r[static_cast<Eigen::Index>(2 * i + 1)] = (d2 - w.k2) / std::abs(w.k2);
        }
        return r;
    };
    Eigen::MatrixXd J(n, 3);
    double lambda = 1e-3;
    Eigen::VectorXd r = res(p);
    for (int it = 0; it < 100; ++it) {
        for (int k = 0; k < 3; ++k) {
            Eigen::Vector3d q = p;
            const double h = 1e-7 * std::max(std::abs(p[k]), 1e-300);
            q[k] += h;
            J.col(k) = (res(q) - r) / h;
        }
        const Eigen::MatrixXd A = J.transpose() * J;
        const Eigen::Vector3d g = J.transpose() * r;
        bool stepped = false;
        for (int tries = 0; tries < 20 && !stepped; ++tries) {
            Eigen::Matrix3d Ad = A;
            Ad.diagonal() *= 1.0 + lambda;
            const Eigen::Vector3d q = p - Ad.ldlt().solve(g);
            const Eigen::VectorXd rq = res(q);
            if (q.allFinite() && rq.allFinite() && rq.squaredNorm() < r.squaredNorm()) {
                const double fall = r.squaredNorm() - rq.squaredNorm();
                p = q;
                r = rq;
                lambda = std::max(lambda / 10.0, 1e-12);
                stepped = true;
                if (fall < 1e-14 * std::max(r.squaredNorm(), 1e-300)) it = 100;
            } else {
                lambda *= 10.0;
            }
        }
        if (!stepped) break;
    }
    if (!(p[0] < 0 && p[1] > 0 && p[2] > 0) || !p.allFinite()) return t;
    // Standard errors from the scatter of the residuals over their degrees of freedom (at least one).
    const double dof = std::max<double>(1.0, static_cast<double>(n) - 3.0);
    const Eigen::Matrix3d cov = (J.transpose() * J).inverse() * (r.squaredNorm() / dof);
    if (!cov.allFinite()) return t;
    t = {p[0], p[1], p[2], std::sqrt(std::max(0.0, cov(0, 0))), std::sqrt(std::max(0.0, cov(1, 1))), true};
    return t;
}

}  // namespace

bool run_offsets_stage(const MeasuredData& data, Model& model0, const FitOptions& o, MeasuredData& shifted, FitReport& rep) {
    if (data.has_phi() || !o.fit_baseline || !model0.placeholder || data.run_starts.size() < 2) return false;
    std::vector<std::string> notes;
    Prep pr = prepare(data, model0, o, notes);
    pr.predictability = data_horizon(pr);
    const std::vector<RunWell> wells = data_wells(pr, hac_lag_of(pr));
    bool left = false, right = false;
    for (const RunWell& w : wells) {
        left = left || w.side == "left";
        right = right || w.side == "right";
    }
    if (!left || !right) return false;
    // Only where the chain removed the offsets: the runs' means lie within half of each one's reach of each other.
    const std::size_t R = data.run_starts.size();
    std::vector<double> lo(R, INFINITY), hi(R, -INFINITY), sum(R, 0.0), cnt(R, 0.0);
    for (std::size_t i = 0; i < data.size(); ++i) {
        const std::size_t r = pr.run_of(i);
        if (!std::isfinite(data.x[i])) continue;
        lo[r] = std::min(lo[r], data.x[i]);
        hi[r] = std::max(hi[r], data.x[i]);
        sum[r] += data.x[i];
        cnt[r] += 1;
    }
    for (const RunWell& a : wells)
        for (const RunWell& b : wells) {
            const double reach = 0.25 * std::min(hi[a.run] - lo[a.run], hi[b.run] - lo[b.run]);
            if (!(std::abs(sum[a.run] / cnt[a.run] - sum[b.run] / cnt[b.run]) < reach)) return false;
        }
    std::vector<RunWell> sided;
    for (const RunWell& w : wells)
        if (!w.side.empty()) sided.push_back(w);
    const Tied t = tie_wells(sided);
    if (!t.ok) {
        rep.notes.push_back("the runs lie in different wells but their x were centred by the measurement chain; their local laws "
                            "fit no cubic with a well on each side, so no offsets are restored and one force law sees both runs at the same place");
        return false;
    }
    shifted = data;
    std::string said;
    double c = 0, g = 0;
    for (const RunWell& w : sided) {
        const bool l = w.side == "left";
        const double off = (l ? t.yL : t.yR) - w.x0;
        rep.run_offsets.push_back({w.run, off, l ? t.syL : t.syR});
        const std::size_t a = data.run_starts[w.run], b = w.run + 1 < data.run_starts.size() ? data.run_starts[w.run + 1] : data.size();
        for (std::size_t i = a; i < b; ++i) shifted.x[i] += off;
        c = w.c;
        g = w.gain;
        char buf[160];
        std::snprintf(buf, sizeof buf, "%srun %zu (%s well) by %+.4g +/- %.2g", said.empty() ? "" : ", ", w.run + 1, w.side.c_str(), off,
                      l ? t.syL : t.syR);
        said += buf;
    }
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "the runs lie in different wells, but the measurement chain centred each run's x on zero: each run's local law "
                  "(frequency and even term) tied to one cubic puts the wells at %.4g +/- %.2g and %.4g +/- %.2g from its hilltop, "
                  "the origin; x shifted: ",
                  t.yL, t.syL, t.yR, t.syR);
    rep.notes.push_back(buf + said);
    // The tied cubic starts the baseline, its even term as the model's even stiffness, fitted there with k, a3,
    // the damping and the gain (the runs' shared values start the last two: the gain's sign is the data's).
    model0.p.a[1] = t.a3;
    model0.p.k = t.a3 * t.yL * t.yR;
    apply_effect(model0, "even_stiffness", {{"k2", -t.a3 * (t.yL + t.yR)}});
    if (c > 0) model0.p.c = c * model0.p.m;
    if (g != 0) model0.p.input_gain = g * model0.p.m;
    return true;
}

}  // namespace impactlab::identify::detail
