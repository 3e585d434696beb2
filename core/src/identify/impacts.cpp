// Impacts seen in the data, and the impact law a model predicts, for the impact-law residual.
#include <algorithm>
#include <cmath>
#include <random>

#include "identify/internal.hpp"

namespace impactlab::identify::detail {

namespace {

constexpr int kSide = 12;        // samples of each one-sided fit used to find impacts
constexpr int kFitSide = 10;     // samples of flight each side in the piecewise fit

struct PieceFit {
    double rss = INFINITY, level = 0, vm = 0, vp = 0;
};

// Least squares of x(t) = level + vm (t - ti) + am (t - ti)^2 / 2 (t < ti), level (ti <= t <= to),
// level + vp (t - to) + ap (t - to)^2 / 2 (t > to) over samples [a, b].
PieceFit piece_fit(const std::vector<double>& t, const std::vector<double>& x, std::size_t a, std::size_t b, double ti,
                   double to, bool quad_left, bool quad_right) {
    Eigen::Matrix<double, 5, 5> G = Eigen::Matrix<double, 5, 5>::Zero();
    Eigen::Matrix<double, 5, 1> r = Eigen::Matrix<double, 5, 1>::Zero();
    double xx = 0;
    for (std::size_t j = a; j <= b; ++j) {
        Eigen::Matrix<double, 5, 1> row = Eigen::Matrix<double, 5, 1>::Zero();
        row[0] = 1.0;
        if (t[j] < ti) {
            const double s = t[j] - ti;
            row[1] = s;
            row[2] = quad_left ? 0.5 * s * s : 0.0;
        } else if (t[j] > to) {
            const double s = t[j] - to;
            row[3] = s;
            row[4] = quad_right ? 0.5 * s * s : 0.0;
        }
        G.noalias() += row * row.transpose();
        r.noalias() += row * x[j];
        xx += x[j] * x[j];
    }
    for (int k = 0; k < 5; ++k) G(k, k) += 1e-18 + 1e-12 * G(k, k);
    const Eigen::Matrix<double, 5, 1> beta = G.ldlt().solve(r);
    PieceFit f;
    f.rss = xx - beta.dot(r);
    f.level = beta[0];
    f.vm = beta[1];
    f.vp = beta[3];
    return f;
}

}  // namespace

namespace {

struct EventFit {
    bool ok = false;
    ImpactObs ob{};
    double rss = INFINITY, rss_smooth = INFINITY;
};

// The piecewise fit of one event: entry near the split after sample i, held samples up to p, flight on
// [left_begin, right_end]. Also the RSS of one smooth quartic over the same samples, for the test.
EventFit fit_event(const std::vector<double>& t, const std::vector<double>& x, double dt, std::size_t i, std::size_t p,
                   std::size_t left_begin, std::size_t right_end, double ti_lo, double ti_hi, double to_lo, double to_hi) {
    EventFit ev;
    if (i < left_begin + 2 || right_end < p + 2) return ev;
    const bool ql = i - left_begin >= 4, qr = right_end - p >= 4;
    double best_ti = t[i], best_to = t[i];
    PieceFit best;
    auto consider = [&](double ti, double to) {
        const PieceFit f = piece_fit(t, x, left_begin, right_end, ti, to, ql, qr);
        if (f.rss < best.rss) {
            best = f;
            best_ti = ti;
            best_to = to;
        }
    };
    for (double ti = ti_lo; ti <= ti_hi + 1e-12 * dt; ti += 0.25 * dt)
        for (double to = std::max(ti, to_lo); to <= to_hi + 1e-12 * dt; to += 0.25 * dt) consider(ti, to);
    const double ti_c = best_ti, to_c = best_to;
    for (double ti = ti_c - 0.25 * dt; ti <= ti_c + 0.25 * dt + 1e-12 * dt; ti += 0.025 * dt)
        for (double to = std::max(ti, to_c - 0.25 * dt); to <= to_c + 0.25 * dt + 1e-12 * dt; to += 0.025 * dt) consider(ti, to);
    // One smooth quartic through the whole stretch: what the data would look like without an impact.
    const std::size_t n = right_end - left_begin + 1;
    Eigen::MatrixXd A(static_cast<Eigen::Index>(n), 5);
    Eigen::VectorXd y(static_cast<Eigen::Index>(n));
    const double tc = t[(left_begin + right_end) / 2], sc = 1.0 / (static_cast<double>(n) * dt);
    for (std::size_t j = 0; j < n; ++j) {
        const double s = (t[left_begin + j] - tc) * sc;
        for (int k = 0; k < 5; ++k) A(static_cast<Eigen::Index>(j), k) = std::pow(s, k);
        y[static_cast<Eigen::Index>(j)] = x[left_begin + j];
    }
    const Eigen::VectorXd beta = A.colPivHouseholderQr().solve(y);
    ev.rss_smooth = (A * beta - y).squaredNorm();
    ev.rss = best.rss;
    ev.ob.t_in = best_ti;
    ev.ob.t_out = best_to;
    ev.ob.level = best.level;
    ev.ob.v_minus = best.vm;
    ev.ob.v_plus = std::min(best.vp, 0.0);
    ev.ob.i_first = i + 1;
    ev.ob.i_last = p;
    ev.ok = std::isfinite(best.rss);
    return ev;
}

// Samples after split i that stay at one level (within 2 tol of each other).
std::size_t plateau_end(const std::vector<double>& x, std::size_t i, double tol) {
    std::size_t p = i + 1;
    double lo = x[i + 1], hi = x[i + 1];
    while (p + 1 < x.size()) {
        const double v = x[p + 1];
        const double nlo = std::min(lo, v), nhi = std::max(hi, v);
        if (nhi - nlo > 2 * tol) break;
        lo = nlo;
        hi = nhi;
        ++p;
    }
    return p;
}

}  // namespace

std::vector<ImpactObs> find_impacts(const std::vector<double>& t, const std::vector<double>& x, double sigma_x,
                                    double level_hint) {
    std::vector<ImpactObs> out;
    const std::size_t n = x.size();
    if (n < 4 * kSide) return out;
    const double dt = (t.back() - t.front()) / static_cast<double>(n - 1);
    const auto cl = onesided_slope(kSide, 2, dt, true), cr = onesided_slope(kSide, 2, dt, false);
    // J[i]: velocity after minus velocity before the split between samples i and i+1.
    std::vector<double> J(n, 0.0), vl(n, 0.0);
    for (std::size_t i = kSide - 1; i + kSide < n; ++i) {
        double a = 0, b = 0;
        for (int k = 0; k < kSide; ++k) {
            a += cl[static_cast<std::size_t>(k)] * x[i + 1 - kSide + static_cast<std::size_t>(k)];
            b += cr[static_cast<std::size_t>(k)] * x[i + 1 + static_cast<std::size_t>(k)];
        }
        vl[i] = a;
        J[i] = b - a;
    }
    std::vector<double> absJ;
    absJ.reserve(n);
    for (std::size_t i = kSide - 1; i + kSide < n; ++i) absJ.push_back(std::abs(J[i]));
    double noise_J = 1.4826 * median(absJ);
    double g2 = 0;
    for (double c : cl) g2 += c * c;
    noise_J = std::max(noise_J, std::sqrt(2 * g2) * sigma_x);
    const double thr = std::max(10.0 * noise_J, 1e-4);
    const double sig = std::max(sigma_x, 1e-8);   // noise-free data still need finite thresholds
    const double tol = 4.0 * sig + 1e-7;          // a held sample stays this close to the plateau level
    const double s2 = sig * sig;
    // An impact reverses the velocity: the jump must stand out of the one-sided slopes' noise, and the
    // piecewise flight-plateau-flight fit must beat one smooth quartic by far.
    const double min_jump = std::max(0.004, 10.0 * std::sqrt(g2) * sig);
    auto is_kink = [&](const EventFit& ev) {
        return ev.ok && ev.ob.v_minus > 0.002 && ev.ob.v_minus - ev.ob.v_plus > min_jump && (ev.rss_smooth - ev.rss) / s2 > 40.0 &&
               ev.rss_smooth > 4.0 * ev.rss;
    };

    // Pass 1: strong impacts, where the velocity drops abruptly.
    std::vector<char> used(n, 0);
    for (std::size_t i = kSide - 1; i + kSide < n; ++i) {
        if (used[i] || !(J[i] < -thr) || !(vl[i] > 0.5 * thr)) continue;
        if (J[i + 1] < J[i] || (i > 0 && J[i - 1] < J[i])) continue;
        const std::size_t p = plateau_end(x, i, tol);
        if (p + 4 >= n) break;
        std::size_t right_end = std::min(n - 1, p + kFitSide);
        for (std::size_t j = p + 2; j <= right_end && j + kSide < n; ++j)
            if (J[j] < -thr && vl[j] > 0.5 * thr) {
                right_end = j;
                break;
            }
        std::size_t left_begin = i + 1 >= static_cast<std::size_t>(kFitSide) ? i + 1 - kFitSide : 0;
        while (left_begin < i && used[left_begin]) ++left_begin;
        const EventFit ev = fit_event(t, x, dt, i, p, left_begin, right_end, t[i] - dt, t[i + 1],
                                      t[p >= i + 2 ? p - 1 : i], t[p + 1]);
        if (!is_kink(ev) || !(ev.ob.v_minus > 0.5 * thr)) continue;
        out.push_back(ev.ob);
        for (std::size_t j = i + 1; j <= p; ++j) used[j] = 1;
        i = p;
    }

    // Pass 2: slow impacts and long contacts, which pass 1 smears out: every stretch that reaches the bumper
    // level, tested against a smooth turning point.
    std::vector<double> lev;
    for (const auto& ob : out) lev.push_back(ob.level);
    const double level = lev.size() >= 3 ? median(lev) : level_hint;
    if (std::isfinite(level)) {
        const double near = 8.0 * sig + 2e-6;
        for (std::size_t i = kSide; i + kSide < n; ++i) {
            if (used[i + 1] || !(x[i + 1] >= level - near) || x[i] >= level - near) continue;
            // The run of samples near the level starting at i+1 is the candidate plateau.
            std::size_t p = i + 1;
            while (p + 1 < n && x[p + 1] >= level - near && !used[p + 1]) ++p;
            if (p + kFitSide >= n) break;
            std::size_t left_begin = i + 1 - static_cast<std::size_t>(kFitSide);
            while (left_begin < i && used[left_begin]) ++left_begin;
            std::size_t right_end = p + kFitSide;
            for (std::size_t j = p + 1; j <= right_end; ++j)
                if (used[j]) {
                    right_end = j - 1;
                    break;
                }
            // The run starts where the approach comes near the level, not at the entry: search it all
            // (bounded for long contacts).
            const std::size_t span = p - i;
            const EventFit ev = fit_event(t, x, dt, i, p, left_begin, right_end, t[i] - dt, t[std::min(p, i + std::min<std::size_t>(span, 10))],
                                          t[p - std::min<std::size_t>(span, 10)], t[p + 1]);
            if (is_kink(ev) && std::abs(ev.ob.level - level) < near) {
                out.push_back(ev.ob);
                for (std::size_t j = i + 1; j <= p; ++j) used[j] = 1;
            }
            i = p;
        }
        std::sort(out.begin(), out.end(), [](const ImpactObs& a, const ImpactObs& b) { return a.t_in < b.t_in; });
    }
    return out;
}

double apparent_kappa(const ImpactObs& im) { return im.v_minus > 0 ? -im.v_plus / im.v_minus : 0.0; }

ImpactLawData impact_law_data(const Prep& pr, const Model& m, bool dwell, const std::vector<char>& use) {
    ImpactLawData d;
    d.dwell = dwell;
    const double g = m.sensor_gain();
    for (std::size_t k = 0; k < pr.impacts.size(); ++k) {
        const ImpactObs& im = pr.impacts[k];
        if ((!use.empty() && !use[k]) || (!dwell && im.v_minus < 0.02)) continue;
        d.vm.push_back(im.v_minus / g);
        d.obs.push_back(dwell ? im.t_out - im.t_in : apparent_kappa(im));
    }
    return d;
}

std::array<const char*, 3> impact_law_names(bool dwell) {
    return dwell ? std::array<const char*, 3>{"Ti0", "Ti1", "a_T"} : std::array<const char*, 3>{"kappa0", "kappa1", "a_kappa"};
}

Eigen::VectorXd impact_law_residual(const ImpactLawData& d, const Eigen::VectorXd& th) {
    const auto n = static_cast<Eigen::Index>(d.obs.size());
    Eigen::VectorXd r(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        const auto k = static_cast<std::size_t>(i);
        r[i] = (th[0] - th[1]) * std::exp(-th[2] * d.vm[k]) + th[1] - d.obs[k];
    }
    return r;
}

PredictedImpacts predict_impacts(const Prep& pr, const Model& m, double rtol) {
    PredictedImpacts out;
    const std::size_t ni = pr.impacts.size();
    out.obs.assign(ni, ImpactObs{});
    out.ok.assign(ni, 0);
    if (!m.bumper() || ni == 0) return out;
    const MeasuredData& d = *pr.data;
    // The window starts where the smoothed state is clear of the impact (the S-G half-width and a margin)
    // and ends with enough flight after it for the detector's fits.
    const std::size_t lead = static_cast<std::size_t>(pr.Hv) + 3 * kFitSide, tail = 3 * kFitSide;
    constexpr int kRealisations = 2;   // noise draws averaged per impact
    for (std::size_t k = 0; k < ni; ++k) {
        const ImpactObs& im = pr.impacts[k];
        if (im.i_first < lead + 1) continue;
        std::size_t a = std::max(im.i_first - lead, pr.run_start[pr.run_of(im.i_first)]);
        if (k > 0) a = std::max(a, pr.impacts[k - 1].i_last + 2);
        const std::size_t b = std::min(pr.run_last(im.i_first), im.i_last + tail);
        const std::size_t pre_end = im.i_first >= 2 ? im.i_first - 2 : 0;
        if (pre_end < a + 8 || b < im.i_last + kFitSide || !std::isfinite(pr.xs[a]) || !std::isfinite(pr.vs[a])) continue;
        const std::vector<double> sim = simulate_window(pr, m, a, b, true, rtol, pre_end);
        if (sim.size() != b - a + 1) continue;
        const std::vector<double> tw(d.t.begin() + static_cast<long>(a), d.t.begin() + static_cast<long>(b) + 1);
        std::mt19937_64 rng(0x5eed + k);
        std::normal_distribution<double> noise(0.0, pr.sigma_x);
        ImpactObs acc{};
        int found = 0;
        for (int r = 0; r < kRealisations; ++r) {
            std::vector<double> xw(sim.size());
            for (std::size_t j = 0; j < sim.size(); ++j) xw[j] = sim[j] + noise(rng);
            const std::vector<ImpactObs> seen = find_impacts(tw, xw, pr.sigma_x, m.measure(m.p.xI));
            // The simulated impact nearest the measured one (within 10 samples).
            const ImpactObs* best = nullptr;
            for (const auto& s : seen)
                if (std::abs(s.t_in - im.t_in) <= 10 * pr.dt && (!best || std::abs(s.t_in - im.t_in) < std::abs(best->t_in - im.t_in)))
                    best = &s;
            if (!best) continue;
            acc.t_in += best->t_in;
            acc.t_out += best->t_out;
            acc.level += best->level;
            acc.v_minus += best->v_minus;
            acc.v_plus += best->v_plus;
            ++found;
        }
        if (found == 0) continue;
        const double f = 1.0 / found;
        out.obs[k] = {acc.t_in * f, acc.t_out * f, acc.level * f, acc.v_minus * f, acc.v_plus * f, im.i_first, im.i_last};
        out.ok[k] = 1;
    }
    return out;
}

}  // namespace impactlab::identify::detail
