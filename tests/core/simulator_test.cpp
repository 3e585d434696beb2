// The hybrid simulator in free flight: energy conservation and the energy balance with damping, event times
// against closed forms, Poincare section instants, consistency of a state, the uniform sampler.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <numbers>
#include <vector>

#include "impactlab/drive.hpp"
#include "impactlab/forces.hpp"
#include "impactlab/params.hpp"
#include "impactlab/simulator.hpp"
#include "coasting.hpp"

using namespace impactlab;
using impactlab::testing::harmonic;

namespace {

constexpr double kPi = std::numbers::pi;

// Records everything the simulator reports.
struct Recorder : Observer {
    std::vector<SectionPoint> sections;
    std::vector<ImpactEvent> impacts;
    struct Change { double t; Regime from, to; };
    std::vector<Change> changes;
    std::vector<Piece> pieces;   // t0, t1, regime only (the step pointer is not kept)
    void on_piece(const Piece& p) override { pieces.push_back({p.t0, p.t1, p.regime, nullptr, p.x_hold}); }
    void on_section(const SectionPoint& sp) override { sections.push_back(sp); }
    void on_impact(const ImpactEvent& e) override { impacts.push_back(e); }
    void on_regime(double t, Regime from, Regime to) override { changes.push_back({t, from, to}); }
};

// Integral of f(t, x, v) along the trajectory, by 8-point Gauss-Legendre on each piece's dense output
// (each piece cut into `sub` parts).
template <class F>
struct PathIntegral : Observer {
    F f;
    int sub;
    double value = 0;
    PathIntegral(F fn, int subdivisions) : f(fn), sub(subdivisions) {}
    void on_piece(const Piece& piece) override {
        static constexpr double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
        static constexpr double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
        const double len = (piece.t1 - piece.t0) / sub;
        for (int s = 0; s < sub; ++s) {
            const double mid = piece.t0 + (s + 0.5) * len, half = 0.5 * len;
            for (int i = 0; i < 4; ++i)
                for (double sign : {-1.0, 1.0}) {
                    const double t = mid + sign * half * x[i];
                    const Vec2 y = piece.at(t);
                    value += w[i] * half * f(t, y[0], y[1]);
                }
        }
    }
};

Tolerances tight(double rtol) {
    Tolerances t;
    t.rtol = rtol;   // only rtol: the absolute parts follow it (rosenbrock.hpp)
    return t;
}

// A1 stiffness with the forcing and the resistance off and the (rigid) bumper out of reach.
Params conservative_a1(const char* version = "A1H") {
    Params p = make_version(version);
    p.c = 0;
    p.T = 0;
    p.m0e = 0;
    p.xI = 0.05;
    return p;
}

}  // namespace

namespace {
struct ConservativeRun { double worst_rel_error, xmin, xmax; std::uint64_t steps; };

// 20 s of a conservative run from x = -0.02 m at rest: above the hilltop's energy, so the cart swings over
// both wells (|x| < 0.05 m, clear of the bumper). Checks the run itself; returns the worst |E - E0|/E0.
ConservativeRun conservative_run(const Params& p, double rtol) {
    const Drive drive(5.0);
    Simulator sim(tight(rtol));
    State s;
    s.x = -0.02;
    Simulator::make_consistent(p, drive, s);
    const double E0 = mechanical_energy(p, s.x, s.v);
    REQUIRE(E0 > 0);   // above the hilltop (V(0) = 0)
    ConservativeRun r{0, 0, 0, 0};
    Recorder rec;
    for (int i = 1; i <= 200; ++i) {
        sim.advance(p, drive, s, 0.1 * i, &rec);
        r.worst_rel_error = std::max(r.worst_rel_error, std::abs(mechanical_energy(p, s.x, s.v) - E0) / E0);
        r.xmax = std::max(r.xmax, s.x);
        r.xmin = std::min(r.xmin, s.x);
    }
    r.steps = s.steps;
    CHECK(s.t == 20.0);
    CHECK(s.impacts == 0);
    CHECK(rec.impacts.empty());
    // Every piece is free flight and the pieces tile [0, 20].
    REQUIRE(!rec.pieces.empty());
    CHECK(rec.pieces.front().t0 == 0.0);
    CHECK(rec.pieces.back().t1 == 20.0);
    bool tiled = true, free = true;
    for (std::size_t i = 1; i < rec.pieces.size(); ++i) tiled &= rec.pieces[i].t0 == rec.pieces[i - 1].t1;
    for (const auto& pc : rec.pieces) free &= pc.regime == Regime::Free;
    CHECK(tiled);
    CHECK(free);
    return r;
}
}  // namespace

