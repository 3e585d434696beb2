// Signal processing for impactlab fit: noise level, Savitzky-Golay weights, the weak-form kernel, the
// omega(t) fitted to phi, the dominant period.
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <unsupported/Eigen/FFT>

#include "identify/internal.hpp"

namespace impactlab::identify::detail {

double median(std::vector<double> v) {
    if (v.empty()) return kNaN;
    const auto mid = v.begin() + static_cast<long>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    double m = *mid;
    if (v.size() % 2 == 0) m = 0.5 * (m + *std::max_element(v.begin(), mid));
    return m;
}

double quantile(std::vector<double> v, double q) {
    if (v.empty()) return kNaN;
    const double pos = std::clamp(q, 0.0, 1.0) * static_cast<double>(v.size() - 1);
    const auto k = static_cast<std::size_t>(pos);
    std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
    const double a = v[k];
    if (k + 1 >= v.size()) return a;
    const double b = *std::min_element(v.begin() + static_cast<long>(k) + 1, v.end());
    return a + (pos - static_cast<double>(k)) * (b - a);
}

double wasserstein1_sorted(const std::vector<double>& a, const std::vector<double>& b, int quantiles) {
    double s = 0;
    for (int k = 0; k < quantiles; ++k) {
        const double q = (k + 0.5) / quantiles;
        const auto ia = static_cast<std::size_t>(q * static_cast<double>(a.size()));
        const auto ib = static_cast<std::size_t>(q * static_cast<double>(b.size()));
        s += std::abs(a[std::min(ia, a.size() - 1)] - b[std::min(ib, b.size() - 1)]);
    }
    return s / quantiles;
}

double noise_sigma(const std::vector<double>& x) {
    if (x.size() < 16) return 0.0;
    std::vector<double> d;
    d.reserve(x.size());
    for (std::size_t i = 0; i + 4 < x.size(); ++i)
        d.push_back(std::abs(x[i] - 4 * x[i + 1] + 6 * x[i + 2] - 4 * x[i + 3] + x[i + 4]));
    // var(4th difference) = 70 sigma^2; MAD of a normal = 0.6745 sigma.
    return median(std::move(d)) / 0.6745 / std::sqrt(70.0);
}

std::vector<double> welch_sum(const std::vector<double>& x, std::size_t seg, bool remove_line, std::size_t& segments) {
    segments = 0;
    if (x.size() < seg) return {};
    std::vector<double> win(seg);
    for (std::size_t k = 0; k < seg; ++k) win[k] = 0.5 - 0.5 * std::cos(2.0 * kPi * static_cast<double>(k) / static_cast<double>(seg));
    Eigen::FFT<double> fft;
    std::vector<double> buf(seg), psd(seg / 2 + 1, 0.0);
    std::vector<std::complex<double>> spec;
    const double c = 0.5 * static_cast<double>(seg - 1);
    for (std::size_t a = 0; a + seg <= x.size(); a += seg / 2) {
        // The segment's mean (and drift) would leak into every bin.
        double sx = 0, sxy = 0;
        for (std::size_t k = 0; k < seg; ++k) {
            sx += x[a + k];
            if (remove_line) sxy += (static_cast<double>(k) - c) * x[a + k];
        }
        const double mean = sx / static_cast<double>(seg);
        const double slope = remove_line ? sxy / (static_cast<double>(seg) * (static_cast<double>(seg) * static_cast<double>(seg) - 1) / 12.0) : 0.0;
        for (std::size_t k = 0; k < seg; ++k)
            buf[k] = (remove_line ? x[a + k] - mean - slope * (static_cast<double>(k) - c) : x[a + k] - mean) * win[k];
        fft.fwd(spec, buf);
        for (std::size_t k = 0; k <= seg / 2; ++k) psd[k] += std::norm(spec[k]);
        ++segments;
    }
    return psd;
}

double noise_sigma_spectral(const std::vector<double>& x) {
    // Welch: Hann-windowed segments of 1024 samples, half overlapping, each detrended; the one-sided PSD of
    // white noise of variance s^2 is 2 s^2 / fs, so s^2 = PSD * fs / 2 with the PSD in units of 1/fs.
    constexpr std::size_t kSeg = 1024;
    if (x.size() < 2 * kSeg) return INFINITY;
    double wss = 0;
    for (std::size_t k = 0; k < kSeg; ++k) {
        const double w = 0.5 - 0.5 * std::cos(2.0 * kPi * static_cast<double>(k) / static_cast<double>(kSeg));
        wss += w * w;
    }
    std::size_t count = 0;
    const std::vector<double> psd = welch_sum(x, kSeg, true, count);
    // The floor: the median over the top fifth of the band (below Nyquist), where a sampled mechanical
    // signal has least power. |X_k|^2 / sum(w^2) is the two-sided periodogram's variance density per bin.
    std::vector<double> top;
    for (std::size_t k = kSeg / 2 * 4 / 5; k < kSeg / 2; ++k) top.push_back(psd[k] / (static_cast<double>(count) * wss));
    return std::sqrt(median(std::move(top)));
}

std::vector<double> savgol(int half, int degree, int deriv, double dt) {
    const int n = 2 * half + 1;
    Eigen::MatrixXd A(n, degree + 1);
    for (int j = 0; j < n; ++j)
        for (int k = 0; k <= degree; ++k) A(j, k) = std::pow(static_cast<double>(j - half), k);
    const Eigen::MatrixXd C = (A.transpose() * A).ldlt().solve(A.transpose());
    double fact = 1;
    for (int k = 2; k <= deriv; ++k) fact *= k;
    std::vector<double> c(static_cast<std::size_t>(n));
    for (int j = 0; j < n; ++j) c[static_cast<std::size_t>(j)] = fact * C(deriv, j) / std::pow(dt, deriv);
    return c;
}

std::vector<double> onesided_slope(int n, int degree, double dt, bool left) {
    Eigen::MatrixXd A(n, degree + 1);
    for (int j = 0; j < n; ++j) {
        const double tau = left ? static_cast<double>(j - (n - 1)) - 0.5 : static_cast<double>(j) + 0.5;
        for (int k = 0; k <= degree; ++k) A(j, k) = std::pow(tau, k);
    }
    const Eigen::MatrixXd C = (A.transpose() * A).ldlt().solve(A.transpose());
    std::vector<double> c(static_cast<std::size_t>(n));
    for (int j = 0; j < n; ++j) c[static_cast<std::size_t>(j)] = C(1, j) / dt;   // slope at tau = 0 (the split)
    return c;
}

std::vector<double> apply_fir(const std::vector<double>& x, const std::vector<double>& c) {
    const std::size_t n = x.size(), len = c.size(), M = len / 2;
    std::vector<double> y(n, kNaN);
    if (n < len) return y;
    for (std::size_t i = M; i + M < n; ++i) {
        double s = 0;
        const double* xp = &x[i - M];
        for (std::size_t k = 0; k < len; ++k) s += c[k] * xp[k];
        y[i] = s;
    }
    return y;
}

Kernel make_kernel(int H, double dt) {
    Kernel K;
    K.H = H;
    const double L = (H + 1) * dt;
    const std::size_t n = static_cast<std::size_t>(2 * H + 1);
    K.w.resize(n);
    K.w1.resize(n);
    K.w2.resize(n);
    double S = 0;
    for (int j = -H; j <= H; ++j) {
        const double tau = j * dt, u = tau * tau / (L * L), q = 1.0 - u;
        const double q4 = q * q * q * q, q5 = q4 * q;
        const auto k = static_cast<std::size_t>(j + H);
        K.w[k] = q5 * q;
        K.w1[k] = 12.0 * tau * q5 / (L * L);                                  // -phi'
        K.w2[k] = -12.0 * q5 / (L * L) + 120.0 * tau * tau * q4 / (L * L * L * L);   // phi''
        S += K.w[k];
    }
    double g = 0;
    for (std::size_t k = 0; k < n; ++k) {
        K.w[k] /= S;
        K.w1[k] /= S;
        K.w2[k] /= S;
        g += K.w2[k] * K.w2[k];
    }
    K.noise_gain = std::sqrt(g);
    return K;
}

namespace {

// Symmetric positive definite band system (half-bandwidth B) by LDL^T, in place; a(i, j) stored at
// band[i][j - i] for j = i..i+B.
void band_solve(std::vector<std::array<double, 4>>& band, std::vector<double>& rhs) {
    constexpr int B = 3;
    const int n = static_cast<int>(rhs.size());
    for (int i = 0; i < n; ++i) {
        for (int k = std::max(0, i - B); k < i; ++k) {
            // a(k, i) = L(i, k) * D(k)
            const double lik = band[static_cast<std::size_t>(k)][static_cast<std::size_t>(i - k)] /
                               band[static_cast<std::size_t>(k)][0];
            for (int j = i; j <= std::min(n - 1, k + B); ++j)
                band[static_cast<std::size_t>(i)][static_cast<std::size_t>(j - i)] -=
                    lik * band[static_cast<std::size_t>(k)][static_cast<std::size_t>(j - k)];
        }
    }
    // Forward: L y = rhs (L(i,k) = band[k][i-k] / D(k)), then D, then back.
    for (int i = 0; i < n; ++i)
        for (int k = std::max(0, i - B); k < i; ++k)
            rhs[static_cast<std::size_t>(i)] -= band[static_cast<std::size_t>(k)][static_cast<std::size_t>(i - k)] /
                                                band[static_cast<std::size_t>(k)][0] * rhs[static_cast<std::size_t>(k)];
    for (int i = 0; i < n; ++i) rhs[static_cast<std::size_t>(i)] /= band[static_cast<std::size_t>(i)][0];
    for (int i = n - 1; i >= 0; --i)
        for (int j = i + 1; j <= std::min(n - 1, i + B); ++j)
            rhs[static_cast<std::size_t>(i)] -= band[static_cast<std::size_t>(i)][static_cast<std::size_t>(j - i)] /
                                                band[static_cast<std::size_t>(i)][0] * rhs[static_cast<std::size_t>(j)];
}

Drive fit_drive_once(const std::vector<double>& t, const std::vector<double>& phi, double spacing, double& rms) {
    // phi as a quadratic spline on uniform knots (C1, so omega = phi' is piecewise linear and continuous):
    // exactly the Drive family. Uniform quadratic B-splines give a banded, constraint-free least squares.
    const double t0 = t.front(), t1 = t.back();
    const std::size_t K = std::max<std::size_t>(1, static_cast<std::size_t>(std::llround((t1 - t0) / spacing)));
    const double D = (t1 - t0) / static_cast<double>(K);
    const std::size_t nc = K + 2;
    std::vector<std::array<double, 4>> band(nc, {0, 0, 0, 0});
    std::vector<double> rhs(nc, 0.0);
    auto basis = [&](double tt, std::size_t& s, double b[3]) {
        const double u = (tt - t0) / D;
        s = static_cast<std::size_t>(std::clamp(std::floor(u), 0.0, static_cast<double>(K - 1)));
        const double r = u - static_cast<double>(s);
        b[0] = 0.5 * (1 - r) * (1 - r);
        b[1] = 0.5 * (-2 * r * r + 2 * r + 1);
        b[2] = 0.5 * r * r;
    };
    const double ref = phi.front();   // subtract a constant for conditioning
    for (std::size_t i = 0; i < t.size(); ++i) {
        std::size_t s;
        double b[3];
        basis(t[i], s, b);
        for (int p = 0; p < 3; ++p) {
            rhs[s + static_cast<std::size_t>(p)] += b[p] * (phi[i] - ref);
            for (int q = p; q < 3; ++q) band[s + static_cast<std::size_t>(p)][static_cast<std::size_t>(q - p)] += b[p] * b[q];
        }
    }
    for (std::size_t k = 0; k < nc; ++k) band[k][0] += 1e-12;   // regular where a stretch holds no sample
    band_solve(band, rhs);
    std::vector<double> knots(K + 1), w(K + 1);
    for (std::size_t k = 0; k <= K; ++k) {
        knots[k] = k == K ? t1 : t0 + D * static_cast<double>(k);
        w[k] = std::max(0.0, (rhs[k + 1] - rhs[k]) / D);
    }
    Drive d = Drive::piecewise_linear(knots, w, ref + 0.5 * (rhs[0] + rhs[1]));
    double ss = 0;
    for (std::size_t i = 0; i < t.size(); ++i) {
        const double e = d.phi(t[i]) - phi[i];
        ss += e * e;
    }
    rms = std::sqrt(ss / static_cast<double>(t.size()));
    return d;
}

}  // namespace

Drive fit_drive(const std::vector<double>& t, const std::vector<double>& phi, double spacing, double& rms) {
    const double noise = std::max(noise_sigma(phi), 1e-6);
    Drive d = fit_drive_once(t, phi, spacing, rms);
    const double dt = (t.back() - t.front()) / static_cast<double>(t.size() - 1);
    for (int halving = 0; halving < 4 && rms > 3.0 * noise && spacing / 2 >= 20 * dt; ++halving) {
        spacing /= 2;
        double r2 = 0;
        Drive d2 = fit_drive_once(t, phi, spacing, r2);
        if (r2 >= rms) break;
        d = d2;
        rms = r2;
    }
    return d;
}

double stdev(const std::vector<double>& v, std::size_t a, std::size_t b) {
    double m = 0, s = 0, c = 0;
    for (std::size_t i = a; i < b; ++i)
        if (std::isfinite(v[i])) {
            m += v[i];
            c += 1;
        }
    if (c < 2) return 0;
    m /= c;
    for (std::size_t i = a; i < b; ++i)
        if (std::isfinite(v[i])) s += (v[i] - m) * (v[i] - m);
    return std::sqrt(s / (c - 1));
}

std::vector<double> highpass_fft(const std::vector<double>& x, double dt, double cut_hz) {
    if (x.size() < 4 || !(cut_hz > 0) || !(dt > 0)) return x;
    double mean = 0;
    for (double v : x) {
        if (!std::isfinite(v)) return x;
        mean += v;
    }
    mean /= static_cast<double>(x.size());
    // The least length from n up with no prime factor above 7 (the FFT's cost stays N log N; they lie within a
    // few percent of any n), the gap bridged by a straight line from the last sample back to the first, so
    // that the periodic signal the transform sees is the record's own.
    auto smooth7 = [](std::size_t m) {
        for (std::size_t f : {2, 3, 5, 7})
            while (m % f == 0) m /= f;
        return m == 1;
    };
    const std::size_t n = x.size();
    std::size_t N = n;
    while (!smooth7(N)) ++N;
    std::vector<double> buf(N, 0.0);
    for (std::size_t i = 0; i < n; ++i) buf[i] = x[i] - mean;
    for (std::size_t i = n; i < N; ++i) {
        const double w = static_cast<double>(i - n + 1) / static_cast<double>(N - n + 1);
        buf[i] = (1.0 - w) * buf[n - 1] + w * buf[0];
    }
    Eigen::FFT<double> fft;
    std::vector<std::complex<double>> spec;
    fft.fwd(spec, buf);
    const double df = 1.0 / (static_cast<double>(N) * dt);
    for (std::size_t k = 0; k < spec.size(); ++k) {
        const std::size_t fk = std::min(k, N - k);   // the negative frequencies mirror the positive ones
        if (static_cast<double>(fk) * df < cut_hz) spec[k] = 0.0;
    }
    fft.inv(buf, spec);
    buf.resize(x.size());
    return buf;
}

double dominant_period(const std::vector<double>& x, double dt) {
    std::size_t N = 1;
    while (N < x.size()) N <<= 1;
    double mean = 0;
    for (double v : x) mean += v;
    mean /= static_cast<double>(x.size());
    std::vector<double> buf(N, 0.0);
    const double n = static_cast<double>(x.size());
    for (std::size_t i = 0; i < x.size(); ++i)
        buf[i] = (x[i] - mean) * (0.5 - 0.5 * std::cos(kTwoPi * static_cast<double>(i) / (n - 1)));
    Eigen::FFT<double> fft;
    std::vector<std::complex<double>> spec;
    fft.fwd(spec, buf);
    std::size_t best = 1;
    double pmax = 0;
    for (std::size_t k = 2; k < N / 2; ++k) {
        const double p = std::norm(spec[k]);
        if (p > pmax) {
            pmax = p;
            best = k;
        }
    }
    return static_cast<double>(N) * dt / static_cast<double>(best);
}

double quantum_sigma(const std::vector<double>& x) {
    if (x.size() < 16) return 0.0;
    double q = INFINITY;
    for (std::size_t i = 0; i + 1 < x.size(); ++i)
        if (const double d = std::abs(x[i + 1] - x[i]); d > 0) q = std::min(q, d);
    if (!std::isfinite(q)) return 0.0;
    // A step only where nearly every change is a whole number of it (random decimals fall on one 2 % of the time).
    std::size_t changes = 0, whole = 0;
    for (std::size_t i = 0; i + 1 < x.size(); ++i) {
        const double d = std::abs(x[i + 1] - x[i]);
        if (!(d > 0)) continue;
        ++changes;
        const double r = d / q;
        if (r < 1e6 && std::abs(r - std::round(r)) < 0.01) ++whole;
    }
    return changes > 0 && static_cast<double>(whole) >= 0.99 * static_cast<double>(changes) ? q / std::sqrt(12.0) : 0.0;
}

}  // namespace impactlab::identify::detail

namespace impactlab::identify {
// The smaller of the two estimates (signal only adds to either), but never below the rounding of a sensor that
// reads in steps: a slow record in an ADC's counts has most of its 4th differences zero, and a noise of 0
// made every error "inf times the noise".
double estimate_noise(const std::vector<double>& x) {
    return std::max(std::min(detail::noise_sigma(x), detail::noise_sigma_spectral(x)), detail::quantum_sigma(x));
}
}  // namespace impactlab::identify
