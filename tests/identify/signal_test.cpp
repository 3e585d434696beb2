// The signal tools of the fit (core/src/identify/signal.cpp): noise estimates, Savitzky-Golay weights, FIR,
// the weak-form kernel, the drive fitted to phi, the dominant period and the high-pass of a declared chain.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "identify/internal.hpp"

namespace dt = impactlab::identify::detail;

TEST_CASE("signal: median and quantile") {
    CHECK(dt::median({3.0, 1.0, 2.0}) == 2.0);
    CHECK(dt::median({4.0, 1.0, 2.0, 3.0}) == doctest::Approx(2.5));
    CHECK(dt::quantile({0.0, 1.0, 2.0, 3.0, 4.0}, 0.0) == 0.0);
    CHECK(dt::quantile({0.0, 1.0, 2.0, 3.0, 4.0}, 1.0) == 4.0);
    CHECK(dt::quantile({0.0, 1.0, 2.0, 3.0, 4.0}, 0.5) == doctest::Approx(2.0));
}

TEST_CASE("signal: the noise on a smooth signal is found by both estimates") {
    std::mt19937 rng(5);
    std::normal_distribution<double> g(0.0, 3e-6);
    std::vector<double> x(20000);
    for (std::size_t i = 0; i < x.size(); ++i) x[i] = 0.01 * std::sin(2.0 * 3.141592653589793 * 2.0 * static_cast<double>(i) * 1e-3) + g(rng);
    CHECK(dt::noise_sigma(x) == doctest::Approx(3e-6).epsilon(0.05));
    CHECK(dt::noise_sigma_spectral(x) == doctest::Approx(3e-6).epsilon(0.1));
    CHECK(impactlab::identify::estimate_noise(x) == doctest::Approx(3e-6).epsilon(0.1));
    CHECK(std::isinf(dt::noise_sigma_spectral(std::vector<double>(100, 0.0))));
}

TEST_CASE("signal: a record in whole counts has at least their rounding noise; decimals and noise add no floor") {
    // 30 counts decaying at 60 rad/s, 1 kHz: most 4th differences are zero, the rounding is 1 / sqrt(12).
    std::vector<double> counts(2000);
    for (std::size_t i = 0; i < counts.size(); ++i) {
        const double t = static_cast<double>(i) * 1e-3;
        counts[i] = std::round(30.0 * std::cos(60.0 * t) * std::exp(-2.0 * t));
    }
    CHECK(dt::noise_sigma(counts) == 0.0);
    CHECK(dt::quantum_sigma(counts) == doctest::Approx(1.0 / std::sqrt(12.0)));
    CHECK(impactlab::identify::estimate_noise(counts) == doctest::Approx(1.0 / std::sqrt(12.0)));
    // The same counts in volts of 2.5 mV a count: the step scales with the unit.
    std::vector<double> volts(counts);
    for (double& v : volts) v *= 2.5e-3;
    CHECK(impactlab::identify::estimate_noise(volts) == doctest::Approx(2.5e-3 / std::sqrt(12.0)));
    // Noise in full floating point: no step.
    std::mt19937 rng(3);
    std::normal_distribution<double> g(0.0, 3e-6);
    std::vector<double> x(4000);
    for (std::size_t i = 0; i < x.size(); ++i) x[i] = 0.01 * std::sin(0.0126 * static_cast<double>(i)) + g(rng);
    CHECK(dt::quantum_sigma(x) == 0.0);
    // Printed to 1e-6 with 3e-6 of noise: the step's rounding lies below the noise, which stands.
    std::vector<double> printed(x);
    for (double& v : printed) v = std::round(v * 1e6) / 1e6;
    CHECK(dt::quantum_sigma(printed) < 0.3e-6);
    CHECK(impactlab::identify::estimate_noise(printed) == doctest::Approx(impactlab::identify::estimate_noise(x)).epsilon(0.05));
}

