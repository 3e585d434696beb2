// Impacts: the rigid laws G and H (restitution kappa(v-), sticking for T_imp(v-), permanent contact while
// N > 0, chattering), and the compliant Hunt-Crossley bumper (C, C1) against the Hertz contact solution.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include "impactlab/drive.hpp"
#include "impactlab/forces.hpp"
#include "impactlab/params.hpp"
#include "impactlab/simulator.hpp"
#include "coasting.hpp"

using namespace impactlab;
using impactlab::testing::coasting;

namespace {

constexpr double kPi = std::numbers::pi;

struct Recorder : Observer {
    std::vector<ImpactEvent> impacts;
    std::vector<SectionPoint> sections;
    void on_section(const SectionPoint& sp) override { sections.push_back(sp); }
    struct Change { double t; Regime from, to; };
    std::vector<Change> changes;
    struct Span { double t0, t1; Regime regime; double x_hold; };
    std::vector<Span> pieces;
    std::uint64_t stop_after_changes_to_contact = 0;   // 0: never stop
    std::uint64_t contact_entries = 0;
    void on_piece(const Piece& p) override { pieces.push_back({p.t0, p.t1, p.regime, p.x_hold}); }
    void on_impact(const ImpactEvent& e) override { impacts.push_back(e); }
    void on_regime(double t, Regime from, Regime to) override {
        changes.push_back({t, from, to});
        if (to == Regime::Contact) ++contact_entries;
    }
    bool stop() const override {
        return stop_after_changes_to_contact && contact_entries >= stop_after_changes_to_contact;
    }
};

Tolerances tight(double rtol) {
    Tolerances t;
    t.rtol = rtol;
    return t;
}

// MODEL.md's rigid laws, written out here from its table (not read from the registry).
struct RigidLaw { double k0, k1, ak, Ti0, Ti1, aT; };
constexpr RigidLaw kG{0.6242, 0.0, 0.5061, 0.0, 0.0, 0.0};
constexpr RigidLaw kH{0.6150, 0.1350, 0.6594, 6.2193e-3, 4.0689e-3, 2.1733};
double kappa(const RigidLaw& l, double v) { return (l.k0 - l.k1) * std::exp(-l.ak * std::abs(v)) + l.k1; }
double t_imp(const RigidLaw& l, double v) { return (l.Ti0 - l.Ti1) * std::exp(-l.aT * std::abs(v)) + l.Ti1; }

// First root of N(t) after t0 (N(t0) > 0), by a scan and bisection to the last bit.
double first_root_of_normal_force(const Params& p, const Drive& d, double t0) {
    auto N = [&](double t) { return normal_force(p, d, t); };
    REQUIRE(N(t0) > 0);
    double a = t0, b = t0;
    while (N(b) > 0) {
        a = b;
        b += 1e-3;
        REQUIRE(b < t0 + 100.0);
    }
    for (int i = 0; i < 200; ++i) {
        const double m = 0.5 * (a + b);
        if (m <= a || m >= b) break;
        (N(m) > 0 ? a : b) = m;
    }
    return b;
}

// Contact with a compliant bumper, from the dense output: crossings of x = xI, and the work of the
// bumper's force split into its elastic part kI h^n1 and the rest (damping and the F >= 0 clamp).
struct ContactWatcher : Observer {
    double xI, kI, b, n1, n2, n3;
    std::vector<double> entries, exits;
    double work_total = 0, work_elastic = 0;   // int F v dt, int kI h^n1 v dt
    double h_max = 0;

