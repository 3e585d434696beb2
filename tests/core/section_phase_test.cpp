// The Poincare section phase phi0: sections at phi = phi0 + 2 pi k land where an independent run stopped
// at that instant is (free flight, held at a rigid bumper, a piecewise-linear drive), n counts revolutions,
// phi0 = 0 (and 2 pi) is the stroboscopic section bit for bit, and poincare_section takes the phase.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "impactlab/drive.hpp"
#include "impactlab/params.hpp"
#include "impactlab/simulator.hpp"
#include "impactlab/sweep.hpp"
#include "coasting.hpp"

using namespace impactlab;
using impactlab::testing::harmonic;

namespace {

constexpr double kPi = std::numbers::pi;

struct Sections : Observer {
    std::vector<SectionPoint> pts;
    void on_section(const SectionPoint& sp) override { pts.push_back(sp); }
};

Tolerances tight() {
    Tolerances t;
    t.rtol = 1e-10;
    return t;
}

// The run with sections at phi0 from `start` to t_end.
std::vector<SectionPoint> sections_at(const Params& p, const Drive& d, State s, double phi0, double t_end) {
    Simulator sim(tight());
    sim.set_section_phase(phi0);
    Simulator::make_consistent(p, d, s);
    Sections rec;
    sim.advance(p, d, s, t_end, &rec);
    return rec.pts;
}

// The same start advanced to each section's instant in turn by a simulator that takes no sections of its
// own there (phase 0): what the cart is at that t, found without the section machinery.
void check_against_stopped_run(const Params& p, const Drive& d, State s, const std::vector<SectionPoint>& pts) {
    Simulator sim(tight());
    Simulator::make_consistent(p, d, s);
    double worst_x = 0, worst_v = 0;
    for (const SectionPoint& sp : pts) {
        sim.advance(p, d, s, sp.t);
        REQUIRE(s.t == sp.t);
        CAPTURE(sp.n);
        CHECK((s.regime == Regime::Free) == (sp.regime == Regime::Free));
        const bool held = s.regime != Regime::Free;
        worst_x = std::max(worst_x, std::abs((held ? p.xI : s.x) - sp.x));
        worst_v = std::max(worst_v, std::abs((held ? 0.0 : s.v) - sp.v));
    }
    MESSAGE(pts.size() << " sections vs runs stopped there: |dx| <= " << worst_x << " m, |dv| <= " << worst_v << " m/s");
    CHECK(worst_x < 1e-7);
    CHECK(worst_v < 1e-5);
}

// Sections n = 1, 2, ... at the drive's time of phase phi0 + 2 pi (n - 1) (exactly: at that of section_phi,
// which rounds it its own way), and every one up to t_end.
void check_instants(const Drive& d, const std::vector<SectionPoint>& pts, double phi0, double t_end) {
    const auto expected = static_cast<std::size_t>(std::floor((d.phi(t_end) - phi0) / kTwoPi)) + 1;
    REQUIRE(pts.size() == expected);
    Simulator sim;
    sim.set_section_phase(phi0);
    for (std::size_t i = 0; i < pts.size(); ++i) {
        CAPTURE(i);
        CHECK(pts[i].n == static_cast<std::int64_t>(i) + 1);
        CHECK(pts[i].t == d.time_of_phase(sim.section_phi(pts[i].n)));
        CHECK(d.phi(pts[i].t) == doctest::Approx(phi0 + kTwoPi * static_cast<double>(i)).epsilon(1e-13));
    }
}

}  // namespace

TEST_CASE("sections at phi0 are where the cart is at phi = phi0 + 2 pi k: rigid bumper, regimes I, II and III") {
    // xI = 5 mm right of the hilltop: the magnets press the cart on the bumper, the unbalance at 12 rad/s
    // pulls it off once a revolution, and it comes back with impacts (H: each sticks for a few ms).
    Params p = make_version("A1H");
    p.xI = 0.005;
    const Drive d(12.0);
    State start;
    start.x = p.xI;
    const double t_end = 12.0;
    bool any_held = false;
    for (double phi0 : {0.4, 2.0, 3.3, 5.9}) {
        CAPTURE(phi0);
        const auto pts = sections_at(p, d, start, phi0, t_end);
        check_instants(d, pts, phi0, t_end);
        check_against_stopped_run(p, d, start, pts);
        int held = 0;
        for (const auto& sp : pts) held += sp.regime != Regime::Free;
        MESSAGE("phi0 = " << phi0 << ": " << held << " of " << pts.size() << " sections held at the bumper");
        any_held = any_held || held > 0;
        for (const auto& sp : pts)
            if (sp.regime != Regime::Free) {
                CHECK(sp.x == p.xI);
                CHECK(sp.v == 0.0);
            }
    }
    CHECK(any_held);
    // At phi0 = 0.4 the first section is still in the contact the run starts in (it lifts after phi ~ pi).
    const auto first = sections_at(p, d, start, 0.4, 1.0);
    REQUIRE(!first.empty());
    CHECK(first[0].regime == Regime::Contact);
}

