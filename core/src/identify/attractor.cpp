// The attractor's statistics: what a chaotic record and a right model share although their trajectories part
// within the predictability horizon. A free run is compared with the record block by block, by the distance
// between the distributions of x and of v (Wasserstein-1, in units of the record's own spread), by the rate
// of well changes and by the power spectrum. Each block is a unit of the final gate's paired test.
#include <algorithm>
#include <cmath>
#include <complex>
#include <unsupported/Eigen/FFT>

#include "identify/internal.hpp"

namespace impactlab::identify::detail {

namespace {

constexpr std::size_t kBlocks = 8;

// Wasserstein-1 distance of two samples (512 quantiles).
double wasserstein1(std::vector<double> a, std::vector<double> b) {
    if (a.empty() || b.empty()) return kNaN;
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    return wasserstein1_sorted(a, b, 512);
}

}  // namespace

// Passages between the two wells: crossings of the band [mid - band, mid + band] from one side to the other.
namespace {
// Which side of the band [mid - band, mid + band] s is on: +1 above, -1 below, 0 inside.
int band_side(double s, double mid, double band) { return s > mid + band ? 1 : s < mid - band ? -1 : 0; }
}  // namespace

std::size_t well_changes(const std::vector<double>& x, double mid, double band) {
    int side = 0;
    std::size_t n = 0;
    for (double v : x) {
        if (!std::isfinite(v)) continue;
        const int s = band_side(v, mid, band);
        if (s == 0) continue;
        if (side != 0 && s != side) ++n;
        side = s;
    }
    return n;
}

namespace {
// The fraction of the visits to either side of [mid - band, mid + band] in which the motion turns back at least
// twice (by more than the band: noise does not turn it).
double oscillating_visits(const std::vector<double>& x, double mid, double band) {
    int side = 0, dir = 0, turns = 0;
    double ext = 0;
    std::size_t visits = 0, oscillating = 0;
    for (double s : x) {
        if (!std::isfinite(s)) continue;
        const int at = band_side(s, mid, band);
        if (at != 0 && at != side) {
            if (side != 0) {
                ++visits;
                if (turns >= 2) ++oscillating;
            }
            side = dir = at;
            turns = 0;
            ext = s;
        }
        if (side == 0) continue;
        if (dir * (s - ext) > 0) ext = s;   // still going the same way: the extremum moves on
        else if (dir * (ext - s) > band) {   // turned back
            ++turns;
            dir = -dir;
            ext = s;
        }
    }
    return visits ? static_cast<double>(oscillating) / static_cast<double>(visits) : 0.0;
}
}  // namespace

std::size_t well_changes(const std::vector<double>& x, const WellBand& wb) { return wb.found ? well_changes(x, wb.hilltop, wb.band) : 0; }

namespace {

// Welch's one-sided PSD of x (Hann segments of `seg` samples, half overlapping, mean removed), bins 0..seg/2.
std::vector<double> welch(const std::vector<double>& x, std::size_t seg) {
    std::size_t count = 0;
    std::vector<double> psd = welch_sum(x, seg, false, count);
    for (double& p : psd) p /= static_cast<double>(count);
    return psd;
}

}  // namespace

WellBand well_band(const std::vector<double>& x, bool chaotic) {
    WellBand wb;
    std::vector<double> v;
    for (double s : x)
        if (std::isfinite(s)) v.push_back(s);
    if (v.size() < 200) return wb;
    const double lo = quantile(v, 0.01), hi = quantile(v, 0.99);
    if (!(hi > lo)) return wb;
    // A chaotic motion between wells can fill the dip with its fast swings through the hilltop (the mismatch
    // set's asymmetric chaos, x high-passed, has none). Its visits to either side of the median still turn back
    // and forth inside one well (18-26 % of them), where a periodic motion about one well swings once per visit.
    auto by_median = [&]() {
        const double mid = quantile(v, 0.5), band = 0.15 * (quantile(v, 0.75) - quantile(v, 0.25));
        if (chaotic && band > 0 && oscillating_visits(v, mid, band) >= 0.15) {
            wb.found = true;
            wb.hilltop = mid;
            wb.band = band;
        }
        return wb;
    };
    // A histogram of 40 bins, smoothed over three: two humps with a dip between them below half the lower hump
    // are two wells; the dip's bin is the hilltop.
    constexpr int kBins = 40;
    std::vector<double> h(kBins, 0.0), sm(kBins, 0.0);
    for (double s : v) {
        const int b = static_cast<int>((s - lo) / (hi - lo) * kBins);
        if (b >= 0 && b < kBins) h[static_cast<std::size_t>(b)] += 1;
    }
    for (int b = 0; b < kBins; ++b) {
        double s = 0, c = 0;
        for (int d = -1; d <= 1; ++d)
            if (b + d >= 0 && b + d < kBins) {
                s += h[static_cast<std::size_t>(b + d)];
                c += 1;
            }
        sm[static_cast<std::size_t>(b)] = s / c;
    }
    const auto left = std::max_element(sm.begin(), sm.begin() + kBins / 2);
    const auto right = std::max_element(sm.begin() + kBins / 2, sm.end());
    const auto dip = std::min_element(left, right + 1);
    if (dip == left || dip == right || !(*dip < 0.5 * std::min(*left, *right))) return by_median();
    const double bw = (hi - lo) / kBins;
    const double xl = lo + (static_cast<double>(left - sm.begin()) + 0.5) * bw, xr = lo + (static_cast<double>(right - sm.begin()) + 0.5) * bw;
    const double hilltop = lo + (static_cast<double>(dip - sm.begin()) + 0.5) * bw, band = 0.15 * (xr - xl);
    // A well is a place the motion oscillates in. A steady oscillation about one well also has two humps (the
    // arcsine density of its turning points), but it visits each side for one swing only: a pair of wells
    // needs some visits that turn back and forth inside one side (a chaotic cross-well record: 19-25 %).
    if (oscillating_visits(v, hilltop, band) < 0.05) return by_median();
    wb.found = true;
    wb.hilltop = hilltop;
    wb.band = band;
    return wb;
}

AttractorStats attractor_stats(const Prep& pr, const std::vector<double>& sim, std::size_t from) {
    AttractorStats st;
    const std::vector<double>& xd = pr.data->x;
    const std::size_t n = std::min(sim.size(), xd.size());
    std::vector<double> d, s, dv, sv;
    for (std::size_t i = from; i < n; ++i)
        if (std::isfinite(sim[i]) && std::isfinite(xd[i])) {
            d.push_back(xd[i]);
            s.push_back(sim[i]);
        }
    std::size_t finite_data = 0;
    for (std::size_t i = from; i < n; ++i) finite_data += std::isfinite(xd[i]) ? 1 : 0;
    // A run that stalled part of the way has no attractor to compare: every unit missing.
    if (d.size() < 4 * kBlocks || static_cast<double>(d.size()) < 0.9 * static_cast<double>(finite_data)) return st;
    st.ok = true;
    const double sd = std::max(stdev(d, 0, d.size()), 1e-300);
    // Velocities by central differences of the samples: the same operator on both, noise and all.
    auto diff = [&](const std::vector<double>& x, std::vector<double>& out) {
        for (std::size_t i = 1; i + 1 < x.size(); ++i) out.push_back((x[i + 1] - x[i - 1]) / (2.0 * pr.dt));
    };
    diff(d, dv);
    diff(s, sv);
    const double sdv = std::max(stdev(dv, 0, dv.size()), 1e-300);
    const WellBand wb = well_band(d, pr.predictability.measured && !pr.predictability.regular);
    const double seconds = static_cast<double>(d.size()) * pr.dt;
    const double rate_d = wb.found ? static_cast<double>(well_changes(d, wb.hilltop, wb.band)) / seconds : 0.0;
    // The spectrum by bands one forcing frequency wide, each around a harmonic (and one below the first, for
    // subharmonics and the slow wandering between wells): a periodic model puts its power in its lines, a
    // chaotic record spreads it, and band powers compare the two fairly where single bins would not. Segments
    // of about eight forcing periods (a power of two); a band 40 dB below the record's total counts little.
    std::size_t seg = 64;
    while (seg < 8.0 * pr.period / pr.dt && seg < d.size() / (2 * kBlocks)) seg *= 2;
    const double df = 1.0 / (static_cast<double>(seg) * pr.dt), f0 = 1.0 / pr.period;
    auto bands = [&](const std::vector<double>& psd) {
        std::vector<double> b(9, 0.0);
        for (std::size_t k = 1; k < psd.size(); ++k) {
            const double f = static_cast<double>(k) * df;
            const double h = f / f0;
            if (h < 0.1 || h >= 8.5) continue;
            b[h < 0.5 ? 0 : static_cast<std::size_t>(std::lround(h))] += psd[k];
        }
        return b;
    };
    const std::vector<double> bd = bands(welch(d, seg));
    double total = 0;
    for (double v : bd) total += v;
    const double eps = 1e-4 * total;
    const std::size_t m = d.size();
    for (std::size_t b = 0; b < kBlocks; ++b) {
        const std::size_t a = b * m / kBlocks, e = (b + 1) * m / kBlocks;
        const std::vector<double> sb(s.begin() + static_cast<long>(a), s.begin() + static_cast<long>(e));
        st.hist_x.push_back(wasserstein1(sb, d) / sd);
        const std::size_t av = a > 0 ? a - 1 : 0, ev = std::min(e, sv.size());
        const std::vector<double> svb(sv.begin() + static_cast<long>(av), sv.begin() + static_cast<long>(ev));
        st.hist_v.push_back(wasserstein1(svb, dv) / sdv);
        if (wb.found) {
            const double r = static_cast<double>(well_changes(sb, wb.hilltop, wb.band)) / (static_cast<double>(e - a) * pr.dt);
            // Relative to the record's rate, on a log scale, with half a change per block as the least rate.
            const double least = 0.5 / (static_cast<double>(e - a) * pr.dt);
            st.wells.push_back(std::abs(std::log(std::max(r, least) / std::max(rate_d, least))));
            st.rate_sim += r / kBlocks;
        }
        if (total > 0) {
            const std::vector<double> ps = welch(sb, std::min(seg, sb.size()));
            if (ps.size() == seg / 2 + 1) {
                const std::vector<double> bs = bands(ps);
                double q = 0, c = 0;
                for (std::size_t k = 0; k < bd.size(); ++k) {
                    if (!(bd[k] > eps)) continue;
                    const double db = 10.0 * std::log10((bs[k] + eps) / (bd[k] + eps));
                    q += db * db;
                    c += 1;
                }
                st.spectrum_db.push_back(c > 0 ? std::sqrt(q / c) : 0.0);
            } else {
                st.spectrum_db.push_back(INFINITY);
            }
        }
    }
    st.wells_found = wb.found;
    st.rate_data = rate_d;
    return st;
}

double AttractorStats::mean(const std::vector<double>& v) {
    double s = 0, c = 0;
    for (double x : v)
        if (std::isfinite(x)) {
            s += x;
            c += 1;
        }
    return c > 0 ? s / c : kNaN;
}

std::vector<PrintedError> attractor_errors(const AttractorStats& st) {
    std::vector<PrintedError> out;
    auto unit = [&](const char* name, const std::vector<double>& v) {
        PrintedError e;
        e.name = name;
        e.kind = PrintedError::Kind::Mean;
        e.missing_fails = false;
        for (double x : v) {
            e.num.push_back(x);
            e.den.push_back(1.0);
        }
        if (!e.num.empty()) out.push_back(std::move(e));
    };
    if (!st.ok) {
        // A free run that never got going (a model the integrator cannot follow): every unit missing.
        PrintedError e;
        e.name = kErrHistX;
        e.kind = PrintedError::Kind::Mean;
        e.num.assign(kBlocks, INFINITY);
        e.den.assign(kBlocks, 1.0);
        out.push_back(std::move(e));
        return out;
    }
    unit(kErrHistX, st.hist_x);
    unit(kErrHistV, st.hist_v);
    if (st.wells_found) unit(kErrWells, st.wells);
    unit(kErrSpectrum, st.spectrum_db);
    return out;
}

}  // namespace impactlab::identify::detail