TEST_CASE("free, undamped, unforced run across both wells conserves the mechanical energy") {
    for (const std::string version : {"A1H", "A1G", "A3G", "A1C"}) {
        Params p = conservative_a1(version.c_str());
        if (version == "A3G") {   // A3's stiffness, the same switches off
            const Params a3 = make_version("A3G");
            p.k = a3.k;
            p.a = a3.a;
            p.b = a3.b;
        }
        CAPTURE(version);
        const ConservativeRun r = conservative_run(p, 1e-12);
        MESSAGE(version << ": conservative run over 20 s at rtol 1e-12, " << r.steps
                        << " steps, worst relative energy error " << r.worst_rel_error << ", x in [" << r.xmin
                        << ", " << r.xmax << "]");
        CHECK(r.worst_rel_error < 1e-9);
        CHECK(r.xmax > 0.019);   // really crossed to the right well and back
        CHECK(r.xmin < -0.019);
    }
    // The energy error is the integrator's: it shrinks in proportion to rtol.
    const ConservativeRun coarse = conservative_run(conservative_a1("A1H"), 1e-10);
    const ConservativeRun fine = conservative_run(conservative_a1("A1H"), 1e-12);
    MESSAGE("energy error at rtol 1e-10: " << coarse.worst_rel_error << ", at 1e-12: " << fine.worst_rel_error);
    CHECK(fine.worst_rel_error < coarse.worst_rel_error / 20);
}

TEST_CASE("damped run: the energy lost equals the work of the bearing resistance") {
    // A1 with its own c and T (dry friction included), forcing off, bumper out of reach.
    Params p = make_version("A1H");
    p.m0e = 0;
    p.xI = 0.05;
    const Drive drive(5.0);
    auto power = [&p](double, double, double v) { return resistance(p, v).F * v; };
    PathIntegral<decltype(power)> dissipated(power, 4);
    Simulator sim(tight(1e-10));
    State s;
    s.x = -0.025;
    s.v = 0.3;
    Simulator::make_consistent(p, drive, s);
    const double E0 = mechanical_energy(p, s.x, s.v);
    sim.advance(p, drive, s, 20.0, &dissipated);
    const double E1 = mechanical_energy(p, s.x, s.v);
    const double lost = E0 - E1;
    MESSAGE("damped run: energy lost " << lost << " J, work of F_R " << dissipated.value << " J, difference "
                                       << lost - dissipated.value << " J");
    CHECK(lost > 0.1 * E0);   // the resistance did take a good share
    CHECK(dissipated.value == doctest::Approx(lost).epsilon(1e-7).scale(0));
    CHECK(std::abs(s.v) < 1e-3);   // settled in a well by t = 20 s
}

TEST_CASE("event time of a rigid impact matches the closed form to 1e-9 s (harmonic oscillator)") {
    // m = 1, k = 100: from x = -A at rest the cart reaches xI = 0 at pi/(2 omega0) with v- = A omega0; with
    // springs only it then comes back to xI after half a period of free flight.
    const double A = 0.01, w0 = 10.0;
    for (const std::string version : {"A1H", "A1G"}) {
        const Params p = harmonic(version.c_str());
        const Drive drive(3.0);
        Simulator sim(tight(1e-10));
        State s;
        s.x = -A;
        Simulator::make_consistent(p, drive, s);
        Recorder rec;
        sim.advance(p, drive, s, 0.5, &rec);
        CAPTURE(version);
        REQUIRE(rec.impacts.size() >= 2);
        const double t1 = kPi / (2 * w0);
        const auto& e1 = rec.impacts[0];
        MESSAGE(version << ": first impact at " << e1.t << " s, error " << e1.t - t1 << " s; v- error "
                        << e1.v_minus - A * w0 << " m/s");
        CHECK(std::abs(e1.t - t1) < 1e-9);
        CHECK(std::abs(e1.v_minus - A * w0) < 1e-9);
        // After the release (T_imp later, with v+) a half period of free flight brings it back at |v+|.
        const double t_rel = t1 + e1.duration;
        const double t2 = t_rel + kPi / w0;
        const auto& e2 = rec.impacts[1];
        MESSAGE(version << ": second impact error " << e2.t - t2 << " s");
        CHECK(std::abs(e2.t - t2) < 1e-9);
        CHECK(e2.v_minus == doctest::Approx(-e1.v_plus).epsilon(1e-8));
    }
}

