// Sweeps and sections: convergence of section points with the tolerance, the CF diagram of A1H (short and
// full), the EF ramp, count_period, progress and cancellation, the CSV writer, sweeps over xI and m0e.
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "impactlab/params.hpp"
#include "impactlab/sweep.hpp"

using namespace impactlab;

namespace {

constexpr double kPi = std::numbers::pi;

Tolerances with_rtol(double rtol) {
    Tolerances t;
    t.rtol = rtol;
    return t;
}

// The recorded x at one omega of a diagram.
std::vector<double> xs_at(const Diagram& d, double omega) {
    std::vector<double> xs;
    for (const auto& pt : d.points)
        if (std::abs(pt.omega - omega) < 1e-9) xs.push_back(pt.x);
    return xs;
}

double min_of(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }
double max_of(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

}  // namespace

TEST_CASE("count_period: clusters of section points") {
    CHECK(count_period({}, 1e-6) == 0);
    CHECK(count_period({0.1, 0.1 + 1e-9, 0.1 - 1e-9}, 1e-6) == 1);
    CHECK(count_period({-0.015, -0.009, -0.015, -0.009, -0.015}, 1e-6) == 2);
    CHECK(count_period({1.0, 2.0, 3.0, 1.0, 2.0, 3.0}, 1e-3) == 3);
    // More clusters than max_period: max_period + 1 ("not periodic").
    std::vector<double> many;
    for (int i = 0; i < 40; ++i) many.push_back(0.001 * i);
    CHECK(count_period(many, 1e-6, 16) == 17);
    CHECK(count_period(many, 1e-6, 50) == 40);
    // The tolerance decides.
    CHECK(count_period({0.0, 2e-6}, 1e-6) == 2);
    CHECK(count_period({0.0, 2e-6}, 1e-5) == 1);
}

TEST_CASE("poincare_section: one point per revolution, n counted after the transient, at phi = 2 pi n") {
    const Params p = make_version("A1H");
    State s;
    s.x = -0.011;
    s.t = 3.0;   // the drive starts where the state is, phase 0
    const double omega = 9.0;
    const auto pts = poincare_section(p, omega, 12, 5, s);
    REQUIRE(pts.size() == 12);
    for (std::size_t i = 0; i < pts.size(); ++i) {
        CHECK(pts[i].n == static_cast<std::int64_t>(i) + 6);
        CHECK(pts[i].t == doctest::Approx(3.0 + 2 * kPi * static_cast<double>(pts[i].n) / omega).epsilon(1e-14));
    }
    CHECK(s.t == doctest::Approx(3.0 + 2 * kPi * 17 / omega).epsilon(1e-14));
    CHECK(pts.back().x == s.x);
    CHECK(pts.back().v == s.v);
}

TEST_CASE("section points converge with the tolerance: rtol 1e-7 and 1e-10 agree to 1e-6 m") {
    const Params p = make_version("A1H");
    // 5 and 9 rad/s: period 1 in the left well; 11.5 rad/s: period 2.
    for (double omega : {5.0, 9.0, 11.5}) {
        State settled;
        settled.x = -0.011;   // the left well
        poincare_section(p, omega, 1, 60, settled, with_rtol(1e-10));
        State a = settled, b = settled;
        const auto pa = poincare_section(p, omega, 20, 0, a, with_rtol(1e-7));
        const auto pb = poincare_section(p, omega, 20, 0, b, with_rtol(1e-10));
        REQUIRE(pa.size() == 20);
        REQUIRE(pb.size() == 20);
        double worst = 0;
        std::vector<double> xs;
        for (std::size_t i = 0; i < pa.size(); ++i) {
            CHECK(pa[i].t == pb[i].t);
            worst = std::max(worst, std::abs(pa[i].x - pb[i].x));
            xs.push_back(pb[i].x);
        }
        CAPTURE(omega);
        MESSAGE("omega " << omega << ": |x(rtol 1e-7) - x(rtol 1e-10)| <= " << worst << " m over 20 sections; "
                         << a.steps - settled.steps << " vs " << b.steps - settled.steps << " steps");
        CHECK(worst < 1e-6);
        CHECK(count_period(xs, 1e-5) == (omega < 11 ? 1 : 2));
        CHECK(max_of(xs) < -0.005);   // still in the left well
        // A looser tolerance takes fewer steps (the tolerance is really used).
        CHECK(a.steps - settled.steps < b.steps - settled.steps);
    }
}

TEST_CASE("short CF sweep of A1H: period 1 at 9.25 and 10.25, period 2 at 11.25 and 12.25, left well") {
    // run_cf_sweep starts at rest at x = 0; at 9.25 rad/s the forcing throws the cart into the left well,
    // where the full 300-step run also has it (checked below against that run).
    const Params p = make_version("A1H");
    CfSpec spec;
    spec.omega_min = 9.25;
    spec.omega_max = 12.25;
    spec.steps = 4;
    spec.transient = 60;
    spec.record = 16;
    Progress progress;
    const Diagram d = run_cf_sweep(p, spec, &progress);
    CHECK(d.protocol == "cf-up");
    CHECK(d.model == "A1H");
    CHECK_FALSE(d.cancelled);
    CHECK(progress.fraction.load() == 1.0);
    REQUIRE(d.points.size() == 64);
    const double omegas[4] = {9.25, 10.25, 11.25, 12.25};
    const int periods[4] = {1, 1, 2, 2};
    for (int j = 0; j < 4; ++j) {
        const auto xs = xs_at(d, omegas[j]);
        CAPTURE(omegas[j]);
        REQUIRE(xs.size() == 16);
        CHECK(count_period(xs, 1e-5) == periods[j]);
        CHECK(max_of(xs) < -0.005);
        CHECK(min_of(xs) > -0.02);
    }
    // In period 2 the two section points are well apart (a real doubling, not noise).
    const auto x12 = xs_at(d, 12.25);
    CHECK(max_of(x12) - min_of(x12) > 1e-3);
    // Simulated time: 76 revolutions at each omega.
    double expect = 0;
    for (double w : omegas) expect += 76 * 2 * kPi / w;
    CHECK(d.simulated_seconds == doctest::Approx(expect).epsilon(1e-12));
}

TEST_CASE("full CF diagram of A1H (300 omegas, 20 + 70 periods): the features of MODEL.md and Fig. 3") {
    const Params p = make_version("A1H");
    const auto start = std::chrono::steady_clock::now();
    const Diagram d = run_cf_sweep(p, CfSpec{});
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    MESSAGE("A1H CF diagram: " << secs << " s wall, " << d.simulated_seconds << " s simulated, " << d.steps
                               << " steps, " << d.impacts << " impacts");
    REQUIRE(d.points.size() == 300u * 70u);
    auto period_at = [&](int j) { return count_period(xs_at(d, 25.0 * j / 300.0), 1e-5); };
    // Near the hilltop at small omega, then a slide into the left well at about 2 to 2.6 rad/s (MODEL.md).
    CHECK(std::abs(min_of(xs_at(d, 25.0 * 12 / 300.0))) < 2e-3);   // 1 rad/s
    int jump = 0;
    for (int j = 1; j <= 300 && !jump; ++j)
        if (max_of(xs_at(d, 25.0 * j / 300.0)) < -0.005) jump = j;
    MESSAGE("left well reached at omega = " << 25.0 * jump / 300.0);
    CHECK(25.0 * jump / 300.0 >= 1.9);
    CHECK(25.0 * jump / 300.0 <= 2.7);
    // Period 1 at 9.25, period 2 over 11.25..12.5, chaos somewhere in 13..19, period 1 again near 24.
    CHECK(period_at(111) == 1);
    for (int j = 135; j <= 150; ++j) {
        CAPTURE(j);
        CHECK(period_at(j) == 2);
    }
    int chaotic = 0;
    for (int j = 156; j <= 228; ++j) chaotic += period_at(j) > 16;
    CHECK(chaotic > 30);
    CHECK(period_at(288) == 1);
    CHECK(d.impacts > 0);   // the bumper is reached in the chaotic range
    // The short sweep's omegas are on this grid (9.25 = 25 * 111/300, ...): same attractors, same points.
    CfSpec spec;
    spec.omega_min = 9.25;
    spec.omega_max = 12.25;
    spec.steps = 4;
    spec.transient = 60;
    spec.record = 16;
    const Diagram s = run_cf_sweep(p, spec);
    for (int j : {111, 123, 135, 147}) {
        const double w = 25.0 * j / 300.0;
        const auto full = xs_at(d, w), part = xs_at(s, w);
        CAPTURE(w);
        CHECK(count_period(full, 1e-5) == count_period(part, 1e-5));
        CHECK(std::abs(min_of(full) - min_of(part)) < 1e-5);
        CHECK(std::abs(max_of(full) - max_of(part)) < 1e-5);
    }
}

TEST_CASE("CF sweep down visits the omegas in reverse order") {
    const Params p = make_version("A1G");
    CfSpec spec;
    spec.omega_min = 6.0;
    spec.omega_max = 8.0;
    spec.steps = 3;
    spec.transient = 2;
    spec.record = 3;
    spec.direction = SweepDirection::Down;
    const Diagram d = run_cf_sweep(p, spec);
    CHECK(d.protocol == "cf-down");
    REQUIRE(d.points.size() == 9);
    const double expect[3] = {8.0, 7.0, 6.0};
    for (std::size_t i = 0; i < 9; ++i) CHECK(d.points[i].omega == doctest::Approx(expect[i / 3]).epsilon(1e-15));
}

TEST_CASE("EF ramp: one point per revolution, omega(t) increasing along the ramp") {
    const Params p = make_version("A1C");
    EfSpec spec;
    spec.omega_max = 12.0;
    spec.t_ramp = 100.0;
    Progress progress;
    const Diagram d = run_ef_ramp(p, spec, &progress);
    CHECK(d.protocol == "ef");
    CHECK(progress.fraction.load() == 1.0);
    // phi(100) = 12 * 100 / 2 = 600 rad: 95 revolutions.
    REQUIRE(d.points.size() == 95);
    for (std::size_t i = 0; i < d.points.size(); ++i) {
        // The n-th section is at 0.5 a t^2 = 2 pi n with a = 0.12, so omega = a t = sqrt(2 a 2 pi n).
        const double n = static_cast<double>(i + 1);
        CHECK(d.points[i].omega == doctest::Approx(std::sqrt(2 * 0.12 * 2 * kPi * n)).epsilon(1e-12));
    }
    CHECK(d.simulated_seconds == 100.0);
}

TEST_CASE("cancellation stops a sweep early and says so") {
    const Params p = make_version("A1H");
    Progress progress;
    progress.cancel = true;
    const Diagram d = run_cf_sweep(p, CfSpec{}, &progress);
    CHECK(d.cancelled);
    CHECK(d.points.empty());
    CHECK(progress.fraction.load() < 1.0);
    Progress ef;
    ef.cancel = true;
    const Diagram e = run_ef_ramp(p, EfSpec{}, &ef);
    CHECK(e.cancelled);
    CHECK(e.simulated_seconds < 2800.0);
}

TEST_CASE("write_diagram_csv: header omega,x,v and one row per point, 10 significant digits") {
    Diagram d;
    d.points = {{1.5, -0.0123456789012, 0.25}, {2.0, 1e-3, -1.0 / 3.0}};
    std::ostringstream out;
    out.precision(3);
    write_diagram_csv(d, out);
    CHECK(out.str() == "omega,x,v\n1.5,-0.0123456789,0.25\n2,0.001,-0.3333333333\n");
    CHECK(out.precision() == 3);   // the stream's precision is restored
}

TEST_CASE("sweep_levels: the swept parameter from lo to hi, the others the model's and the fixed omega") {
    const Params p = make_version("A1H");
    ParamSweep s;
    s.over = SweepParam::XI;
    s.lo = -0.004;
    s.hi = 0.006;
    s.steps = 6;
    s.omega = 18.0;
    const auto up = sweep_levels(p, s);
    REQUIRE(up.size() == 6);
    CHECK(up.front().xI == -0.004);
    CHECK(up.back().xI == doctest::Approx(0.006).epsilon(1e-15));
    for (std::size_t j = 0; j < up.size(); ++j) {
        CHECK(up[j].omega == 18.0);
        CHECK(up[j].m0e == p.m0e);
        if (j > 0) CHECK(up[j].xI > up[j - 1].xI);
    }
    s.direction = SweepDirection::Down;
    const auto down = sweep_levels(p, s);
    REQUIRE(down.size() == 6);
    for (std::size_t j = 0; j < 6; ++j) CHECK(down[j].xI == up[5 - j].xI);
    // Over omega: run_cf_sweep's levels, the model's xI and m0e.
    const ParamSweep w{SweepParam::Omega, 2.0, 10.0, 5, SweepDirection::Up, 0.0};
    const auto ws = sweep_levels(p, w);
    REQUIRE(ws.size() == 5);
    for (std::size_t j = 0; j < 5; ++j) {
        CHECK(ws[j].omega == 2.0 + 8.0 * static_cast<double>(j) / 4);
        CHECK(ws[j].xI == p.xI);
        CHECK(ws[j].m0e == p.m0e);
    }
    // One step: the start of the range.
    s.steps = 1;
    REQUIRE(sweep_levels(p, s).size() == 1);
    CHECK(sweep_levels(p, s)[0].xI == -0.004);
}

TEST_CASE("a CF sweep over xI at fixed omega is run_cf_levels over hand-made levels, its points carrying xI") {
    const Params p = make_version("A1G");
    const ParamSweep s{SweepParam::XI, -0.003, 0.003, 4, SweepDirection::Up, 17.0};
    const Diagram d = run_cf_param_sweep(p, s, 3, 4);
    std::vector<CfLevel> hand;   // xI_j = lo + (hi - lo) j / (steps - 1), written out
    for (int j = 0; j < 4; ++j) hand.push_back({17.0, -0.003 + (0.003 - -0.003) * j / 3, p.m0e});
    const Diagram e = run_cf_levels(p, hand, 3, 4);
    CHECK(d.over == SweepParam::XI);
    CHECK(d.omega == 17.0);
    CHECK(d.protocol == "cf-up");
    REQUIRE(d.points.size() == 16);
    REQUIRE(e.points.size() == 16);
    for (std::size_t i = 0; i < d.points.size(); ++i) {
        CAPTURE(i);
        CHECK(d.points[i].omega == doctest::Approx(hand[i / 4].xI).epsilon(1e-15));   // xI, not omega
        CHECK(d.points[i].x == e.points[i].x);
        CHECK(d.points[i].v == e.points[i].v);
    }
    std::ostringstream csv;
    write_diagram_csv(d, csv);
    CHECK(csv.str().rfind("xI,x,v\n-0.003,", 0) == 0);
}

TEST_CASE("check_sweep: each parameter's range, the bumper, the fixed omega") {
    const Params h = make_version("A1H");
    CHECK(check_sweep(h, {SweepParam::XI, -0.01, 0.01, 10, SweepDirection::Up, 18.0}).empty());
    CHECK(check_sweep(h, {SweepParam::M0e, 0.01, 0.04, 10, SweepDirection::Up, 18.0}).empty());
    CHECK(check_sweep(h, {SweepParam::Omega, 1.0, 25.0, 10, SweepDirection::Up, 0.0}).empty());
    CHECK(check_sweep(h, {SweepParam::XI, -0.2, 0.01, 10, SweepDirection::Up, 18.0}).find("outside [-0.1, 0.1] m") != std::string::npos);
    CHECK(check_sweep(h, {SweepParam::M0e, 0.0, 0.04, 10, SweepDirection::Up, 18.0}).find("outside (0, 10] kg m") != std::string::npos);
    CHECK(check_sweep(h, {SweepParam::XI, 0.01, -0.01, 10, SweepDirection::Up, 18.0}).find("below the start") != std::string::npos);
    CHECK(check_sweep(h, {SweepParam::XI, -0.01, 0.01, 10, SweepDirection::Up, 0.0}).find("omega 0 rad/s") == 0);
    CHECK(check_sweep(make_version("A1none"), {SweepParam::XI, -0.01, 0.01, 10, SweepDirection::Up, 18.0}).find("no bumper") !=
          std::string::npos);
    CHECK(parse_sweep_param("xI") == SweepParam::XI);
    CHECK(!parse_sweep_param("xi"));
}

TEST_CASE("run_cf_levels with a settle budget: a level still in its transient is marked not settled, never chaos") {
    // A1H at 18 rad/s, the bumper moved from 0 to 2.63 mm in 20 levels: the last level's 70 section points are
    // a chaotic transient (the orbit settles on a period 18 after about 3000 periods). Judged by the map's own
    // test with 10 more records it reads kLevelNotSettled, with its points those of the last record run.
    const Params p = make_version("A1H");
    ParamSweep s;
    s.over = SweepParam::XI;
    s.lo = 0.0;
    s.hi = 0.00263;
    s.steps = 20;
    s.omega = 18.0;
    const Diagram d = run_cf_param_sweep(p, s, 20, 70, nullptr, {}, nullptr, 10);
    REQUIRE(d.levels.size() == 20);
    CHECK(d.levels.back().at == doctest::Approx(0.00263));
    CHECK(d.levels.back().period == kLevelNotSettled);
    CHECK(d.levels.back().count == 70);
    for (const DiagramLevel& lv : d.levels) CHECK(lv.period != 0);   // no chaos verdict in a diagram
    std::size_t n = 0;
    for (const DiagramLevel& lv : d.levels) {
        CHECK(lv.first == n);
        n += lv.count;
    }
    CHECK(n == d.points.size());
    std::ostringstream csv;
    write_diagram_csv(d, csv);
    CHECK(csv.str().rfind("xI,x,v,period\n", 0) == 0);
    CHECK(csv.str().find(",-1\n") != std::string::npos);
    // Without a budget: the protocol alone, no verdicts, three columns.
    const Diagram raw = run_cf_param_sweep(p, s, 20, 70);
    CHECK(raw.levels.empty());
    CHECK(raw.points.size() == 20 * 70);
}

TEST_CASE("settle_level: A1C at 11 rad/s after a CF step settles on period 2; a chaotic level reads 0 or not settled") {
    const Params p = make_version("A1C");
    ParamSweep s;
    s.lo = 10.5;
    s.hi = 11.0;
    s.steps = 3;
    const Diagram d = run_cf_param_sweep(p, s, 20, 70, nullptr, {}, nullptr, 10);
    REQUIRE(d.levels.size() == 3);
    CHECK(d.levels.back().period == 2);
    // The scan's verdicts (chaos allowed) and the diagram's (not) on one chaotic level, A1C at 16 rad/s.
    State st;
    Simulator::make_consistent(p, Drive(16.0, 0.0, 0.0), st);
    std::vector<SectionPoint> rec = poincare_section(p, 16.0, 70, 200, st);
    std::vector<SectionPoint> rec2 = rec;
    CHECK(settle_level(p, 16.0, st, rec, 16, 10, {}, true) == 0);
    CHECK(settle_level(p, 16.0, st, rec2, 32, 2, {}, false) == kLevelNotSettled);
}