TEST_CASE("a section taken during a sticking impact (regime II) at a chosen phase") {
    // A linear oscillator (omega0 = 10 rad/s) from x = -A at rest hits the bumper at 0 after a quarter period
    // and sticks there for T_imp: phi0 puts section 1 2 ms into it.
    const Params p = harmonic("A1H");
    const double omega = 7.0, t_hit = kPi / 20.0;
    const double phi0 = omega * (t_hit + 2e-3);
    const Drive d(omega);
    State start;
    start.x = -0.01;
    const auto pts = sections_at(p, d, start, phi0, 3.0);
    check_instants(d, pts, phi0, 3.0);
    REQUIRE(!pts.empty());
    CHECK(pts[0].regime == Regime::Sticking);
    CHECK(pts[0].x == 0.0);
    CHECK(pts[0].v == 0.0);
    check_against_stopped_run(p, d, start, pts);
}

TEST_CASE("sections at phi0 under piecewise-linear drives: the EF ramp and a ramp with a plateau") {
    const Params p = make_version("A1G");
    const double phi0 = 2.5;
    {
        const Drive d = Drive::ef_ramp(25.1, 60.0);
        const auto pts = sections_at(p, d, State{}, phi0, 60.0);
        check_instants(d, pts, phi0, 60.0);   // phi(60) = 753 rad: 120 sections from 2.5 rad on
        CHECK(pts.size() == 120);
        // The states over the first 20 s (omega < 8.4 rad/s, the left well): beyond, the chaos of the ramp
        // makes the stopped run's other step sequence grow into millimetres.
        const auto early = sections_at(p, d, State{}, phi0, 20.0);
        check_instants(d, early, phi0, 20.0);
        check_against_stopped_run(p, d, State{}, early);
    }
    {
        // A knot between two sections and a section right on the second knot's phase.
        const Drive base = Drive::piecewise_linear({0.0, 4.0, 9.0}, {6.0, 10.0, 10.0});
        const double phi_knot = base.phi(9.0);
        const double phi0_knot = phi_knot - kTwoPi * std::floor(phi_knot / kTwoPi);
        for (double ph : {phi0, phi0_knot}) {
            CAPTURE(ph);
            State start;
            start.x = -0.011;
            const auto pts = sections_at(p, base, start, ph, 14.0);
            check_instants(base, pts, ph, 14.0);
            check_against_stopped_run(p, base, start, pts);
        }
    }
}

TEST_CASE("phi0 = 0 and 2 pi are the stroboscopic section phi = 2 pi n, bit for bit") {
    Params p = make_version("A1H");
    p.xI = 0.005;
    const Drive d = Drive::piecewise_linear({0.0, 5.0}, {4.0, 13.0});
    State start;
    start.x = -0.011;
    State s_def = start;
    Simulator def(tight());
    Simulator::make_consistent(p, d, s_def);
    Sections r_def;
    def.advance(p, d, s_def, 20.0, &r_def);
    REQUIRE(r_def.pts.size() > 20);
    for (const auto& sp : r_def.pts) CHECK(sp.t == d.time_of_phase(kTwoPi * static_cast<double>(sp.n)));
    for (double phi0 : {0.0, kTwoPi}) {
        CAPTURE(phi0);
        const auto pts = sections_at(p, d, start, phi0, 20.0);
        REQUIRE(pts.size() == r_def.pts.size());
        bool same = true;
        for (std::size_t i = 0; i < pts.size(); ++i)
            same = same && pts[i].n == r_def.pts[i].n && pts[i].t == r_def.pts[i].t && pts[i].x == r_def.pts[i].x &&
                   pts[i].v == r_def.pts[i].v && pts[i].regime == r_def.pts[i].regime;
        CHECK(same);
    }
    Simulator sim;
    CHECK(sim.section_phase() == 0.0);
    CHECK(sim.section_phi(7) == 7 * kTwoPi);
}

