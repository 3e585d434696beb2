// The record's wells from its x histogram (core/src/identify/attractor.cpp): a steady oscillation in one well,
// whose density has its humps at the turning points, is no pair of wells; a motion that dwells in two wells
// and passes between them is, and each passage is counted once.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "identify/internal.hpp"

namespace dt = impactlab::identify::detail;

TEST_CASE("attractor: a steady oscillation in one well has no pair of wells, at any amplitude or offset") {
    std::mt19937 rng(5);
    std::normal_distribution<double> noise(0.0, 1e-6);
    for (double amp : {1e-4, 1.5e-3, 0.02})
        for (double offset : {0.0, 0.012}) {
            CAPTURE(amp);
            CAPTURE(offset);
            std::vector<double> x;
            for (int i = 0; i < 80000; ++i)   // 40 s at 2 kHz of an 8.05 Hz response with a 3rd harmonic
                x.push_back(offset + amp * (std::sin(2 * std::numbers::pi * 8.05 * i / 2000.0) +
                                            0.05 * std::sin(3 * 2 * std::numbers::pi * 8.05 * i / 2000.0)) +
                            noise(rng));
            const dt::WellBand wb = dt::well_band(x);
            CHECK_FALSE(wb.found);
            CHECK(dt::well_changes(x, wb) == 0);
        }
}

TEST_CASE("attractor: a motion that dwells in two wells has them, the hilltop between, each passage counted once") {
    // Oscillations of 3 mm about wells at -12 and +12 mm, hopping to the other well after 2-8 periods.
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> dwell(2, 8);
    std::vector<double> x;
    const int per = 250;   // samples per period (8 Hz at 2 kHz)
    int hops = 0;
    double well = -0.012;
    while (x.size() < 80000) {
        const int n = dwell(rng);
        for (int i = 0; i < n * per; ++i) x.push_back(well + 0.003 * std::sin(2 * std::numbers::pi * i / per));
        for (int i = 0; i < per; ++i)   // the passage: half a cosine over one period
            x.push_back(well - 2 * well * 0.5 * (1 - std::cos(std::numbers::pi * i / per)));
        well = -well;
        ++hops;
    }
    const dt::WellBand wb = dt::well_band(x);
    REQUIRE(wb.found);
    CHECK(std::abs(wb.hilltop) < 0.003);
    CHECK(dt::well_changes(x, wb) == doctest::Approx(hops).epsilon(0.02));
}
