// The mouse sets the state, the companion cart and the grazing monitor, and a bumper moved into the cart
// (it once teleported the cart, and the rig and the status bar disagreed on the regime), all without a
// window: the engine's commands, the lockstep pair, the monitor against a fine
// sampling of the core's dense output.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "../../app/gui/sim/companion_track.hpp"
#include "../../app/gui/views/contact_label.hpp"
#include "../../app/gui/sim/grazing_monitor.hpp"
#include "../../app/gui/sim/sim_engine.hpp"
#include "engine_fixtures.hpp"
#include "../../app/gui/sim/sim_thread.hpp"
#include "../../app/gui/sim/state_pick.hpp"

using namespace impactlab;
using namespace impactlab::gui;
using namespace impactlab::gui::testing;

namespace {

// The largest jump of x between two consecutive samples [m].
double largest_step(const std::vector<SimMsg>& samples) {
    double worst = 0;
    for (std::size_t i = 1; i < samples.size(); ++i) worst = std::max(worst, std::abs(samples[i].x - samples[i - 1].x));
    return worst;
}

}  // namespace

TEST_CASE("the bumper and the cart: the bumper moved into the cart pushes it continuously, not in frame-sized steps") {
    for (const std::string model : {"A1C", "A1H"}) {
        CAPTURE(model);
        for (const bool one_jump : {false, true}) {
            CAPTURE(one_jump);
            VectorSink sink;
            SimEngine e(config(model, 9.0), &sink);   // period 1 in the left well, x in about [-14, -7] mm
            const double frame = 1.0 / 60;          // 1x real time, 60 frames a second
            double t = 2.0;
            e.advance_to(t);
            sink.msgs.clear();
            // The slider dragged from +5 mm to -20 mm, 0.5 mm a frame (before the fix: a 0.5 mm step of x at
            // every frame once the bumper reached the cart), or the whole way in one frame (a 13 mm jump).
            double xI = 0.005;
            for (int f = 0; f < 120; ++f) {
                if (one_jump ? f == 0 : xI > -0.020) {
                    xI = one_jump ? -0.020 : std::max(-0.020, xI - 0.0005);
                    REQUIRE(e.apply(SimCommand::xi(xI)));
                }
                t += frame;
                e.advance_to(t);
            }
            const std::vector<SimMsg> samples = sink.of(MsgKind::Sample);
            REQUIRE(samples.size() > 1000);
            // One push is at most kBumperPush; the cart's own motion adds |v| dt (< 0.1 m/s x 1 ms).
            CHECK(largest_step(samples) < kBumperPush + 1e-4);
            CHECK(e.params().xI == -0.020);   // it got there (25 mm at 0.1 m/s: 0.25 s)
            CHECK(e.bumper_target() == -0.020);
            CHECK(e.state().x <= -0.020 + (model == "A1C" ? 1e-4 : 1e-12));
        }
    }
}

TEST_CASE("the bumper and the cart: paused, the bumper moves at once; resending the same xI leaves a pressed cart alone") {
    VectorSink sink;
    EngineConfig c = config("A1C", 9.0);
    c.xI = -0.015;   // the magnets press the cart onto the compliant bumper
    SimEngine e(c, &sink);
    e.advance_to(3.0);
    const double x = e.state().x;
    REQUIRE(x > -0.015);   // pressed some micrometres deep
    REQUIRE(e.apply(SimCommand::xi(-0.015)));
    CHECK(e.state().x == x);   // before: pulled out to x = xI, a 15 um jump at every frame
    REQUIRE(e.apply(SimCommand::paused(true)));
    REQUIRE(e.apply(SimCommand::xi(-0.018)));
    CHECK(e.params().xI == -0.018);
    CHECK(e.state().x <= -0.018 + (x + 0.015) + 1e-15);
}

