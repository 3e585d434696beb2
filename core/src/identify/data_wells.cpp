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
    // The runs' rows, each run centred on its own mean so its polynomial is local and well conditioned.
    std::vector<std::size_t> runs;
    std::vector<std::vector<std::size_t>> rows_of;
    std::vector<double> mean_of;
    for (std::size_t run = 0; run < pr.run_start.size(); ++run) {
        std::vector<std::size_t> rows;
        for (std::size_t i : pr.rows)
            if (pr.run_of(i) == run) rows.push_back(i);
        if (rows.size() < 200) continue;
        // A run that changes wells (a chaotic record) has no one well to measure.
        const std::vector<double> xr(d.x.begin() + static_cast<long>(rows.front()), d.x.begin() + static_cast<long>(rows.back()) + 1);
        if (const WellBand wb = well_band(xr, pr.predictability.measured && !pr.predictability.regular); well_changes(xr, wb) >= 4) continue;
        double xm = 0;
        for (std::size_t i : rows) xm += d.x[i];
        runs.push_back(run);
        mean_of.push_back(xm / static_cast<double>(rows.size()));
        rows_of.push_back(std::move(rows));
    }
    if (runs.empty()) return out;
    // One regression over every run: the damping c and the input's gain g are the rig's, shared (a single-sine
    // record alone cannot tell its stiffness from its gain); each run has its own local k, k2, k3 and F0.
    const std::size_t R = runs.size();
    Eigen::Index n = 0;
    for (const auto& r : rows_of) n += static_cast<Eigen::Index>(r.size());
    const Eigen::Index ncol = 2 + 4 * static_cast<Eigen::Index>(R);
    Eigen::MatrixXd X = Eigen::MatrixXd::Zero(n, ncol);
    Eigen::VectorXd y(n);
    // The weak form: the kernel's averages of each run's centred x, x^2, x^3 and of u (a row's window never
    // reaches across a run's start).
    std::vector<double> xc(pr.n), x2(pr.n), x3(pr.n);
    for (std::size_t i = 0; i < pr.n; ++i) {
        const std::size_t run = pr.run_of(i);
        const auto q = static_cast<std::size_t>(std::find(runs.begin(), runs.end(), run) - runs.begin());
        xc[i] = d.x[i] - (q < R ? mean_of[q] : 0.0);
        x2[i] = xc[i] * xc[i];
        x3[i] = x2[i] * xc[i];
    }
    const std::vector<double> fa = apply_fir(xc, pr.K.w2), fv = apply_fir(xc, pr.K.w1), f1 = apply_fir(xc, pr.K.w),
                              f2 = apply_fir(x2, pr.K.w), f3 = apply_fir(x3, pr.K.w), fu = apply_fir(pr.u, pr.K.w);
    Eigen::Index r = 0;
    for (std::size_t q = 0; q < R; ++q)
        for (std::size_t c : rows_of[q]) {
            y[r] = fa[c];
            const Eigen::Index b0 = 2 + 4 * static_cast<Eigen::Index>(q);
            X(r, 0) = -fv[c];
            X(r, 1) = fu[c];
            X(r, b0) = -f1[c];
            X(r, b0 + 1) = -f2[c];
            X(r, b0 + 2) = -f3[c];
            X(r, b0 + 3) = 1.0;
            ++r;
        }
    const Eigen::VectorXd beta = X.colPivHouseholderQr().solve(y);
    const Eigen::VectorXd e = y - X * beta;
    const Eigen::MatrixXd V = hac_cov(X, e, hac_lag);
    if (!beta.allFinite() || !V.allFinite()) return out;
    for (std::size_t q = 0; q < R; ++q) {
        const Eigen::Index b0 = 2 + 4 * static_cast<Eigen::Index>(q);
        const double k = beta[b0], k2 = beta[b0 + 1], k3 = beta[b0 + 2], F0 = beta[b0 + 3];
        // The equilibrium near the run's mean: k x + k2 x^2 + k3 x^3 = F0, by Newton from F0/k.
        double x0 = k != 0 ? F0 / k : 0.0;
        for (int it = 0; it < 30; ++it) {
            const double f = k * x0 + k2 * x0 * x0 + k3 * x0 * x0 * x0 - F0, df = k + 2 * k2 * x0 + 3 * k3 * x0 * x0;
            if (df == 0) break;
            x0 -= f / df;
        }
        RunWell w;
        w.run = runs[q];
        w.c = beta[0];
        w.gain = beta[1];
        w.x0 = x0 + mean_of[q];
        const double keff = k + 2 * k2 * x0 + 3 * k3 * x0 * x0, k2eff = k2 + 3 * k3 * x0;
        // Uncertainties by the delta method over (k, k2, k3, F0) through x0.
        Eigen::Vector4d gk, g2;
        gk << 1.0, 2 * x0, 3 * x0 * x0, 0.0;
        g2 << 0.0, 1.0, 3 * x0, 0.0;
        const Eigen::Matrix4d Vs = V.block(b0, b0, 4, 4);
        const double sk = std::sqrt(std::max(0.0, gk.dot(Vs * gk))), s2 = std::sqrt(std::max(0.0, g2.dot(Vs * g2)));
        if (!(keff > 0)) continue;   // not a well
        w.omega = std::sqrt(keff);
        w.somega = 0.5 * sk / w.omega;
        w.k2 = k2eff;
        w.sk2 = s2;
        // The side: the local law is softer toward the barrier (k2 < 0: barrier at +x, the left well).
        w.side = std::abs(k2eff) > 3.0 * s2 ? (k2eff < 0 ? "left" : "right") : "";
        // The barrier by the local law: the nearest zero of the restoring force toward the softer side, and the
        // depth per unit mass as the potential there. Only where the barrier lies within twice the run's reach
        // of its equilibrium: farther, the local law is extrapolated and says nothing of the depth.
        double reach = 0;
        for (std::size_t i : rows_of[q]) reach = std::max(reach, std::abs(d.x[i] - w.x0));
        const double dir = k2eff < 0 ? 1.0 : -1.0;
        double yb = kNaN, prev = 0;
        for (int i = 1; i <= 4000; ++i) {
            const double yy = dir * 2.0 * reach * i / 4000.0, f = keff * yy + k2eff * yy * yy + k3 * yy * yy * yy;
            if (i > 1 && (f > 0) != (prev > 0)) {
                yb = yy;
                break;
            }
            prev = f;
        }
        w.depth = kNaN;
        if (std::isfinite(yb)) {
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
    char buf[1200];
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
    // Beyond the scatter, and by more than the equation error's bias at one drive frequency can make of mirror-image
    // wells (a tenth).
    const bool differ = std::abs(dw) > 3.0 * sw && std::abs(dw) > 0.10 * std::max(left->omega, right->omega);
    if (!differ) {
        std::snprintf(buf, sizeof buf,
                      "no asymmetry: the left and right wells have the same linear frequency within the scatter "
                      "(%.4g +/- %.2g Hz and %.4g +/- %.2g Hz, measured from each run's data)",
                      fl, left->somega / (2 * kPi), fr, right->somega / (2 * kPi));
        return buf;
    }
    const bool left_stiffer = dw > 0;
    std::string depth = "; their depths are not measurable from motion that stays this far from the barrier";
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

std::string well_frequency_identifiability(const std::vector<RunWell>& wells, const WellReport& model_wells,
                                           const std::vector<UnseparatedPair>& unseparated) {
    const UnseparatedPair* traded = nullptr;
    for (const UnseparatedPair& u : unseparated)
        if (u.a == "k" || u.b == "k") traded = &u;
    // k traded against another spring term (a3 where the motion spans little of the travel) leaves the well's
    // frequency, their sum there, pinned: only a trade against the gain or the damping unpins the frequency.
    const std::string partner = traded ? (traded->a == "k" ? traded->b : traded->a) : "";
    const bool spring_partner = partner == "a1" || partner == "a3" || partner == "a5" || partner == "k2";
    if (spring_partner) traded = nullptr;
    constexpr double kApart = 0.15;
    std::string out;
    for (const RunWell& w : wells) {
        if (!(w.omega > 0) || !std::isfinite(w.somega)) continue;
        const Well* near = nullptr;   // the model's well nearest the run's own
        for (const Well& m : model_wells.wells)
            if (m.omega > 0 && (!near || std::abs(m.x - w.x0) < std::abs(near->x - w.x0))) near = &m;
        if (!near) continue;
        const double apart = std::abs(near->omega - w.omega) / w.omega;
        if (apart <= kApart && !traded) continue;
        const std::string trade = traded ? ", and k trades off against " + partner + " in the fit" : "";
        const char* why = spring_partner ? "its motion spans too little of the travel to tell the linear spring from the nonlinear one"
                                         : "steady forcing at one frequency lets k trade off against the gain and the damping; a "
                                           "transient would separate them";
        char buf[400];
        std::snprintf(buf, sizeof buf,
                      "run %zu: the well's frequency is not identifiable from this record: the model written puts it at %.3g Hz, the "
                      "run's own local law at %.3g +/- %.2g Hz (%.0f %% apart)%s. The record does not pin it (%s): neither "
                      "value is a finding",
                      w.run + 1, near->omega / kTwoPi, w.omega / kTwoPi, w.somega / kTwoPi, 100.0 * apart, trade.c_str(), why);
        out += (out.empty() ? "" : "; ") + std::string(buf);
    }
    return out;
}

}  // namespace impactlab::identify::detail
