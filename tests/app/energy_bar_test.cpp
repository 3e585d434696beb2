// The energy bar's arithmetic over the GUI's engine: the two bars agree when the ledger closes, their
// segments are what the ledger says, and the balance starts afresh on a change of model or state but not
// of omega.
#include <doctest/doctest.h>

#include <cmath>
#include <numeric>

#include "../../app/gui/views/energy_bar.hpp"
#include "../../app/gui/sim/sim_engine.hpp"
#include "impactlab/forces.hpp"

using namespace impactlab;
using namespace impactlab::gui;

TEST_CASE("energy bar: in and out agree on a chaotic A1H run, and each segment is the ledger's") {
    EngineConfig cfg;
    cfg.model = "A1H";
    cfg.omega = 16.0;
    SimEngine e(cfg);
    e.advance_to(20.0);
    const EnergyBalance& b = e.energy();
    REQUIRE(b.t == doctest::Approx(20.0));
    const double floor = potential_floor(e.params());
    CHECK(floor < 0);   // the double well's floor lies below the hilltop V(0) = 0
    CHECK(floor <= spring_magnet_potential(e.params(), b.x));
    const EnergyBars bars = energy_bars(b, e.params().m, floor);
    const double in = std::accumulate(bars.in.begin(), bars.in.end(), 0.0);
    const double out = std::accumulate(bars.out.begin(), bars.out.end(), 0.0);
    CHECK(bars.full == std::max(in, out));
    CHECK(std::abs(in - out) < 1e-6 * bars.full);
    CHECK(bars.in[1] == b.work_unbalance);
    CHECK(bars.out[2] == b.dissipated_resistance);
    CHECK(bars.out[3] == b.dissipated_bumper);
    CHECK(bars.out[3] > 0);   // omega = 16: the cart hits the bumper
    CHECK(bars.out[0] == doctest::Approx(0.5 * e.params().m * b.v * b.v));
}

TEST_CASE("energy bar: a model switch or a reset starts a new balance; an omega change continues it") {
    EngineConfig cfg;
    cfg.model = "A1C";
    cfg.omega = 12.0;
    SimEngine e(cfg);
    e.advance_to(5.0);
    const double w_before = e.energy().work_unbalance;
    REQUIRE(w_before > 0);
    e.apply(SimCommand::omega(13.0));
    CHECK(e.energy().work_unbalance == w_before);
    CHECK(e.energy().t0 == 0.0);
    e.advance_to(8.0);
    CHECK(e.energy().work_unbalance != w_before);
    CHECK(std::abs(e.energy().residual()) < 1e-5 * e.energy().turnover());
    e.apply(SimCommand::set_model("A1G"));
    CHECK(e.energy().t0 == doctest::Approx(8.0));
    CHECK(e.energy().work_unbalance == 0.0);
    e.advance_to(9.0);
    e.apply(SimCommand::reset(-0.011, 0.0));
    CHECK(e.energy().t0 == 0.0);
    CHECK(e.energy().dissipated_resistance == 0.0);
}
