// The visualiser's simulation side without a window: commands applied between steps (model switch, xI,
// omega, step one period, reset), what gets published, and the paced thread itself.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include "../../app/gui/sim/sim_engine.hpp"
#include "engine_fixtures.hpp"
#include "../../app/gui/sim/sim_thread.hpp"

using namespace impactlab;
using namespace impactlab::gui;
using namespace impactlab::gui::testing;

TEST_CASE("engine: samples on a fixed grid, sections from the core, everything in time order") {
    VectorSink sink;
    SimEngine e(config("A1H", 12.0), &sink);
    e.advance_to(2.0);
    CHECK(e.state().t == doctest::Approx(2.0));
    const double dt = e.sample_dt();
    CHECK(sink.count(MsgKind::Sample) == doctest::Approx(2.0 / dt).epsilon(0.01));
    // 2 s at 12 rad/s: 3 sections (phi = 2 pi, 4 pi, 6 pi).
    CHECK(sink.count(MsgKind::Section) == 3);
    double t_prev = -1;
    for (const auto& m : sink.msgs) {
        CHECK(m.t >= t_prev);
        t_prev = m.t;
        if (m.kind == MsgKind::Section) {
            const double n = m.phi / (2 * std::numbers::pi);
            CHECK(std::abs(n - std::round(n)) < 1e-9);
        }
        CHECK(std::isfinite(m.energy));
    }
}

TEST_CASE("engine: a reader that falls behind defers the simulation; no record and no Poincare section is lost") {
    // A ring that the UI drains too slowly (a loaded machine at 100x) once dropped records, Poincare sections
    // among them, and a period-2 map then lost its alternation and went back to settling.
    struct SlowReader final : MsgSink {
        std::vector<SimMsg> pending, read;
        std::size_t capacity = 4096, reserve = 1024, dropped = 0;
        void put(const SimMsg& m) override {
            if (pending.size() >= capacity) ++dropped;
            else pending.push_back(m);
        }
        bool has_room() override { return pending.size() + reserve <= capacity; }
    } sink;
    SimEngine e(config("A1G", 10.9113), &sink);
    const double t_end = 60.0;   // 60,000 samples at 1 ms, fifteen times what the reader holds
    int slices = 0;
    while (e.state().t < t_end && slices < 1000) {
        e.advance_to(t_end);
        ++slices;
        CHECK(sink.dropped == 0);
        sink.read.insert(sink.read.end(), sink.pending.begin(), sink.pending.end());
        sink.pending.clear();
    }
    CHECK(e.state().t == doctest::Approx(t_end));
    CHECK(slices > 10);   // deferred many times, never dropped
    const double period = 2 * std::numbers::pi / 10.9113;
    std::vector<double> sections;
    for (const auto& m : sink.read)
        if (m.kind == MsgKind::Section) sections.push_back(m.t);
    CHECK(sections.size() == static_cast<std::size_t>(t_end / period));
    for (std::size_t i = 1; i < sections.size(); ++i) CHECK(sections[i] - sections[i - 1] == doctest::Approx(period).epsilon(1e-9));
    std::size_t samples = 0;
    for (const auto& m : sink.read) samples += m.kind == MsgKind::Sample;
    CHECK(samples == doctest::Approx(t_end / e.sample_dt()).epsilon(1e-3));
}

TEST_CASE("engine: a model switch mid-run keeps x, v and phi, and bumps the epoch") {
    VectorSink sink;
    SimEngine e(config("A1H", 12.0), &sink);   // period 2 in the left well, clear of the bumper at xI = 0
    const char* chain[] = {"A1G", "A1C", "A1C1", "A3H", "A3C", "A1H"};
    double t = 1.0;
    for (const char* name : chain) {
        e.advance_to(t);
        t += 0.37;
        REQUIRE(e.state().x < e.params().xI);
        const double x = e.state().x, v = e.state().v, phi = e.phi(), time = e.state().t;
        const auto epoch = e.epoch();
        REQUIRE(e.apply(SimCommand::set_model(name)));
        CHECK(e.params().name == name);
        CHECK(e.state().x == x);
        CHECK(e.state().v == v);
        CHECK(e.phi() == phi);
        CHECK(e.state().t == time);
        CHECK(e.epoch() == epoch + 1);
        CHECK(sink.msgs.back().epoch == e.epoch());   // the change is published at once
        CHECK(sink.msgs.back().x == x);
    }
    e.advance_to(t + 1.0);
    CHECK(std::isfinite(e.state().x));
    CHECK(e.state().t == doctest::Approx(t + 1.0));
}