TEST_CASE("Poincare sections land exactly on drive.time_of_phase(2 pi n), held ones at (xI, 0)") {
    const double A = 0.01, w0 = 10.0;
    const Params p = harmonic("A1H");
    // Choose omega so that section 1 falls 2 ms into the sticking phase of the first impact.
    const double t_imp = kPi / (2 * w0);
    const double omega = 2 * kPi / (t_imp + 2e-3);
    const Drive drive(omega, 0.0, 0.0);
    Simulator sim(tight(1e-10));
    State s;
    s.x = -A;
    Simulator::make_consistent(p, drive, s);
    Recorder rec;
    sim.advance(p, drive, s, 2.0, &rec);
    REQUIRE(rec.sections.size() >= 10);
    for (std::size_t i = 0; i < rec.sections.size(); ++i) {
        const auto& sp = rec.sections[i];
        CAPTURE(i);
        CHECK(sp.n == static_cast<std::int64_t>(i) + 1);
        CHECK(sp.t == drive.time_of_phase(2 * kPi * static_cast<double>(sp.n)));   // exactly
    }
    // Section 1 is inside regime II: (xI, 0).
    REQUIRE(!rec.impacts.empty());
    CHECK(rec.impacts[0].t < rec.sections[0].t);
    CHECK(rec.sections[0].t < rec.impacts[0].t + rec.impacts[0].duration);
    CHECK(rec.sections[0].regime == Regime::Sticking);
    CHECK(rec.sections[0].x == p.xI);
    CHECK(rec.sections[0].v == 0.0);

    // Free flight sections against the closed form of a linear oscillator without a bumper.
    const Params free = harmonic("A1H", 0.05);
    const Drive d2(7.0, 0.0, 0.0);
    State f;
    f.x = -A;
    Simulator::make_consistent(free, d2, f);
    Recorder r2;
    sim.advance(free, d2, f, 10.0, &r2);
    REQUIRE(r2.sections.size() == 11);   // 10 s at 7 rad/s: 11.1 revolutions
    double worst = 0;
    for (const auto& sp : r2.sections) {
        CHECK(sp.t == d2.time_of_phase(2 * kPi * static_cast<double>(sp.n)));
        CHECK(sp.regime == Regime::Free);
        worst = std::max(worst, std::abs(sp.x - (-A * std::cos(w0 * sp.t))));
        CHECK(sp.v == doctest::Approx(A * w0 * std::sin(w0 * sp.t)).epsilon(1e-7).scale(1e-3));
    }
    MESSAGE("harmonic oscillator: worst section x error " << worst << " m over 10 s");
    CHECK(worst < 1e-9);
}

TEST_CASE("sections with a ramped drive follow the drive's own phase") {
    Params p = make_version("A1G");
    const Drive drive = Drive::ef_ramp(25.1, 60.0);
    Simulator sim;
    State s;
    Simulator::make_consistent(p, drive, s);
    Recorder rec;
    sim.advance(p, drive, s, 60.0, &rec);
    // phi(60) = 25.1 * 60 / 2 = 753 rad: 119 full revolutions.
    REQUIRE(rec.sections.size() == 119);
    for (const auto& sp : rec.sections) CHECK(sp.t == drive.time_of_phase(2 * kPi * static_cast<double>(sp.n)));
}