    double force(double h, double v) const {
        if (h <= 0) return 0.0;
        const double sgn = v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0);
        return std::max(0.0, kI * (std::pow(h, n1) + b * std::pow(h, n2) * std::pow(std::abs(v), n3) * sgn));
    }
    void on_piece(const Piece& piece) override {
        auto g = [&](double t) { return piece.at(t)[0] - xI; };
        const double g0 = g(piece.t0), g1 = g(piece.t1);
        if ((g0 <= 0) != (g1 <= 0)) {
            double a = piece.t0, c = piece.t1;
            for (int i = 0; i < 200; ++i) {
                const double m = 0.5 * (a + c);
                if (m <= a || m >= c) break;
                ((g(m) <= 0) == (g0 <= 0) ? a : c) = m;
            }
            (g0 <= 0 ? entries : exits).push_back(0.5 * (a + c));
        }
        // Gauss-Legendre (8 points) on 32 sub-intervals of the piece.
        static constexpr double gx[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                         0.9602898564975363};
        static constexpr double gw[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                         0.1012285362903763};
        const int sub = 32;
        const double len = (piece.t1 - piece.t0) / sub;
        for (int s = 0; s < sub; ++s) {
            const double mid = piece.t0 + (s + 0.5) * len, half = 0.5 * len;
            for (int i = 0; i < 4; ++i)
                for (double sign : {-1.0, 1.0}) {
                    const Vec2 y = piece.at(mid + sign * half * gx[i]);
                    const double h = y[0] - xI;
                    if (h <= 0) continue;
                    h_max = std::max(h_max, h);
                    work_total += gw[i] * half * force(h, y[1]) * y[1];
                    work_elastic += gw[i] * half * kI * std::pow(h, n1) * y[1];
                }
        }
    }
};

