// The live omega ramp (a teaching overlay): the engine's drive moves omega linearly at the asked
// rate with phi continuous, section points keep phi = 2 pi n on the ramp, and it stops at its target.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "../../app/gui/sim/sim_engine.hpp"
#include "engine_fixtures.hpp"

using namespace impactlab;
using namespace impactlab::gui;
using namespace impactlab::gui::testing;

TEST_CASE("omega ramp: linear at the asked rate, phi continuous, constant after the target") {
    VectorSink sink;
    EngineConfig cfg;
    cfg.model = "A1H";
    cfg.omega = 8.0;
    SimEngine e(cfg, &sink);
    e.advance_to(2.0);
    const double phi_before = e.phi();
    const std::uint32_t epoch = e.epoch();
    REQUIRE(e.apply(SimCommand::ramp(10.0, 0.5)));   // 4 s of ramp
    CHECK(e.epoch() == epoch + 1);
    CHECK(e.phi() == doctest::Approx(phi_before).epsilon(1e-12));
    sink.msgs.clear();
    e.advance_to(8.0);
    bool linear = true, sections_on_phase = true;
    double w_end = 0;
    for (const SimMsg& m : sink.msgs) {
        const double expect = m.t <= 6.0 ? 8.0 + 0.5 * (m.t - 2.0) : 10.0;
        linear &= std::abs(m.omega - expect) < 1e-9;
        if (m.kind == MsgKind::Section) {
            const double n = std::round(m.phi / kTwoPi);
            sections_on_phase &= std::abs(m.phi - kTwoPi * n) < 1e-9 * std::max(1.0, m.phi);
        }
        w_end = m.omega;
    }
    CHECK(linear);
    CHECK(sections_on_phase);
    CHECK(w_end == 10.0);
    // The energy balance went on through the ramp.
    CHECK(e.energy().t0 == 0.0);
    CHECK(std::abs(e.energy().residual()) < 1e-5 * e.energy().turnover());
}

TEST_CASE("omega ramp: bad rates and targets are clamped, a set omega ends the ramp") {
    EngineConfig cfg;
    cfg.omega = 5.0;
    SimEngine e(cfg);
    REQUIRE(e.apply(SimCommand::ramp(1e9, -1e9)));   // to kMaxOmega at kMaxRampRate
    e.advance_to(1.0);
    CHECK(e.drive().omega(1.0) == doctest::Approx(5.0 + kMaxRampRate));
    REQUIRE(e.apply(SimCommand::ramp(NAN, NAN)));    // NaN target: stays where it is
    REQUIRE(e.apply(SimCommand::omega(12.0)));
    e.advance_to(3.0);
    CHECK(e.drive().omega(3.0) == 12.0);
    const std::uint32_t epoch = e.epoch();
    REQUIRE(e.apply(SimCommand::ramp(12.0, 0.1)));   // already there: no new epoch
    CHECK(e.epoch() == epoch);
}
