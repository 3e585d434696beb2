// The energy balance (core/energy): every term a quadrature of its own power, so the balance closing is a
// check of the simulator and the ledger together; the bumper's share against the impact events.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "impactlab/drive.hpp"
#include "impactlab/energy.hpp"
#include "impactlab/params.hpp"
#include "impactlab/simulator.hpp"
#include "coasting.hpp"

using namespace impactlab;

namespace {

// The ledger and an impact recorder on one run.
struct LedgerAndImpacts : Observer {
    EnergyLedger ledger;
    double impact_loss = 0;   // sum of 1/2 m (v-^2 - v+^2) over the rigid impacts [J]
    const Params& p;
    LedgerAndImpacts(const Params& params, const Drive& d) : ledger(params, d), p(params) {}
    void on_piece(const Piece& pc) override { ledger.on_piece(pc); }
    void on_impact(const ImpactEvent& e) override {
        impact_loss += 0.5 * p.m * (e.v_minus * e.v_minus - e.v_plus * e.v_plus);
    }
};

struct Run { EnergyBalance b; double impact_loss; std::uint64_t impacts; };

Run run(const Params& p, double omega, double seconds) {
    const Drive d(omega);
    Simulator sim;
    State s;
    s.x = -0.011;
    Simulator::make_consistent(p, d, s);
    LedgerAndImpacts obs(p, d);
    obs.ledger.reset(s);
    double last_resistance = 0;
    bool monotone = true;
    for (int i = 1; i <= 20; ++i) {
        sim.advance(p, d, s, seconds * i / 20, &obs);
        monotone &= obs.ledger.balance().dissipated_resistance >= last_resistance;
        last_resistance = obs.ledger.balance().dissipated_resistance;
    }
    CHECK(monotone);
    CHECK(obs.ledger.balance().t == s.t);
    return {obs.ledger.balance(), obs.impact_loss, s.impacts};
}

}  // namespace

TEST_CASE("the energy balance closes on every version, periodic and chaotic") {
    for (const char* version : {"A1C", "A1C1", "A1G", "A1H", "A3C", "A3C1", "A3G", "A3H"}) {
        for (const double omega : {9.0, 16.0}) {
            CAPTURE(version);
            CAPTURE(omega);
            const Params p = make_version(version);
            const Run r = run(p, omega, 30.0);
            const EnergyBalance& b = r.b;
            MESSAGE(std::string(version) << " omega " << omega << ": W " << b.work_unbalance << " J, D_R "
                            << b.dissipated_resistance << " J, D_I " << b.dissipated_bumper << " J, dE "
                            << b.E - b.E0 << " J, residual " << b.residual() << " J");
            CHECK(b.work_unbalance > 0);            // the unbalance feeds the motion on average
            CHECK(b.dissipated_resistance > 0);
            CHECK(b.dissipated_bumper >= -1e-9 * b.turnover());
            CHECK(b.work_effects == 0.0);
            CHECK(std::abs(b.residual()) < 1e-5 * b.turnover());   // measured 2e-8 .. 4e-7
            if (p.rigid()) {
                // The bumper's share is the kinetic energy the impacts took (up to the releases below eps_v
                // that end in permanent contact, which lose their tiny v+ as well).
                CHECK(b.dissipated_bumper >= r.impact_loss - 1e-9);
                CHECK(b.dissipated_bumper <= r.impact_loss * (1 + 1e-3) + 1e-9);
            }
        }
    }
}

TEST_CASE("one compliant impact: the bumper's hysteresis is the kinetic energy lost, nothing else does work") {
    for (const char* version : {"A1C", "A1C1"}) {
        CAPTURE(version);
        const Params p = impactlab::testing::coasting(version);
        const Drive d(1.0);
        Simulator sim;
        State s;
        s.x = -1e-3;
        s.v = 0.5;   // [m/s] towards the bumper
        Simulator::make_consistent(p, d, s);
        EnergyLedger ledger(p, d);
        ledger.reset(s);
        sim.advance(p, d, s, 0.05, &ledger);   // in, out, and coasting away
        REQUIRE(s.v < 0);
        const EnergyBalance& b = ledger.balance();
        const double lost = 0.5 * p.m * (0.25 - s.v * s.v);
        CHECK(lost > 0);
        CHECK(b.dissipated_bumper == doctest::Approx(lost).epsilon(1e-6));
        CHECK(b.work_unbalance == 0.0);
        CHECK(b.dissipated_resistance == 0.0);
        CHECK(std::abs(b.residual()) < 1e-5 * b.turnover());   // measured 4e-7 at the default tolerances
    }
}

TEST_CASE("a free, unforced, undamped run: every term stays 0 and E is conserved") {
    Params p = make_version("A1H");
    p.c = 0;
    p.T = 0;
    p.m0e = 0;
    p.xI = 0.05;   // out of reach
    const Drive d(5.0);
    Simulator sim;
    State s;
    s.x = -0.02;
    EnergyLedger ledger(p, d);
    ledger.reset(s);
    sim.advance(p, d, s, 10.0, &ledger);
    const EnergyBalance& b = ledger.balance();
    CHECK(b.work_unbalance == 0.0);
    CHECK(b.dissipated_resistance == 0.0);
    CHECK(std::abs(b.dissipated_bumper) < 1e-6 * std::abs(b.E0));
    CHECK(std::abs(b.E - b.E0) < 1e-6 * std::abs(b.E0));
}