// Hertz contact m h'' = -kI h^(3/2) from h = 0 at speed v0: h_max from the energy, and the duration
// t_c = 2 int_0^hmax dh / sqrt(v0^2 - (4 kI / 5m) h^(5/2)) = 2 (h_max / v0) int_0^1 du / sqrt(1 - u^(5/2)),
// the integral by Gauss-Legendre after u = 1 - w^2 (which removes the endpoint singularity).
double hertz_integral() {
    auto f = [](double w) {
        const double u = 1.0 - w * w;
        const double d = 1.0 - std::pow(u, 2.5);
        return d > 0 ? 2.0 * w / std::sqrt(d) : 2.0 / std::sqrt(2.5);   // the w -> 0 limit
    };
    static constexpr double gx[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
    static constexpr double gw[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
    const int n = 4000;
    double sum = 0;
    for (int s = 0; s < n; ++s) {
        const double mid = (s + 0.5) / n, half = 0.5 / n;
        for (int i = 0; i < 4; ++i) sum += gw[i] * half * (f(mid - half * gx[i]) + f(mid + half * gx[i]));
    }
    return sum;
}

}  // namespace

TEST_CASE("a single G or H impact: v+ = -kappa(v-) v-, held for T_imp(v-), released with v+") {
    for (const std::string version : {"A1G", "A1H"}) {
        const RigidLaw& law = version == "A1G" ? kG : kH;
        for (double v0 : {0.01, 0.2, 0.9, 3.0}) {
            const Params p = coasting(version.c_str());
            const Drive drive(10.0);
            Simulator sim(tight(1e-10));
            State s;
            const double d = 1e-3;
            s.x = p.xI - d;
            s.v = v0;
            Simulator::make_consistent(p, drive, s);
            Recorder rec;
            const double t_end = d / v0 + 0.02;
            sim.advance(p, drive, s, t_end, &rec);
            CAPTURE(version);
            CAPTURE(v0);
            REQUIRE(rec.impacts.size() == 1);
            const ImpactEvent e = rec.impacts[0];
            const double t_hit = d / v0;
            CHECK(std::abs(e.t - t_hit) < 1e-12);
            CHECK(e.v_minus == doctest::Approx(v0).epsilon(1e-12));
            const double k = kappa(law, e.v_minus), T = t_imp(law, e.v_minus);
            CHECK(e.v_plus == doctest::Approx(-k * e.v_minus).epsilon(1e-14));
            CHECK(e.duration == doctest::Approx(T).epsilon(1e-14).scale(1e-18));
            if (T > 0) {
                // II from the impact to t + T_imp, then I.
                REQUIRE(rec.changes.size() == 2);
                CHECK(rec.changes[0].from == Regime::Free);
                CHECK(rec.changes[0].to == Regime::Sticking);
                CHECK(rec.changes[0].t == e.t);
                CHECK(rec.changes[1].from == Regime::Sticking);
                CHECK(rec.changes[1].to == Regime::Free);
                CHECK(rec.changes[1].t == doctest::Approx(e.t + T).epsilon(1e-15));
                // Held at xI meanwhile.
                double held = 0;
                for (const auto& pc : rec.pieces)
                    if (pc.regime == Regime::Sticking) {
                        held += pc.t1 - pc.t0;
                        CHECK(pc.x_hold == p.xI);
                    }
                CHECK(held == doctest::Approx(T).epsilon(1e-12));
            } else {
                CHECK(rec.changes.empty());   // G: instantaneous, straight back to free flight
            }
            // Then it coasts away with v+.
            CHECK(s.t == t_end);
            CHECK(s.regime == Regime::Free);
            CHECK(s.v == doctest::Approx(e.v_plus).epsilon(1e-12));
            CHECK(s.x == doctest::Approx(p.xI + e.v_plus * (t_end - e.t - T)).epsilon(1e-10));
            CHECK(s.impacts == 1);
        }
    }
}

TEST_CASE("end of regime II: III if |v+| < eps_v and pressed, else free flight with v+") {
    // A slow impact (v- = 1e-4 m/s, so |v+| = kappa v- < eps_v = 1e-4 m/s) with the magnets pressing the cart
    // onto the bumper (xI = +5 mm, N = -F_SA(xI) > 0) or pulling it away (xI = -5 mm, N < 0). No forcing, no
    // resistance: the cart coasts to the bumper from 1 um away.
    for (const std::string version : {"A1G", "A1H"}) {
        const RigidLaw& law = version == "A1G" ? kG : kH;
        for (double xI : {0.005, -0.005}) {
            Params p = make_version(version);
            p.c = 0;
            p.T = 0;
            p.m0e = 0;
            p.xI = xI;
            const Drive drive(10.0);
            const bool pressed = normal_force(p, drive, 0.0) > 0;
            REQUIRE(pressed == (xI > 0));
            Simulator sim(tight(1e-10));
            State s;
            s.x = xI - 1e-9;
            s.v = 1e-4;
            Simulator::make_consistent(p, drive, s);
            REQUIRE(s.regime == Regime::Free);
            Recorder rec;
            sim.advance(p, drive, s, 0.05, &rec);
            CAPTURE(version);
            CAPTURE(xI);
            REQUIRE(!rec.impacts.empty());
            const ImpactEvent e = rec.impacts[0];
            CHECK(e.v_plus == doctest::Approx(-kappa(law, e.v_minus) * e.v_minus).epsilon(1e-14));
            CHECK(std::abs(e.v_plus) < 1e-4);
            if (!pressed && law.Ti0 == 0) CHECK(rec.changes.empty());   // G: I -> I, no regime change
            if (pressed || law.Ti0 > 0) REQUIRE(!rec.changes.empty());
            const auto last = rec.changes.empty() ? Recorder::Change{0, Regime::Free, Regime::Free} : rec.changes.back();
            if (!pressed) CHECK(last.to == Regime::Free);
            if (pressed) {
                // Ends at rest on the bumper, entered T_imp(v-) after the impact.
                CHECK(rec.impacts.size() == 1);
                CHECK(last.to == Regime::Contact);
                CHECK(last.from == (law.Ti0 > 0 ? Regime::Sticking : Regime::Free));
                CHECK(last.t == doctest::Approx(e.t + t_imp(law, e.v_minus)).epsilon(1e-14));
                CHECK(s.regime == Regime::Contact);
                CHECK(s.x == xI);
                CHECK(s.v == 0.0);
            } else {
                // Not pressed: back to free flight with v+, and the magnets pull the cart away.
                CHECK(s.regime == Regime::Free);
                CHECK(s.x < xI - 1e-6);
                CHECK(rec.impacts.size() == 1);
            }
        }
    }
}

TEST_CASE("regime III: entered when pressed, left exactly when N crosses zero") {
    // xI = 5 mm, right of the hilltop: the magnets press the cart onto the bumper with -F_SA(xI) = 2.28 N;
    // at omega = 12 the unbalance (3.62 N) pulls it off once a revolution.
    for (const std::string version : {"A1G", "A1H"}) {
        Params p = make_version(version);
        p.xI = 0.005;
        const Drive drive(12.0, 0.0, 0.0);
        const double F0 = -spring_magnet(p, p.xI).F;
        REQUIRE(F0 > 0);
        REQUIRE(p.m0e * 144.0 > F0);
        Simulator sim(tight(1e-10));
        State s;
        s.x = p.xI;
        Simulator::make_consistent(p, drive, s);
        CAPTURE(version);
        REQUIRE(s.regime == Regime::Contact);
        Recorder rec;
        sim.advance(p, drive, s, 0.5, &rec);
        REQUIRE(!rec.changes.empty());
        CHECK(rec.changes[0].from == Regime::Contact);
        CHECK(rec.changes[0].to == Regime::Free);
        const double t_root = first_root_of_normal_force(p, drive, 0.0);
        const double t_closed = (kPi + std::asin(F0 / (p.m0e * 144.0))) / 12.0;
        MESSAGE(version << ": left regime III at " << rec.changes[0].t << " s; root of N " << t_root
                        << " s (error " << rec.changes[0].t - t_root << " s), closed form " << t_closed << " s");
        CHECK(std::abs(t_root - t_closed) < 1e-12);
        CHECK(std::abs(rec.changes[0].t - t_root) < 1e-9);
        // Held at (xI, 0) until then.
        for (const auto& pc : rec.pieces)
            if (pc.t1 <= rec.changes[0].t) CHECK(pc.regime == Regime::Contact);
        // A weaker unbalance never lifts the cart: it stays in III, every section is (xI, 0) in regime III.
        Params weak = p;
        weak.m0e = 0.01;   // m0e w^2 = 1.44 N < -F_SA(xI)
        State w;
        w.x = weak.xI;
        Simulator::make_consistent(weak, drive, w);
        Recorder held;
        sim.advance(weak, drive, w, 5.0, &held);
        CHECK(held.changes.empty());
        CHECK(held.impacts.empty());
        CHECK(w.regime == Regime::Contact);
        REQUIRE(held.sections.size() == 9);   // 5 s at 12 rad/s: 9.5 revolutions
        for (const auto& sp : held.sections) {
            CHECK(sp.t == drive.time_of_phase(2 * kPi * static_cast<double>(sp.n)));
            CHECK(sp.regime == Regime::Contact);
            CHECK(sp.x == weak.xI);
            CHECK(sp.v == 0.0);
        }
    }
}

TEST_CASE("chattering: accumulating impacts end in regime III in a bounded number of steps") {
    // As above; after lifting off the cart comes back while N > 0 and bounces with ever smaller speeds
    // (kappa ~ 0.62 at small v-) until |v+| < eps_v: then regime III, until N crosses zero again.
    for (const std::string version : {"A1G", "A1H"}) {
        Params p = make_version(version);
        p.xI = 0.005;
        const Drive drive(12.0, 0.0, 0.0);
        Simulator sim(tight(1e-10));
        State s;
        s.x = p.xI;
        Simulator::make_consistent(p, drive, s);
        REQUIRE(s.regime == Regime::Contact);
        Recorder rec;
        rec.stop_after_changes_to_contact = 1;   // stop at the first re-entry into III
        const double period = 2 * kPi / 12.0;
        sim.advance(p, drive, s, 3 * period, &rec);
        CAPTURE(version);
        MESSAGE(version << ": back in regime III at t = " << s.t << " s after " << rec.impacts.size()
                        << " impacts, " << s.steps << " steps, " << s.rejected << " rejected");
        REQUIRE(rec.contact_entries == 1);
        CHECK(s.regime == Regime::Contact);
        CHECK(s.x == p.xI);
        CHECK(s.v == 0.0);
        CHECK(rec.impacts.size() >= 3);      // a real sequence of bounces
        CHECK(rec.impacts.size() < 200);     // ... that ends
        CHECK(s.steps < 20000);
        // The velocities fall geometrically and the last impact leaves |v+| < eps_v, pressed (N > 0).
        for (std::size_t i = 1; i < rec.impacts.size(); ++i) CHECK(rec.impacts[i].v_minus < rec.impacts[i - 1].v_minus);
        const ImpactEvent& last = rec.impacts.back();
        CHECK(std::abs(last.v_plus) < 1e-4);
        CHECK(normal_force(p, drive, s.t) > 0);
        CHECK(rec.changes.back().t == doctest::Approx(last.t + last.duration).epsilon(1e-14));
        // The time the bounces took is finite and well inside a revolution.
        CHECK(s.t < rec.changes[0].t + period);
        // And the next lift-off is again at the root of N.
        const double t_rest = s.t;
        Recorder more;
        sim.advance(p, drive, s, t_rest + period, &more);
        REQUIRE(!more.changes.empty());
        CHECK(more.changes[0].from == Regime::Contact);
        const double t_root = first_root_of_normal_force(p, drive, t_rest);
        CHECK(std::abs(more.changes[0].t - t_root) < 1e-9);
    }
}

TEST_CASE("Hunt-Crossley without damping (b = 0) is Hertz contact: duration and restitution 1") {
    const double I = hertz_integral();
    // Cross-check the quadrature with the Beta function: int_0^1 (1 - u^(5/2))^(-1/2) du = (2/5) B(2/5, 1/2).
    const double beta = std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);
    MESSAGE("Hertz: t_c = " << 2 * I << " h_max / v0 (quadrature), (4/5) B(2/5,1/2) = " << 0.8 * beta
                            << ", difference " << 2 * I - 0.8 * beta);
    CHECK(I == doctest::Approx(0.4 * beta).epsilon(1e-9));
    for (const std::string version : {"A1C", "A1C1"}) {
        for (double v0 : {0.05, 0.5}) {
            Params p = coasting(version.c_str());
            set_impact_param(p, "b", 0.0);
            const double kI = impact_param(p, "kI");
            const Drive drive(10.0);
            Simulator sim(tight(1e-10));
            State s;
            const double d = 1e-3;
            s.x = p.xI - d;
            s.v = v0;
            Simulator::make_consistent(p, drive, s);
            ContactWatcher w;
            w.xI = p.xI;
            w.kI = kI;
            w.b = 0;
            w.n1 = w.n2 = 1.5;
            w.n3 = impact_param(p, "n3");
            const double h_max = std::pow(1.25 * p.m * v0 * v0 / kI, 0.4);
            const double t_c = 2 * I * h_max / v0;
            sim.advance(p, drive, s, d / v0 + 3 * t_c, &w);
            CAPTURE(version);
            CAPTURE(v0);
            REQUIRE(w.entries.size() == 1);
            REQUIRE(w.exits.size() == 1);
            const double measured = w.exits[0] - w.entries[0];
            MESSAGE(version << " b=0, v0 " << v0 << ": contact " << measured << " s, Hertz " << t_c
                            << " s (rel. error " << measured / t_c - 1 << "); exit speed " << -s.v
                            << "; h_max " << w.h_max << " m vs " << h_max);
            CHECK(std::abs(w.entries[0] - d / v0) < 1e-12);
            CHECK(measured == doctest::Approx(t_c).epsilon(1e-8).scale(0));
            CHECK(s.v == doctest::Approx(-v0).epsilon(1e-8).scale(0));   // elastic: restitution 1
            CHECK(w.h_max == doctest::Approx(h_max).epsilon(1e-4).scale(0));   // sampled, so slightly below
            CHECK(s.impacts == 0);   // compliant contact is no rigid impact
        }
    }
}