TEST_CASE("make_consistent: a rigid bumper never has the cart beyond it") {
    const Params p = make_version("A1H");   // xI = 0
    const Drive pressing(10.0, 0.0, 0.5 * kPi);   // N = m0e w^2 > 0 at t = 0
    const Drive pulling(10.0, 0.0, 1.5 * kPi);    // N < 0 at t = 0
    State s;
    s.x = 0.004;
    s.v = 0.2;
    Simulator::make_consistent(p, pressing, s);
    CHECK(s.x == p.xI);
    CHECK(s.v == 0.0);
    CHECK(s.regime == Regime::Contact);
    State q;
    q.x = 0.004;
    Simulator::make_consistent(p, pulling, q);
    CHECK(q.x == p.xI);
    CHECK(q.regime == Regime::Free);
    // At rest exactly on the bumper: III if pressed, I if not (MODEL.md).
    State r;
    Simulator::make_consistent(p, pressing, r);
    CHECK(r.regime == Regime::Contact);
    State u;
    Simulator::make_consistent(p, pulling, u);
    CHECK(u.regime == Regime::Free);
    // Left of the bumper: untouched.
    State l;
    l.x = -0.003;
    l.v = 0.1;
    Simulator::make_consistent(p, pressing, l);
    CHECK(l.x == -0.003);
    CHECK(l.v == 0.1);
    CHECK(l.regime == Regime::Free);
    // Compliant models only know regime I, even beyond xI.
    State c;
    c.x = 1e-5;
    c.regime = Regime::Contact;
    Simulator::make_consistent(make_version("A1C"), pressing, c);
    CHECK(c.regime == Regime::Free);
    CHECK(c.x == 1e-5);
    // The next section is the first after t.
    State t;
    t.t = 1.0;
    t.x = -0.01;
    const Drive d(2 * kPi, 0.0, 0.0);   // one revolution a second: phi(1) = 2 pi exactly
    Simulator::make_consistent(p, d, t);
    CHECK(t.next_section == 2);
}

TEST_CASE("UniformSampler: one sample every dt from t_first, matching the state at that time") {
    Params p = make_version("A1H");
    p.xI = 0.05;
    const Drive drive(9.0);
    Simulator sim;
    State s;
    s.x = -0.011;
    Simulator::make_consistent(p, drive, s);
    std::vector<Sample> samples;
    UniformSampler sampler(drive, 0.01, 0.0, [&](const Sample& smp) { samples.push_back(smp); });
    sim.advance(p, drive, s, 1.0, &sampler);
    REQUIRE(samples.size() == 101);
    for (std::size_t i = 0; i < samples.size(); ++i) {
        CHECK(samples[i].t == doctest::Approx(0.01 * static_cast<double>(i)).epsilon(1e-12));
        CHECK(samples[i].phi == doctest::Approx(9.0 * samples[i].t).epsilon(1e-12));
        CHECK(samples[i].omega == 9.0);
    }
    CHECK(samples.front().x == -0.011);
    CHECK(samples.back().x == doctest::Approx(s.x).epsilon(1e-9));
    CHECK(samples.back().v == doctest::Approx(s.v).epsilon(1e-9).scale(1e-6));
    // Against a second run that stops exactly at 0.5 s.
    Simulator sim2;
    State s2;
    s2.x = -0.011;
    Simulator::make_consistent(p, drive, s2);
    sim2.advance(p, drive, s2, 0.5);
    CHECK(samples[50].x == doctest::Approx(s2.x).epsilon(1e-7));
}

