// How far ahead the measured record itself can be predicted, read from the data alone (never from the model
// under test, whose own faults would look like instability): nearby returns of the measured trajectory in a
// delay embedding that includes the forcing, followed forward in time, in the manner of Rosenstein et al.
// (1993). The mean log separation grows with the largest Lyapunov exponent; the time it takes to double is
// the horizon within which a simulation from a fitted initial state can be judged.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "identify/internal.hpp"

namespace impactlab::identify::detail {


DataHorizon data_horizon(const Prep& pr) {
    DataHorizon h;
    const MeasuredData& d = *pr.data;
    const double T = pr.period;
    if (!(T > 0) || pr.n < 64) return h;
    // Nothing drives the record (a free decay): the rig's unforced motion is a flow in the plane (x, v), which
    // has no chaos (Poincare-Bendixson). A decay's returns meet other amplitudes, and with a hardening spring
    // other frequencies, so their parting would measure the decay, not a horizon.
    if (pr.unforced) {
        h.measured = h.regular = true;
        h.periods = INFINITY;
        return h;
    }
    // About 32 samples a forcing period, delays of a quarter period, followed for up to 10 periods.
    const std::size_t s = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(T / pr.dt / 32.0)));
    const std::size_t tau = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(0.25 * T / pr.dt)));
    const std::size_t steps = 320;   // 10 periods of 32 steps
    const std::size_t span = steps * s, back = 2 * tau, sep = static_cast<std::size_t>(std::lround(2.0 * T / pr.dt));
    const double sx = stdev(d.x, 0, pr.n);
    if (!(sx > 0)) return h;
    // The forcing's coordinates weigh heavily: neighbours must meet the same drive, or their separation
    // says nothing about the dynamics.
    const double A = 4.0 * sx;
    std::vector<double> f1(pr.n, 0.0), f2(pr.n, 0.0), f3(pr.n, 0.0);
    if (pr.phi_forced) {
        const auto [wmin, wmax] = std::minmax_element(pr.omega.begin(), pr.omega.end());
        const double wr = std::max(*wmax - *wmin, 1e-9);
        for (std::size_t i = 0; i < pr.n; ++i) {
            f1[i] = A * std::cos(pr.phi[i]);
            f2[i] = A * std::sin(pr.phi[i]);
            f3[i] = *wmax - *wmin > 0.05 * std::abs(*wmax) ? 4.0 * A * (pr.omega[i] - *wmin) / wr : 0.0;
        }
    } else if (!pr.u.empty()) {
        const double su = std::max(stdev(pr.u, 0, pr.u.size()), 1e-300);
        for (std::size_t i = 0; i < pr.n && i < pr.u.size(); ++i) {
            f1[i] = A * pr.u[i] / su;
            f2[i] = i >= tau ? A * pr.u[i - tau] / su : 0.0;
        }
    }
    // Usable sample indices on the coarse grid: a full delay vector behind and `span` samples ahead in the run.
    std::vector<std::size_t> idx;
    for (std::size_t i = 0; i < pr.n; i += s) {
        const std::size_t r0 = pr.run_start[pr.run_of(i)], r1 = pr.run_last(i);
        if (i < r0 + back || i + span > r1) continue;
        if (!std::isfinite(d.x[i]) || !std::isfinite(d.x[i - tau]) || !std::isfinite(d.x[i - back])) continue;
        idx.push_back(i);
    }
    if (idx.size() < 200) return h;
    auto dist2 = [&](std::size_t i, std::size_t j) {
        const double a = d.x[i] - d.x[j], b = d.x[i - tau] - d.x[j - tau], c = d.x[i - back] - d.x[j - back];
        const double e = f1[i] - f1[j], f = f2[i] - f2[j], g = f3[i] - f3[j];
        return a * a + b * b + c * c + e * e + f * f + g * g;
    };
    auto xsep = [&](std::size_t i, std::size_t j) {
        const double a = d.x[i] - d.x[j], b = d.x[i - tau] - d.x[j - tau], c = d.x[i - back] - d.x[j - back];
        return std::sqrt((a * a + b * b + c * c) / 3.0);
    };
    // Reference points spread evenly over the record; each one's nearest neighbour at least two periods away.
    const std::size_t nref = std::min<std::size_t>(300, idx.size() / 4);
    std::vector<double> ysum(steps + 1, 0.0), usum(steps + 1, 0.0);
    std::size_t pairs = 0;
    const bool input = !pr.phi_forced && !pr.u.empty();
    const double su = input ? std::max(stdev(pr.u, 0, pr.u.size()), 1e-300) : 1.0;
    const double floor_sep = std::max(pr.sigma_x, 1e-12 * sx);
    for (std::size_t r = 0; r < nref; ++r) {
        pr.check_cancel();
        const std::size_t i = idx[r * idx.size() / nref];
        double best = INFINITY;
        std::size_t jb = 0;
        for (std::size_t j : idx) {
            if ((i > j ? i - j : j - i) < sep) continue;
            const double q = dist2(i, j);
            if (q < best) {
                best = q;
                jb = j;
            }
        }
        if (!std::isfinite(best)) continue;
        // A neighbour that meets another phase of the drive is no neighbour.
        const double df = std::sqrt((f1[i] - f1[jb]) * (f1[i] - f1[jb]) + (f2[i] - f2[jb]) * (f2[i] - f2[jb]) + (f3[i] - f3[jb]) * (f3[i] - f3[jb]));
        if (df > 0.5 * sx) continue;
        for (std::size_t k = 0; k <= steps; ++k) {
            ysum[k] += std::log(std::max(xsep(i + k * s, jb + k * s), floor_sep));
            if (input) usum[k] += std::abs(pr.u[i + k * s] - pr.u[jb + k * s]) / su;
        }
        ++pairs;
    }
    if (pairs < 20) return h;
    // A measured input that does not repeat (a multisine, noise) drives two nearby returns apart by itself: their
    // separation then says nothing of the dynamics, and the horizon is not measurable from the data.
    if (input)
        for (std::size_t k = 0; k <= steps; ++k)
            if (usum[k] / static_cast<double>(pairs) > 0.25) return h;
    h.pairs = pairs;
    for (std::size_t k = 0; k <= steps; ++k) h.log_separation.emplace_back(static_cast<double>(k) / 32.0, ysum[k] / static_cast<double>(pairs));
    // The separation's start: its least over the first quarter period (stable directions shrink first).
    double y0 = INFINITY;
    for (std::size_t k = 0; k <= 8; ++k) y0 = std::min(y0, h.log_separation[k].second);
    h.measured = true;
    h.periods = INFINITY;
    for (std::size_t k = 0; k <= steps; ++k)
        if (h.log_separation[k].second >= y0 + std::log(2.0)) {
            h.periods = h.log_separation[k].first;
            break;
        }
    // Regular (periodic or quasi-periodic within the noise) when the separation never doubles in 10 periods.
    h.regular = !std::isfinite(h.periods);
    // The exponent: the steepest growth of the mean log separation over a quarter period before its doubling.
    // Nearest returns of a finite record start far above the noise, where growth is already slower than from
    // the noise a fitted initial state leaves, so the doubling of their own separation alone would overstate
    // how long a simulation from the noise stays close: the horizon is the shorter of that and ln 2 / lambda.
    const std::size_t kend = h.regular ? steps : std::max<std::size_t>(8, static_cast<std::size_t>(std::lround(h.periods * 32.0)));
    h.lambda = 0;
    for (std::size_t k = 0; k + 8 <= std::min(kend, steps); ++k)
        h.lambda = std::max(h.lambda, (h.log_separation[k + 8].second - h.log_separation[k].second) / (0.25 * T));
    if (!h.regular && h.lambda > 0) h.periods = std::min(h.periods, std::log(2.0) / h.lambda / T);
    return h;
}

}  // namespace impactlab::identify::detail