TEST_CASE("Hunt-Crossley with damping (C, C1): slower exit, energy lost = work of the damping force") {
    for (const std::string version : {"A1C", "A1C1"}) {
        for (double v0 : {0.05, 0.5}) {
            const Params p = coasting(version.c_str());
            const Drive drive(10.0);
            Simulator sim(tight(1e-10));
            State s;
            const double d = 1e-3;
            s.x = p.xI - d;
            s.v = v0;
            Simulator::make_consistent(p, drive, s);
            ContactWatcher w;
            w.xI = p.xI;
            w.kI = impact_param(p, "kI");
            w.b = impact_param(p, "b");
            w.n1 = impact_param(p, "n1");
            w.n2 = impact_param(p, "n2");
            w.n3 = impact_param(p, "n3");
            const double E0 = mechanical_energy(p, s.x, s.v);
            sim.advance(p, drive, s, d / v0 + 0.02, &w);
            CAPTURE(version);
            CAPTURE(v0);
            REQUIRE(w.entries.size() == 1);
            REQUIRE(w.exits.size() == 1);
            const double lost = E0 - mechanical_energy(p, s.x, s.v);
            const double damping_work = w.work_total - w.work_elastic;
            MESSAGE(version << ", v0 " << v0 << ": contact " << w.exits[0] - w.entries[0] << " s, exit speed "
                            << -s.v << " (e = " << -s.v / v0 << "), energy lost " << lost
                            << " J, damping work " << damping_work << " J (rel. difference " << damping_work / lost - 1
                            << "), elastic work " << w.work_elastic << " J");
            CHECK(s.v < 0);
            CHECK(-s.v < v0);
            CHECK(lost > 0);
            CHECK(lost == doctest::Approx(0.5 * p.m * (v0 * v0 - s.v * s.v)).epsilon(1e-12));
            CHECK(damping_work == doctest::Approx(lost).epsilon(1e-6).scale(0));
            CHECK(std::abs(w.work_elastic) < 1e-6 * lost);   // the elastic part gives back what it took
        }
    }
}