TEST_CASE("normal force, bumper force and force terms") {
    Params p = make_version("A1H");
    p.xI = 0.005;
    const double FSA = spring_magnet(p, p.xI).F;   // negative: the magnets push the cart onto the bumper
    REQUIRE(FSA < 0);
    const Drive drive(12.0, 0.0, 0.0);
    for (double t : {0.0, 0.1, 0.37, 1.0}) {
        const double expect = p.m0e * 144.0 * std::sin(12.0 * t) - FSA;
        CHECK(normal_force(p, drive, t) == doctest::Approx(expect).epsilon(1e-13));
    }
    add_effect(p, "constant_force").p[0] = 0.5;
    CHECK(normal_force(p, drive, 0.0) == doctest::Approx(-FSA + 0.5).epsilon(1e-13));
    const ForceTerms f = force_terms(p, 0.0, -0.01, 0.2, 1.0, 12.0, 0.0);
    CHECK(f.resistance == doctest::Approx(resistance(p, 0.2).F).epsilon(1e-15));
    CHECK(f.spring_magnet == doctest::Approx(spring_magnet(p, -0.01).F).epsilon(1e-15));
    CHECK(f.impact == 0.0);
    CHECK(f.unbalance == doctest::Approx(p.m0e * 144.0 * std::sin(1.0)).epsilon(1e-15));
    CHECK(f.effects == 0.5);
    CHECK(f.net() == doctest::Approx(f.unbalance + 0.5 - f.resistance - f.spring_magnet).epsilon(1e-15));

    // Bumper force: regime III gives N, regime II the mean force of the impulse, free flight 0.
    State s;
    s.x = p.xI;
    s.regime = Regime::Contact;
    CHECK(bumper_force(p, drive, s) == doctest::Approx(normal_force(p, drive, 0.0)).epsilon(1e-15));
    s.regime = Regime::Sticking;
    s.v_impact = 0.4;
    s.v_release = -0.2;
    const double T = (6.2193e-3 - 4.0689e-3) * std::exp(-2.1733 * 0.4) + 4.0689e-3;
    CHECK(bumper_force(p, drive, s) == doctest::Approx(p.m * 0.6 / T).epsilon(1e-12));
    s.regime = Regime::Free;
    CHECK(bumper_force(p, drive, s) == 0.0);
    // Compliant: the Hunt-Crossley force (elastic part only at rest).
    const Params c = make_version("A1C");
    State in;
    in.x = 1e-5;
    CHECK(bumper_force(c, drive, in) == doctest::Approx(2.3983e8 * std::pow(1e-5, 1.5)).epsilon(1e-12));
    CHECK(mechanical_energy(c, 1e-5, 0.0) ==
          doctest::Approx(spring_magnet_potential(c, 1e-5) + 2.3983e8 * std::pow(1e-5, 2.5) / 2.5).epsilon(1e-12));
}

TEST_CASE("an effect's force enters the equation of motion: a constant force shifts the rest position") {
    // Damped linear oscillator (m = 1, k = 100, c = 4) pulled by a constant 0.5 N: rests at F0/k = 5 mm.
    Params p = harmonic("A1H", 0.05);
    p.c = 4.0;
    add_effect(p, "constant_force").p[0] = 0.5;
    const Drive drive(1.0);
    Simulator sim(tight(1e-10));
    State s;
    Simulator::make_consistent(p, drive, s);
    sim.advance(p, drive, s, 20.0);
    CHECK(s.x == doctest::Approx(0.005).epsilon(1e-8));
    CHECK(std::abs(s.v) < 1e-9);
    // The same run with F0 = 0 stays at rest at x = 0.
    p.effects[0].p[0] = 0.0;
    State z;
    Simulator::make_consistent(p, drive, z);
    sim.advance(p, drive, z, 1.0);
    CHECK(z.x == 0.0);
}

// MODEL.md: "An implicit method whose Newton matrix uses that exact slope crawls when the cart rests on a
// compliant bumper; a secant slope F/h' (or a bounded one) keeps the model unchanged and the steps long."
// hunt_crossley.cpp puts the secant slope in the Newton matrix.
TEST_CASE("a cart pressed on a compliant bumper settles near the static penetration, in few steps") {
    // A1C/A1C1 with xI = 5 mm and no forcing: the magnets press the cart on the bumper with about
    // -F_SA(xI) = 2.28 N, so it comes to rest where kI h^1.5 = -F_SA(xI + h). The Hunt-Crossley damping
    // b |h'|^n3 (n3 ~ 0.19) makes the last approach a slow creep: after 10 s h is within a few % of that.
    for (const std::string version : {"A1C", "A1C1"}) {
        Params p = make_version(version);
        p.m0e = 0;
        p.xI = 0.005;
        const double kI = impact_param(p, "kI");
        const Drive drive(1.0);
        Simulator sim;
        State s;
        s.x = 0.004;   // 1 mm off the bumper, at rest: pulled on by the magnets
        Simulator::make_consistent(p, drive, s);
        // Bounded work: at most 200000 steps (1e5 per simulated second would already be a crawl).
        struct Budget : Observer {
            std::uint64_t pieces = 0;
            void on_piece(const Piece&) override { ++pieces; }
            bool stop() const override { return pieces >= 200000; }
        } budget;
        sim.advance(p, drive, s, 10.0, &budget);
        // The rest position, by bisection on the static balance.
        double a = 0, b = 1e-3;
        for (int i = 0; i < 200; ++i) {
            const double h = 0.5 * (a + b);
            (kI * std::pow(h, 1.5) + spring_magnet(p, p.xI + h).F < 0 ? a : b) = h;
        }
        const double h_rest = 0.5 * (a + b);
        CAPTURE(version);
        MESSAGE(version << ": at t = " << s.t << " s, h = " << s.x - p.xI << " m (static " << h_rest << " m) after "
                        << s.steps << " steps, " << s.rejected << " rejected");
        CHECK(s.t == 10.0);   // reached the end within the step budget
        CHECK(s.x - p.xI == doctest::Approx(h_rest).epsilon(0.05).scale(0));
        CHECK(std::abs(s.v) < 1e-6);
        CHECK(s.steps < 100000);
    }
}