TEST_CASE("engine: a model switch keeps xI and an unknown model is refused") {
    SimEngine e(config("A1H", 9.0));
    REQUIRE(e.apply(SimCommand::xi(0.004)));
    REQUIRE(e.apply(SimCommand::set_model("A3G")));
    CHECK(e.bumper_target() == 0.004);
    e.advance_to(0.1);   // the bumper travels at kBumperWallSpeed: 4 mm in 40 ms
    CHECK(e.params().xI == 0.004);
    const auto epoch = e.epoch();
    CHECK_FALSE(e.apply(SimCommand::set_model("B7Q")));
    CHECK(e.params().name == "A3G");
    CHECK(e.epoch() == epoch);
    CHECK(e.apply(SimCommand::set_model("A3G")));   // the same version: nothing to do, no new epoch
    CHECK(e.epoch() == epoch);
}

TEST_CASE("engine: moving xI beyond the cart leaves a valid state, never inside a rigid bumper") {
    for (const std::string model : {"A1G", "A1H", "A3H"}) {
        CAPTURE(model);
        VectorSink sink;
        SimEngine e(config(model, 9.0), &sink);   // period 1 in the left well, x about -14 mm
        e.advance_to(3.0);
        const double xI = e.state().x - 0.003;   // the bumper jumps past the cart (paused: at once)
        REQUIRE(xI > -kMaxAbsXI);
        REQUIRE(e.apply(SimCommand::paused(true)));
        REQUIRE(e.apply(SimCommand::xi(xI)));
        REQUIRE(e.apply(SimCommand::paused(false)));
        CHECK(e.params().xI == xI);
        CHECK(e.state().x <= xI);
        CHECK(e.state().v <= 0.0);
        if (e.state().regime != Regime::Free) CHECK(e.state().x == xI);
        sink.msgs.clear();
        e.advance_to(8.0);
        CHECK(e.state().t == doctest::Approx(8.0));
        for (const auto& m : sink.msgs) {
            CHECK(m.x <= xI + 1e-12);
            if (m.regime != Regime::Free) CHECK(m.x == xI);
        }
        // Pressed onto the bumper by the magnets: it must touch it at some point.
        CHECK(e.state().impacts + (e.state().regime == Regime::Contact ? 1u : 0u) > 0);
    }
}

TEST_CASE("engine: moving a compliant bumper onto the cart puts the cart at the contact point at rest") {
    VectorSink sink;
    SimEngine e(config("A1C", 9.0), &sink);
    e.advance_to(3.0);
    const double xI = e.state().x - 0.003;
    REQUIRE(e.apply(SimCommand::paused(true)));   // paused, the bumper moves at once
    REQUIRE(e.apply(SimCommand::xi(xI)));
    REQUIRE(e.apply(SimCommand::paused(false)));
    CHECK(e.state().x == xI);
    CHECK(e.state().v == 0.0);
    CHECK(e.state().regime == Regime::Free);
    sink.msgs.clear();
    e.advance_to(6.0);
    for (const auto& m : sink.msgs) {
        CHECK(std::isfinite(m.x));
        CHECK(m.x < xI + 1e-3);   // penetration of a stiff Hunt-Crossley bumper stays far below a millimetre
        CHECK(m.force >= 0.0);
    }
}

TEST_CASE("engine: an omega change keeps phi continuous; step one period stops at the next section") {
    VectorSink sink;
    SimEngine e(config("A1H", 9.0), &sink);
    e.advance_to(1.234);
    const double phi = e.phi();
    REQUIRE(e.apply(SimCommand::omega(15.0)));
    CHECK(e.phi() == doctest::Approx(phi).epsilon(1e-14));
    CHECK(e.drive().omega(e.state().t) == 15.0);

    REQUIRE(e.apply(SimCommand::step_period()));
    CHECK(e.paused());
    CHECK(e.stepping());
    sink.msgs.clear();
    e.advance_to(1e9);   // clamped to the section
    CHECK_FALSE(e.stepping());
    CHECK(e.paused());
    REQUIRE(sink.count(MsgKind::Section) == 1);
    // The section ends the step (the grazing monitor's summary of the period comes with it).
    const std::size_t last = sink.msgs.size() - (sink.msgs.back().kind == MsgKind::Grazing ? 2 : 1);
    CHECK(sink.msgs[last].kind == MsgKind::Section);
    const double n = e.phi() / (2 * std::numbers::pi);
    CHECK(n == doctest::Approx(std::round(n)).epsilon(1e-12));
    // The next step goes one full period.
    const double t0 = e.state().t;
    e.apply(SimCommand::step_period());
    e.advance_to(1e9);
    CHECK(e.state().t - t0 == doctest::Approx(2 * std::numbers::pi / 15.0).epsilon(1e-9));
}