TEST_CASE("the bumper and the cart: the rig's badge and the status bar read the contact from one function") {
    const Params c = make_version("A1C"), h = make_version("A1H");
    CHECK(std::string(contact_label(c, Regime::Free, 3.0)) == "I  on the compliant bumper");
    CHECK(std::string(contact_label(c, Regime::Free, 0.0)) == "I  free flight");
    CHECK(std::string(contact_label(h, Regime::Contact, 3.0)) == "III  permanent contact");
    CHECK(std::string(contact_label(h, Regime::Sticking, 0.0)) == "II  sticking (impact)");
    CHECK(in_contact(c, Regime::Free, 3.0));
    CHECK(!in_contact(h, Regime::Free, 0.0));
    // A cart pressed onto the compliant bumper: its samples say so, and so does the label.
    VectorSink sink;
    EngineConfig cfg = config("A1C", 9.0);
    cfg.xI = -0.015;
    SimEngine e(cfg, &sink);
    e.advance_to(2.0);
    const SimMsg& last = sink.msgs.back();
    CHECK(last.force > 0);
    CHECK(std::string(contact_label(e.params(), last.regime, last.force)) == "I  on the compliant bumper");
}

TEST_CASE("the mouse: SetState keeps t and phi, bumps the epoch, and is refused beyond the bumper") {
    VectorSink sink;
    SimEngine e(config("A1H", 9.0), &sink);
    e.advance_to(1.3);
    const double t = e.state().t, phi = e.phi();
    const auto epoch = e.epoch();
    REQUIRE(e.apply(SimCommand::set_state(-0.005, 0.1)));
    CHECK(e.state().t == t);
    CHECK(e.phi() == phi);
    CHECK(e.state().x == -0.005);
    CHECK(e.state().v == 0.1);
    CHECK(e.epoch() == epoch + 1);
    CHECK(sink.msgs.back().x == -0.005);   // shown at once
    // Beyond the rigid bumper at xI = 0: put on it.
    REQUIRE(e.apply(SimCommand::set_state(0.004, 0.0)));
    CHECK(e.state().x == 0.0);
    // What the UI checks before sending, and says in a toast.
    const PickedState beyond = pick_state(0.004, 0.0, 0.0, true);
    CHECK(beyond.x == 0.0);
    CHECK(beyond.note.find("bumper") != std::string::npos);
    const PickedState rail = pick_state(-0.3, 5.0, 0.0, true);
    CHECK(rail.x == -kMaxAbsStateX);
    CHECK(rail.v == kMaxAbsStateV);
    CHECK(rail.note.find("rail") != std::string::npos);
    CHECK(pick_state(-0.004, 0.02, 0.0, true).note.empty());
    CHECK(pick_state(0.004, 0.0, 0.0, false).x == 0.004);   // no bumper, nothing in the way
}

TEST_CASE("the mouse: a held cart stays where the hand is while time goes on; let go, it runs from there") {
    VectorSink sink;
    SimEngine e(config("A1H", 9.0), &sink);
    e.advance_to(1.0);
    REQUIRE(e.apply(SimCommand::hold(-0.004)));
    sink.msgs.clear();
    e.advance_to(2.0);
    CHECK(e.state().t == doctest::Approx(2.0));
    CHECK(e.held());
    const auto held = sink.of(MsgKind::Sample);
    REQUIRE(held.size() > 100);
    for (const auto& m : held) {
        CHECK(m.x == -0.004);
        CHECK(m.v == 0.0);
    }
    CHECK(sink.of(MsgKind::Section).empty());   // the map starts afresh when the cart is let go
    REQUIRE(e.apply(SimCommand::set_state(-0.004, 0.0)));
    CHECK(!e.held());
    e.advance_to(2.5);
    CHECK(e.state().x != -0.004);   // the magnets pull it off the hilltop's slope
}

TEST_CASE("the mouse: a plain click sets the state only when no double-click (view reset) follows") {
    ClickDelay d;
    d.click(0.001, 0.02, 10.0);
    CHECK(!d.due(10.1, 0.3));
    const auto p = d.due(10.31, 0.3);
    REQUIRE(p);
    CHECK(p->first == 0.001);
    CHECK(p->second == 0.02);
    CHECK(!d.due(11.0, 0.3));   // once
    d.click(0.001, 0.02, 20.0);   // the first click of a double-click ...
    d.double_clicked();           // ... the second press
    d.click(0.001, 0.02, 20.2);   // ... and its release
    CHECK(!d.due(21.0, 0.3));
}

