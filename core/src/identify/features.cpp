// Where the residual has a narrow feature: a rail defect a few mm wide, a friction bump near v = 0. A smooth
// generic force with its knots spread over the whole travel cannot follow one; the local generic terms put
// theirs where this finds it. The residual is binned against the variable; a feature is a run of bins whose
// means stand out of a running median of their neighbours (so a smooth trend, which the other terms take,
// is not one), by far more than their scatter. It also finds a slow cycle of the spring rate in the residual,
// where the cycling generic term starts its period.
#include <algorithm>
#include <cmath>

#include "identify/internal.hpp"

namespace impactlab::identify::detail {

namespace {

constexpr int kBins = 64;          // over the 0.5 % .. 99.5 % range of the variable
constexpr int kTrendHalf = 16;     // the running median's half width [bins]: wider than a feature
constexpr double kZPeak = 4.5;     // a feature's peak bin against its own scatter
constexpr double kZMin = 7.0;      // the whole feature's bins against their scatter (chi-square as z)
constexpr int kMinPasses = 8;      // passes of the trajectory through a bin before its mean is trusted
constexpr double kExtent = 0.2;    // the feature's edges: where the deviation falls below this share of its peak

Prep::Feature narrow_feature(const std::vector<double>& s, const Eigen::VectorXd& R, const std::vector<std::size_t>& rows, std::size_t corr) {
    Prep::Feature f;
    const std::size_t n = s.size();
    if (n < 20 * kBins) return f;
    const double lo = quantile(s, 0.005), hi = quantile(s, 0.995);
    if (!(hi > lo)) return f;
    const double w = (hi - lo) / kBins;
    std::vector<double> sum(kBins, 0.0), sum2(kBins, 0.0);
    std::vector<int> count(kBins, 0), passes(kBins, 0);
    std::vector<std::size_t> last(kBins, 0);
    for (std::size_t r = 0; r < n; ++r) {
        const double u = (s[r] - lo) / w;
        const int b = u >= 0 && u < kBins ? static_cast<int>(u) : -1;
        if (b >= 0) {
            const double e = R[static_cast<Eigen::Index>(r)];
            sum[static_cast<std::size_t>(b)] += e;
            sum2[static_cast<std::size_t>(b)] += e * e;
            ++count[static_cast<std::size_t>(b)];
            // Rows of a bin closer in time than the residual's correlation are one pass (a trajectory that
            // lingers at a bin's edge hops in and out of it with the noise).
            const auto k = static_cast<std::size_t>(b);
            if (passes[k] == 0 || rows[r] > last[k] + corr) ++passes[k];
            last[k] = rows[r];
        }
    }
    std::vector<double> mean(kBins, 0.0), se(kBins, INFINITY);
    for (int b = 0; b < kBins; ++b) {
        const auto k = static_cast<std::size_t>(b);
        if (passes[k] < kMinPasses) continue;
        mean[k] = sum[k] / count[k];
        const double var = std::max(0.0, sum2[k] / count[k] - mean[k] * mean[k]);
        se[k] = std::sqrt(var / passes[k]);
    }
    std::vector<double> dev(kBins, 0.0), z(kBins, 0.0);
    for (int b = 0; b < kBins; ++b) {
        const auto k = static_cast<std::size_t>(b);
        if (!std::isfinite(se[k])) continue;
        std::vector<double> around;
        for (int j = std::max(0, b - kTrendHalf); j <= std::min(kBins - 1, b + kTrendHalf); ++j)
            if (std::isfinite(se[static_cast<std::size_t>(j)])) around.push_back(mean[static_cast<std::size_t>(j)]);
        dev[k] = mean[k] - median(around);
        z[k] = se[k] > 0 ? dev[k] / se[k] : 0.0;
    }
    // Each bin that stands out is a peak; out from it while the deviation stays a share of the peak's (either
    // sign: a friction bump is odd in v), bridging one quiet bin. The strongest whole feature wins.
    for (int peak = 0; peak < kBins; ++peak) {
        const auto kp = static_cast<std::size_t>(peak);
        if (!(std::abs(z[kp]) >= kZPeak)) continue;
        const double cut = kExtent * std::abs(dev[kp]);
        auto strong = [&](int b) { return b >= 0 && b < kBins && std::abs(dev[static_cast<std::size_t>(b)]) >= cut; };
        int a = peak, e = peak;
        while (strong(a - 1) || strong(a - 2)) a -= strong(a - 1) ? 1 : 2;
        while (strong(e + 1) || strong(e + 2)) e += strong(e + 1) ? 1 : 2;
        // A feature as wide as the trend's window is a trend, which the global terms take.
        if (e - a + 1 > kTrendHalf) continue;
        double chi2 = 0;
        for (int b = a; b <= e; ++b) chi2 += z[static_cast<std::size_t>(b)] * z[static_cast<std::size_t>(b)];
        const double zf = chi2_to_z(chi2, e - a + 1);
        if (!(zf >= kZMin) || !(zf > f.z)) continue;
        // One bin of margin each side, and at least four bins, so the spline's ends come back to the trend.
        const double mid = 0.5 * (a + e + 1);
        const double half = std::max(2.0, 0.5 * (e - a + 1) + 1.0);
        f.lo = lo + (mid - half) * w;
        f.hi = lo + (mid + half) * w;
        f.z = zf;
    }
    return f;
}

// A slow cycle of the spring rate: the residual's part x S(t), S periodic. For each trial frequency (a
// 4-times oversampled grid from 1.5 cycles of the record to one cycle in 6 forcing periods) the sum of squares
// that x sin and x cos remove beside x and x t (the spring rate and its drift, which other terms take). The
// peak counts against the grid's median, the periodogram's own noise level (a chi-square of 2 degrees each).
constexpr double kMinCycles = 1.5;      // slower is a drift, which the drift laws take
constexpr double kMinPeriods = 6.0;     // faster is no slow change of the spring but the motion's own harmonics
constexpr double kCycleChi2 = 25.0;     // the peak against the noise level (a chance of e^-12.5 per frequency)
constexpr int kMinFrequencies = 12;     // below this the median is no noise level
constexpr std::size_t kCycleRows = 20000;   // rows used at most (the residual is correlated over a window anyway)

Prep::Cycle slow_cycle(const std::vector<double>& t, const std::vector<double>& x, const Eigen::VectorXd& R, double period) {
    Prep::Cycle c;
    const std::size_t n = t.size();
    if (n < 200 || !(period > 0)) return c;
    const double T = t.back() - t.front(), tm = 0.5 * (t.front() + t.back());
    const double f_lo = kMinCycles / T, f_hi = 1.0 / (kMinPeriods * period), df = 1.0 / (4.0 * T);
    if (!(T > 0) || !(f_hi > f_lo) || (f_hi - f_lo) / df < kMinFrequencies) return c;
    const std::size_t stride = std::max<std::size_t>(1, n / kCycleRows);
    std::vector<double> freqs, dss;
    for (double f = f_lo; f <= f_hi; f += df) {
        Eigen::Matrix4d G = Eigen::Matrix4d::Zero();
        Eigen::Vector4d b = Eigen::Vector4d::Zero();
        for (std::size_t i = 0; i < n; i += stride) {
            const double w = kTwoPi * f * (t[i] - t.front());
            const Eigen::Vector4d col(x[i], x[i] * (t[i] - tm) / T, x[i] * std::sin(w), x[i] * std::cos(w));
            G.noalias() += col * col.transpose();
            b.noalias() += col * R[static_cast<Eigen::Index>(i)];
        }
        const Eigen::Vector2d b2 = b.head<2>();
        const double full = b.dot(G.ldlt().solve(b)), nuisance = b2.dot(G.topLeftCorner<2, 2>().ldlt().solve(b2));
        freqs.push_back(f);
        dss.push_back(std::isfinite(full - nuisance) ? std::max(0.0, full - nuisance) : 0.0);
    }
    const auto peak = static_cast<std::size_t>(std::max_element(dss.begin(), dss.end()) - dss.begin());
    const double level = median(dss) / (2.0 * std::log(2.0));   // the median of a chi-square of 2 is 2 ln 2
    if (!(level > 0)) return c;
    const double chi2 = dss[peak] / level;
    // The grid point: within an eighth of a cycle over the record, which the fit's refinement of P takes.
    if (chi2 >= kCycleChi2) c = {1.0 / freqs[peak], chi2};
    return c;
}

}  // namespace

void locate_features(Prep& pr, const Model& m, const Eigen::VectorXd& R) {
    pr.x_feature = {};
    pr.v_feature = {};
    if (R.size() != static_cast<Eigen::Index>(pr.rows.size())) return;
    const MeasuredData& d = *pr.data;
    std::vector<double> xs, vs;
    xs.reserve(pr.rows.size());
    vs.reserve(pr.rows.size());
    for (std::size_t r : pr.rows) {
        xs.push_back(m.true_x(d.x[r]));
        vs.push_back(pr.vs[r] / m.measure_slope(xs.back()));
    }
    // The residual is a weighted mean over a window of 2H + 1 samples: correlated over that many.
    const auto corr = static_cast<std::size_t>(2 * pr.K.H + 1);
    pr.x_feature = narrow_feature(xs, R, pr.rows, corr);
    pr.v_feature = narrow_feature(vs, R, pr.rows, corr);
    pr.cycle = {};
    if (pr.run_start.size() == 1) {   // a cycle runs through one clock: across separate runs it means nothing
        std::vector<double> ts;
        ts.reserve(pr.rows.size());
        for (std::size_t r : pr.rows) ts.push_back(d.t[r]);
        pr.cycle = slow_cycle(ts, xs, R, pr.period);
    }
}

}  // namespace impactlab::identify::detail