TEST_CASE("engine: the section phase changes live: a new epoch, sections at phi0 from then on, steps to them") {
    constexpr double kTau = 2 * std::numbers::pi;
    const auto phase_of = [&](const SimMsg& m) { return m.phi - kTau * std::floor(m.phi / kTau + 1e-12); };
    VectorSink sink;
    EngineConfig cfg = config("A1H", 9.0);
    cfg.phi0 = 1.0;   // --phi0: from the start, no change of epoch
    SimEngine e(cfg, &sink);
    CHECK(e.section_phase() == 1.0);
    e.advance_to(3.0);
    CHECK(e.epoch() == 0);
    for (const SimMsg& m : sink.of(MsgKind::Section)) CHECK(phase_of(m) == doctest::Approx(1.0).epsilon(1e-9));
    CHECK(sink.count(MsgKind::Section) == 5);   // phi(3) = 27 rad: 1, 1 + 2 pi, ..., 1 + 8 pi

    const double t = e.state().t, x = e.state().x, v = e.state().v;
    REQUIRE(e.apply(SimCommand::section_phase(4.0)));
    CHECK(e.epoch() == 1);
    CHECK(e.section_phase() == 4.0);
    CHECK(e.state().t == t);   // the run goes on: only the section instants change
    CHECK(e.state().x == x);
    CHECK(e.state().v == v);
    CHECK(sink.msgs.back().epoch == 1);
    REQUIRE(e.apply(SimCommand::section_phase(4.0)));   // the slider resends its value: nothing new
    CHECK(e.epoch() == 1);
    for (double bad : {-0.1, 7.0, std::nan("")}) CHECK_FALSE(e.apply(SimCommand::section_phase(bad)));
    CHECK(e.section_phase() == 4.0);

    sink.msgs.clear();
    e.advance_to(6.0);
    REQUIRE(sink.count(MsgKind::Section) >= 4);
    for (const SimMsg& m : sink.of(MsgKind::Section)) {
        CHECK(m.epoch == 1);
        CHECK(phase_of(m) == doctest::Approx(4.0).epsilon(1e-9));
    }
    // Step one period ends on the next section of the new phase.
    REQUIRE(e.apply(SimCommand::step_period()));
    e.advance_to(1e9);
    CHECK(e.phi() - kTau * std::floor(e.phi() / kTau) == doctest::Approx(4.0).epsilon(1e-9));
    // The companion cart starts with the cart's sections.
    SimEngine ghost(config("A1G", 9.0));
    REQUIRE(ghost.restart_from(e, "A1G", 0.0));
    CHECK(ghost.section_phase() == 4.0);
}

TEST_CASE("engine: reset returns to t = 0 with the given state; clamps out-of-range commands") {
    SimEngine e(config("A1H", 9.0));
    e.advance_to(2.0);
    REQUIRE(e.apply(SimCommand::reset(0.002, 0.0)));   // beyond the bumper at xI = 0: put on it
    CHECK(e.state().t == 0.0);
    CHECK(e.phi() == 0.0);
    CHECK(e.state().x <= 0.0);
    e.apply(SimCommand::omega(1e6));
    CHECK(e.drive().omega(0.0) == kMaxOmega);
    e.apply(SimCommand::xi(-1.0));
    CHECK(e.bumper_target() == -kMaxAbsXI);
    e.apply(SimCommand::speed(1e9));
    CHECK(e.speed() == kMaxSpeed);
    e.apply(SimCommand::speed(0.0));
    CHECK(e.speed() == kMinSpeed);
}

TEST_CASE("sim thread: paced run, commands through the ring, pause holds the time") {
    EngineConfig cfg = config("A1H", 12.0);
    cfg.speed = 20.0;
    SimThread th(cfg);
    th.start();
    std::vector<SimMsg> got;
    auto drain = [&] { th.samples().drain([&](const SimMsg& m) { got.push_back(m); }); };
    for (int i = 0; i < 40; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        drain();
    }
    REQUIRE(!got.empty());
    const double t_before = got.back().t;
    CHECK(t_before > 0.5);   // 20x for ~0.2 s
    CHECK(t_before < 20.0);
    REQUIRE(th.send(SimCommand::set_model("A1G")));
    REQUIRE(th.send(SimCommand::paused(true)));
    // The thread takes the commands at its next slice: wait for it (up to 5 s on a loaded machine), not a
    // fixed time.
    for (int i = 0; i < 500 && !th.status().paused; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
        drain();
    }
    drain();
    CHECK(th.status().paused);
    const double t_paused = th.status().sim_time;
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    drain();
    CHECK(th.status().sim_time == t_paused);
    CHECK(got.back().epoch == 1);
    th.stop();
    double prev = -1;
    for (const auto& m : got) {
        CHECK(m.t >= prev);
        prev = m.t;
    }
    CHECK(th.status().dropped == 0);
}