TEST_CASE("signal: Savitzky-Golay derivatives are exact on polynomials of their degree, and apply_fir centres them") {
    const double h = 1e-3;
    const std::vector<double> c0 = dt::savgol(5, 3, 0, h), c1 = dt::savgol(5, 3, 1, h), c2 = dt::savgol(5, 3, 2, h);
    REQUIRE(c1.size() == 11);
    std::vector<double> x(50);
    auto poly = [](double t) { return 1.0 + 2.0 * t - 3.0 * t * t + 4.0 * t * t * t; };
    for (std::size_t i = 0; i < x.size(); ++i) x[i] = poly(static_cast<double>(i) * h);
    const std::vector<double> y0 = dt::apply_fir(x, c0), y1 = dt::apply_fir(x, c1), y2 = dt::apply_fir(x, c2);
    CHECK(std::isnan(y1[4]));   // the window leaves the data
    CHECK(std::isnan(y1[45]));
    for (std::size_t i = 5; i < 45; ++i) {
        const double t = static_cast<double>(i) * h;
        CHECK(y0[i] == doctest::Approx(poly(t)).epsilon(1e-10));
        CHECK(y1[i] == doctest::Approx(2.0 - 6.0 * t + 12.0 * t * t).epsilon(1e-7));
        CHECK(y2[i] == doctest::Approx(-6.0 + 24.0 * t).epsilon(1e-5));
    }
}

TEST_CASE("signal: the weak-form kernel averages, and its derivative weights give the averaged derivatives") {
    const double h = 1e-3;
    const dt::Kernel K = dt::make_kernel(20, h);
    REQUIRE(K.w.size() == 41);
    double sw = 0, sw1 = 0, sw2 = 0;
    for (double v : K.w) sw += v;
    CHECK(sw == doctest::Approx(1.0));
    // x = t^2 about 0: the averaged velocity is 0 (symmetric), the averaged acceleration 2.
    for (int k = -20; k <= 20; ++k) {
        const double t = k * h;
        sw1 += K.w1[static_cast<std::size_t>(k + 20)] * t * t;
        sw2 += K.w2[static_cast<std::size_t>(k + 20)] * t * t;
    }
    CHECK(std::abs(sw1) < 1e-9);
    CHECK(sw2 == doctest::Approx(2.0).epsilon(1e-6));
    CHECK(K.noise_gain > 0);
}

TEST_CASE("signal: fit_drive recovers a piecewise-linear omega from phi, dominant_period a sine's period") {
    std::vector<double> t, phi, x;
    for (int i = 0; i <= 10000; ++i) {
        const double s = i * 1e-3;
        t.push_back(s);
        phi.push_back(10.0 * s + 0.5 * s * s);   // omega = 10 + s
        x.push_back(std::sin(2.0 * 3.141592653589793 * s / 0.25));
    }
    double rms = 0;
    const impactlab::Drive d = dt::fit_drive(t, phi, 0.5, rms);
    CHECK(rms < 1e-6);
    CHECK(d.omega(3.0) == doctest::Approx(13.0).epsilon(1e-4));
    CHECK(d.phi(7.0) == doctest::Approx(10.0 * 7.0 + 0.5 * 49.0).epsilon(1e-6));
    CHECK(dt::dominant_period(x, 1e-3) == doctest::Approx(0.25).epsilon(0.02));
}

TEST_CASE("signal: highpass_fft removes what lies below its cut and keeps what lies above, at any record length") {
    // Two slow cycles over the record (0.04 Hz, a slow drift of the wells) under a 5 Hz oscillation, at 200 Hz:
    // a 0.1 Hz cut leaves the 5 Hz part away from the ends. Lengths 2^11 * 5 (the FFT's own) and a prime
    // (bridged to the next length without large prime factors).
    for (std::size_t n : {std::size_t{10240}, std::size_t{10247}}) {
        CAPTURE(n);
        const double dt = 0.005;
        std::vector<double> x(n), fast(n);
        for (std::size_t i = 0; i < n; ++i) {
            const double t = static_cast<double>(i) * dt;
            fast[i] = 1e-3 * std::sin(2 * M_PI * 5.0 * t);
            x[i] = 0.01 + 0.02 * std::sin(2 * M_PI * 2.0 * t / (static_cast<double>(n) * dt)) + fast[i];
        }
        const std::vector<double> y = dt::highpass_fft(x, dt, 0.1);
        REQUIRE(y.size() == n);
        double worst = 0;
        for (std::size_t i = n / 5; i < 4 * n / 5; ++i) worst = std::max(worst, std::abs(y[i] - fast[i]));
        CHECK(worst < 1e-4);   // a tenth of the fast part, of a slow part 20 times larger
        // No cut, or a sample that is not a number: x as it is.
        CHECK(dt::highpass_fft(x, dt, 0.0) == x);
        std::vector<double> bad = x;
        bad[7] = std::nan("");
        CHECK(std::isnan(dt::highpass_fft(bad, dt, 0.1)[7]));
    }
}