TEST_CASE("a cart resting on a compliant bumper costs few steps (it once crawled at 2e6 steps/s)") {
    // The damping factor |h'|^n3 continues linearly below kLinearVelocity, so the force has a finite slope
    // where the resting cart's h' changes sign; before that 100 s took 8.5e7 steps.
    struct Case { const char* version; double m0e, omega, duration; std::uint64_t max_steps; };
    for (const Case c : {Case{"A1C1", 0.1, 0.0833, 100.0, 20000}, Case{"A3C1", 0.25152, 4.0, 50.0, 20000}}) {
        Params p = make_version(c.version);
        p.m0e = c.m0e;
        p.xI = -0.02;
        const Drive drive(c.omega);
        Simulator sim;
        State s;
        Simulator::make_consistent(p, drive, s);
        sim.advance(p, drive, s, c.duration);
        CAPTURE(c.version);
        CHECK(s.t == c.duration);
        CHECK(s.x > p.xI);   // it does rest pressed into the bumper
        CHECK(s.steps < c.max_steps);
    }
    // The force is continuous where the linear part meets the power law, and its slope there is finite.
    const ImpactModel* c1 = find_impact("C1");
    const double h = 3e-8, vl = 1e-7;   // hunt_crossley::kLinearVelocity
    const ContactForce below = c1->contact(c1->defaults.data(), h, vl * (1 - 1e-9));
    const ContactForce above = c1->contact(c1->defaults.data(), h, vl * (1 + 1e-9));
    CHECK(below.F == doctest::Approx(above.F).epsilon(1e-6));
    CHECK(std::isfinite(c1->contact(c1->defaults.data(), h, 0.0).dF_dhdot));
}