TEST_CASE("section phase: the range is checked; n counts revolutions; the next section's time") {
    Simulator sim;
    for (double bad : {-0.1, 6.3, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
        CHECK_THROWS_AS(sim.set_section_phase(bad), std::invalid_argument);
    CHECK(sim.section_phase() == 0.0);
    sim.set_section_phase(1.0);
    CHECK(sim.section_phase() == 1.0);
    CHECK(sim.section_phi(1) == doctest::Approx(1.0).epsilon(1e-15));
    CHECK(sim.section_phi(3) == doctest::Approx(2 * kTwoPi + 1.0).epsilon(1e-15));
    // At phi = 4.5 (revolution 1) the section at 1 rad has passed, the one at 5 rad has not.
    const Drive d(9.0);
    State s;
    s.t = 0.5;
    Simulator::sync_sections(d, s);
    CHECK(sim.next_section_time(d, s) == doctest::Approx(d.time_of_phase(kTwoPi + 1.0)).epsilon(1e-15));
    sim.set_section_phase(5.0);
    CHECK(sim.next_section_time(d, s) == doctest::Approx(d.time_of_phase(5.0)).epsilon(1e-15));
    // Started exactly on a section (the GUI's clicker restarts there): that one is not reported again.
    const Params p = make_version("A1H");
    const Drive on(9.0, 2.0, kTwoPi * 3 + 5.0);
    State at;
    at.t = 2.0;
    at.x = -0.011;
    Simulator::make_consistent(p, on, at);
    Sections rec;
    sim.advance(p, on, at, 2.0 + 2 * kTwoPi / 9.0, &rec);
    REQUIRE(rec.pts.size() == 2);
    CHECK(rec.pts[0].n == 5);
    CHECK(rec.pts[0].t == on.time_of_phase(kTwoPi * 4 + 5.0));
}

TEST_CASE("poincare_section at phi0: n after the transient, the instants, the state left at the last point") {
    const Params p = make_version("A1H");
    State a, b;
    a.x = b.x = -0.011;
    a.t = b.t = 3.0;
    const double omega = 9.0, phi0 = 1.7;
    const auto pts = poincare_section(p, omega, 12, 5, a, {}, nullptr, phi0);
    REQUIRE(pts.size() == 12);
    for (std::size_t i = 0; i < pts.size(); ++i) {
        CHECK(pts[i].n == static_cast<std::int64_t>(i) + 6);
        CHECK(pts[i].t == doctest::Approx(3.0 + (phi0 + 2 * kPi * static_cast<double>(pts[i].n - 1)) / omega).epsilon(1e-14));
    }
    CHECK(a.t == pts.back().t);
    CHECK(pts.back().x == a.x);
    // The default is phi0 = 0, and differs from it (the section of a period-1 orbit moves with the phase).
    const auto zero = poincare_section(p, omega, 12, 5, b);
    State c;
    c.x = -0.011;
    c.t = 3.0;
    const auto zero_explicit = poincare_section(p, omega, 12, 5, c, {}, nullptr, 0.0);
    REQUIRE(zero.size() == 12);
    REQUIRE(zero_explicit.size() == 12);
    CHECK(zero.back().x == zero_explicit.back().x);
    CHECK(zero.back().t == zero_explicit.back().t);
    CHECK(std::abs(zero.back().x - pts.back().x) > 1e-4);
    State d;
    CHECK_THROWS_AS(poincare_section(p, omega, 1, 0, d, {}, nullptr, -1.0), std::invalid_argument);
}

TEST_CASE("a phase changed mid-run with sync_sections: the running revolution's new section is not lost") {
    const Params p = make_version("A1H");
    const Drive d(9.0);
    Simulator sim;
    sim.set_section_phase(1.0);
    State s;
    s.x = -0.011;
    Simulator::make_consistent(p, d, s);
    Sections rec;
    sim.advance(p, d, s, 3.0, &rec);   // phi(3) = 27 rad: the section at 1 + 8 pi = 26.1 rad was taken
    REQUIRE(rec.pts.size() == 5);
    sim.set_section_phase(4.0);
    Simulator::sync_sections(d, s);
    rec.pts.clear();
    sim.advance(p, d, s, 6.0, &rec);   // 4 + 8 pi = 29.1 rad, in the revolution running at the change, then 3 more
    REQUIRE(rec.pts.size() == 4);
    CHECK(rec.pts[0].n == 5);
    CHECK(rec.pts[0].t == d.time_of_phase(sim.section_phi(5)));
    CHECK(d.phi(rec.pts[0].t) == doctest::Approx(4.0 + 8 * kPi).epsilon(1e-14));
}