namespace {
// The cart and its companion advanced in lockstep as the sim thread does; returns |dx| at the end and at
// the largest.
struct Pair {
    VectorSink a, b;
    SimEngine cart, companion;
    Pair(const std::string& model, double omega, const std::string& other, double dx)
        : cart(config(model, omega), &a), companion(config(model, omega), &b) {
        cart.advance_to(40.0);   // settled on the attractor
        companion.set_source(1);
        REQUIRE(companion.restart_from(cart, other, dx));
    }
    void run_to(double t_end) {
        for (double t = cart.state().t; t < t_end;) {
            t = std::min(t_end, t + 0.05);
            const double reached = cart.advance_to(t);
            companion.advance_to(reached);
        }
    }
};
}  // namespace

TEST_CASE("companion: a twin 1 um apart parts by orders of magnitude in chaos and not on a period-1 orbit") {
    {
        Pair chaos("A1H", 18.0, "A1H", kTwinOffset);
        CHECK(chaos.companion.state().x - chaos.cart.state().x == doctest::Approx(kTwinOffset).epsilon(1e-6));
        CHECK(chaos.companion.state().t == chaos.cart.state().t);
        CHECK(chaos.companion.phi() == chaos.cart.phi());
        chaos.run_to(100.0);
        // Samples on one grid: every companion sample has the cart's at the same instant.
        History<SimMsg> cart_h(std::size_t{1} << 17);
        for (const auto& m : chaos.a.msgs)
            if (m.kind == MsgKind::Sample && m.t >= 40.0) cart_h.push(m);
        CompanionTrack track;
        for (const auto& m : chaos.b.msgs) {
            CHECK(m.source == 1);
            track.on_msg(m, cart_h);
        }
        REQUIRE(track.separation().size() > 1000);
        CHECK(track.separation_start() == doctest::Approx(kTwinOffset).epsilon(0.01));
        CHECK(track.separation_max() > 1e-3);   // three decades and more
        CHECK(chaos.companion.state().t == chaos.cart.state().t);
    }
    {
        Pair calm("A1H", 9.0, "A1H", kTwinOffset);
        calm.run_to(100.0);
        CHECK(std::abs(calm.companion.state().x - calm.cart.state().x) < kTwinOffset);   // it converges
    }
}

TEST_CASE("companion: a ghost under another impact law starts from the same state and keeps its own law") {
    Pair p("A1C", 18.0, "A1G", 0.0);
    CHECK(p.companion.params().name == "A1G");
    CHECK(p.companion.state().x == p.cart.state().x);
    CHECK(p.companion.state().v == p.cart.state().v);
    p.run_to(70.0);
    CHECK(std::abs(p.companion.state().x - p.cart.state().x) > 1e-4);   // C and G part
    CHECK(!p.companion.restart_from(p.cart, "A9Q", 0.0));              // an unknown model changes nothing
    CHECK(p.companion.params().name == "A1G");
}

TEST_CASE("companion: the sim thread runs it in lockstep and restarts it with the cart") {
    EngineConfig cfg = config("A1H", 18.0);
    cfg.speed = 20.0;
    SimThread th(cfg);
    th.start();
    REQUIRE(th.send(SimCommand::companion(CompanionMode::Twin)));
    std::vector<SimMsg> got;
    auto drain = [&] { th.samples().drain([&](const SimMsg& m) { got.push_back(m); }); };
    for (int i = 0; i < 30; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        drain();
    }
    REQUIRE(th.send(SimCommand::reset(-0.011, 0.0)));
    for (int i = 0; i < 10; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        drain();
    }
    th.stop();
    drain();
    double last_cart = -1, last_comp = -1;
    bool comp_reset = false;
    for (const auto& m : got) {
        if (m.kind != MsgKind::Sample) continue;
        if (m.source == 0) last_cart = m.t;
        else {
            if (m.t < last_comp) comp_reset = true;   // restarted at t = 0 with the cart
            last_comp = m.t;
        }
    }
    CHECK(last_cart > 0.1);
    CHECK(last_comp == doctest::Approx(last_cart).epsilon(1e-9));   // the same sim time
    CHECK(comp_reset);
}