TEST_CASE("Hunt-Crossley's true slope in h' (what a tangent uses) is the force's derivative") {
    // The law hands the integrator a secant slope; the tangent takes dF_dhdot_true instead, which must be the
    // derivative of F itself on the power law (n3 |h'|^(n3 - 1), steep towards h' = 0) and on the linear part.
    for (const char* id : {"C", "C1"}) {
        CAPTURE(id);
        const ImpactModel* law = find_impact(id);
        const double* ip = law->defaults.data();
        for (double h : {1e-8, 1e-6, 6e-5}) {
            for (double hdot : {-0.5, -3e-3, -2e-6, -5e-8, 0.0, 4e-8, 3e-6, 0.02, 0.7}) {
                CAPTURE(h);
                CAPTURE(hdot);
                const ContactForce c = law->contact(ip, h, hdot);
                if (c.F <= 0.0) continue;   // clipped (h' pulling out fast): no force, no slope
                const double dv = 1e-7 * std::abs(hdot) + 1e-14;
                const double fd = (law->contact(ip, h, hdot + dv).F - law->contact(ip, h, hdot - dv).F) / (2 * dv);
                REQUIRE(std::isfinite(c.dF_dhdot_true));
                CHECK(c.dF_dhdot_true == doctest::Approx(fd).epsilon(1e-6));
                if (std::abs(hdot) > 1e-7) CHECK(c.dF_dhdot_true < c.dF_dhdot);   // n3 < 1: below the secant
            }
        }
        // Out of contact: no force and no slope.
        CHECK(law->contact(ip, -1e-6, 0.1).dF_dhdot_true == 0.0);
    }
}