TEST_CASE("move_bumper: a bumper moved onto the cart pushes it back to the contact point; a sticking ends") {
    for (const char* name : {"A1C", "A1H", "A1G"}) {
        CAPTURE(name);
        Params p = make_version(name);
        const Drive d(18.0);
        State s;
        s.x = -0.004;   // the bumper moves from 0 to -6 mm: it lands on the cart
        s.v = 0.05;
        Simulator::make_consistent(p, d, s);
        Simulator::move_bumper(p, d, s, -0.006);
        CHECK(p.xI == -0.006);
        CHECK(s.x == doctest::Approx(-0.006));
        CHECK(s.x <= p.xI);
        CHECK(s.v == 0.0);
        if (!p.rigid()) CHECK(s.regime == Regime::Free);
        // And the simulation goes on from there without the cart ever passing a rigid bumper.
        Simulator sim;
        double x_max = -1;
        UniformSampler sampler(d, 1e-3, s.t, [&](const Sample& smp) { x_max = std::max(x_max, smp.x); });
        sim.advance(p, d, s, s.t + 1.0, &sampler);
        if (p.rigid()) CHECK(x_max <= p.xI + 1e-12);
    }
    // A sticking in progress ends when the bumper moves away: the cart is left free where it was.
    Params p = make_version("A1H");
    const Drive d(18.0);
    State s;
    s.regime = Regime::Sticking;
    s.t_release = 0.01;
    Simulator::move_bumper(p, d, s, 0.003);
    CHECK(s.regime == Regime::Free);
    CHECK(s.x == 0.0);
    CHECK(s.v == 0.0);
}

TEST_CASE("move_bumper: a compliant bumper the cart presses keeps its depth; a move by nothing changes nothing") {
    // GUI resending the slider's value pulled a pressed cart out of the bumper, a jump
    // of the penetration every frame.
    Params p = make_version("A1C");
    p.xI = -0.015;   // the magnets press the cart (left well at -10.9 mm) onto it
    const Drive d(9.0);
    State s;
    s.x = -0.0149;
    Simulator::make_consistent(p, d, s);
    Simulator().advance(p, d, s, 2.0);
    const double h = s.x - p.xI;
    REQUIRE(h > 1e-7);   // pressed some micrometres deep
    const State before = s;
    Simulator::move_bumper(p, d, s, p.xI);
    CHECK(s.x == before.x);
    CHECK(s.v == before.v);
    Simulator::move_bumper(p, d, s, p.xI - 0.001);   // 1 mm towards the cart: it goes along, as deep as it was
    CHECK(s.x == doctest::Approx(before.x - 0.001).epsilon(1e-12));
    CHECK(s.x - p.xI == doctest::Approx(h).epsilon(1e-9));
    Simulator::move_bumper(p, d, s, p.xI + 0.002);   // away: the cart is left where it is
    CHECK(s.x == doctest::Approx(before.x - 0.001).epsilon(1e-12));
}