TEST_CASE("grazing monitor: the gap to the bumper over a period, against a fine sampling of the orbit") {
    const Params p = [] {
        Params q = make_version("A1H");
        q.xI = 0.0;
        return q;
    }();
    const Drive d(9.0);
    State s;
    s.x = -0.011;
    Simulator::make_consistent(p, d, s);
    Simulator sim;
    sim.advance(p, d, s, 30.0);   // on the period-1 orbit
    struct Obs final : Observer {
        GrazingMonitor mon;
        const Params* p = nullptr;
        std::vector<GrazingMonitor::Period> periods;
        std::vector<double> fine_max;   // max x of the fine samples between sections
        double running = -1;
        void on_piece(const Piece& piece) override {
            mon.on_piece(piece, p->xI, false);
            for (double t = piece.t0; t <= piece.t1; t += 2e-6) running = std::max(running, piece.at(t)[0]);
            running = std::max(running, piece.at(piece.t1)[0]);
        }
        void on_section(const SectionPoint& sp) override {
            GrazingMonitor::Period g;
            if (mon.on_section(sp.t, p->xI, g)) {
                periods.push_back(g);
                fine_max.push_back(running);
            }
            running = -1;
        }
    } obs;
    obs.p = &p;
    sim.advance(p, d, s, 36.0, &obs);
    REQUIRE(obs.periods.size() >= 7);
    for (std::size_t i = 0; i < obs.periods.size(); ++i) {
        const auto& g = obs.periods[i];
        CHECK(g.x_max == doctest::Approx(obs.fine_max[i]).epsilon(1e-7));
        CHECK(g.distance == doctest::Approx(p.xI - g.x_max));
        CHECK(g.distance > 0.001);   // period 1 in the left well: clear of the hilltop
        CHECK(g.impacts == 0);
        CHECK(std::isnan(g.v_impact));
    }
}

TEST_CASE("grazing monitor: impact velocity (rigid) and depth and entry velocity (compliant) from the engine") {
    for (const std::string model : {"A1G", "A1C"}) {
        CAPTURE(model);
        VectorSink sink;
        SimEngine e(config(model, 18.0), &sink);   // chaos: the cart keeps hitting the bumper at x = 0
        e.advance_to(60.0);
        const auto g = sink.of(MsgKind::Grazing);
        REQUIRE(g.size() > 100);
        int with_impacts = 0;
        for (const auto& m : g) {
            if (m.energy < 0.5) {
                if (model == "A1G") CHECK(m.x <= 1e-12);   // no impact: clear of the bumper, or resting on it
                continue;
            }
            ++with_impacts;
            CHECK(m.v > 0.0);   // towards the bumper
            if (model == "A1G") {
                CHECK(std::abs(m.x) < 1e-12);   // touched it, never beyond (but for the last bit)
                CHECK(m.force == 0.0);
            } else {
                CHECK(m.force > 0.0);   // pressed into the compliant bumper ...
                CHECK(m.force < 1e-3);
                CHECK(m.x == doctest::Approx(m.force));   // ... as deep as x went beyond xI = 0
            }
        }
        CHECK(with_impacts > 10);
        // Rigid: the period's v- is the last impact record's before the section.
        if (model == "A1G") {
            double last_v = 0;
            std::size_t checked = 0;
            for (const auto& m : sink.msgs) {
                if (m.kind == MsgKind::Impact) last_v = m.force;
                if (m.kind == MsgKind::Grazing && m.energy > 0.5) {
                    CHECK(m.v == last_v);
                    ++checked;
                }
            }
            CHECK(checked > 10);
        }
    }
}