TEST_CASE("budgets: a stalled run ends in SimulationStalled naming the regime, t and the step size") {
    // Parameters no validation would pass (eps = 1e-300; m = 1e-20 on a compliant bumper): before the budget the
    // step loop spun forever at h_min.
    for (const int which : {1, 2, 3}) {
        Params p = make_version(which < 2 ? "A1H" : "A1C");
        if (which % 2 == 0) p.m = 1e-20;
        else p.eps = 1e-300;
        const Drive drive(10.0);
        Simulator sim;
        State s;
        s.x = 0.001;
        Simulator::make_consistent(p, drive, s);
        std::string msg;
        try {
            sim.advance(p, drive, s, 10.0);
        } catch (const SimulationStalled& e) {
            msg = e.what();
        }
        CAPTURE(which);
        CAPTURE(s.t);
        CAPTURE(s.steps);
        CAPTURE(msg);
        CHECK(msg.find("stalled in regime I (free flight)") != std::string::npos);
        CHECK(msg.find("at t = ") != std::string::npos);
        CHECK(msg.find("step size") != std::string::npos);
        CHECK(s.steps + s.rejected < 4 * kStallWindow);   // caught within two windows
    }
    // The same check on a legal run with a budget it cannot meet: the budget is what throws.
    const Params p = make_version("A1C");
    Tolerances tight_budget;
    tight_budget.max_step_rate = 10.0;
    Simulator sim(tight_budget);
    State s;
    CHECK_THROWS_AS(sim.advance(p, Drive(10.0), s, 1e5), SimulationStalled);
    // A wall-clock budget ends a long run the same way.
    Tolerances wall;
    wall.max_wall_s = 0.05;
    Simulator slow(wall);
    State w;
    CHECK_THROWS_WITH_AS(slow.advance(p, Drive(10.0), w, 1e7), doctest::Contains("wall-clock budget"), SimulationStalled);
}

namespace {
// The state one forcing period on from y0, at constant omega, with the Simulator at rtol.
Vec2 one_period(const Params& p, double omega, const Vec2& y0, double rtol) {
    Tolerances tol;
    tol.rtol = rtol;
    const Drive d(omega, 0.0, 0.0);
    State s;
    s.x = y0[0];
    s.v = y0[1];
    Simulator::make_consistent(p, d, s);
    Simulator(tol).advance(p, d, s, 2.0 * kPi / omega);
    return Vec2(s.x, s.v);
}
}   // namespace

TEST_CASE("dry-friction reversals: no step straddles one unseen, at any rtol") {
    // The friction flips from -T to +T within eps/|a| (about 1 us); an explicit step across it could pass its
    // error estimate with the kink between its stages. A1H at 13.645 rad/s from this state: one step from
    // v = -3.0e-5 to +4.1e-6 m/s put 2.2e-6 m/s into v at rtol 1e-10, while rtol 1e-9 was 6e-10 off.
    const Params p = make_version("A1H");
    const double omega = 13.645037963302023;
    const Vec2 y0(-0.0072949626435705054, -0.075052461845185686);
    const Vec2 ref = one_period(p, omega, y0, 1e-13);
    for (double rtol : {1e-8, 1e-9, 1e-10, 1e-11, 1e-12}) {
        CAPTURE(rtol);
        const Vec2 y = one_period(p, omega, y0, rtol);
        CHECK(std::abs(y[1] - ref[1]) < 1e3 * rtol * 0.1);   // within a thousand times rtol of v's scale
        CHECK(std::abs(y[0] - ref[0]) < 1e3 * rtol * 0.01);
    }
    // And as a rate: 200 random starts each of A1G and A1C over 6..24 rad/s, one forcing period at rtol 1e-10
    // against 1e-13 (scaled); without the cut A1C's largest was 1.9e-7.
    std::uint64_t state = 12345;
    auto uniform = [&] {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return static_cast<double>(state >> 11) * 0x1.0p-53;
    };
    for (const char* name : {"A1G", "A1C"}) {
        CAPTURE(name);
        const Params q = make_version(name);
        double worst = 0;
        for (int i = 0; i < 200; ++i) {
            const double w = 6.0 + 18.0 * uniform(), x = -0.02 + 0.03 * uniform(), v = 0.3 * (uniform() - 0.5);
            const Vec2 e = one_period(q, w, Vec2(x, v), 1e-10) - one_period(q, w, Vec2(x, v), 1e-13);
            worst = std::max(worst, Vec2(e[0] / 0.01, e[1] / 0.1).norm());
        }
        MESSAGE(std::string(name) << ": largest one-period error at rtol 1e-10 (scaled) " << worst);
        CHECK(worst < 1e-7);
    }
}
