// The UI's end of the command ring: a command the full ring refuses is held and resent, in order; a slider's
// values give way to each other so the last one lands; past the backlog's capacity a loss is counted.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <thread>
#include <vector>

#include "../../app/gui/sim/command_link.hpp"
#include "../../app/gui/sim/sim_thread.hpp"
#include "engine_fixtures.hpp"

using namespace impactlab::gui;
using namespace impactlab::gui::testing;

namespace {

// A thread that is not started, so nothing takes its commands, its ring filled through a link.
struct Stalled {
    SimThread th{[] {
        EngineConfig cfg = config("A1H", 9.0);
        cfg.speed = 20.0;
        return cfg;
    }()};
    CommandLink link;
    Stalled() {
        link.attach(&th);
        for (std::size_t i = 0; i < SimThread::kCommandCapacity; ++i) REQUIRE(link.send(SimCommand::speed(20.0)));
        REQUIRE(link.waiting() == 0);
    }
};

// Frames: the held commands resent until none is left, then the samples read until one runs at `omega`.
bool lands(SimThread& th, CommandLink& link, double omega) {
    for (int frame = 0; frame < 400 && !link.flush(); ++frame) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    if (link.waiting() > 0) return false;
    bool seen = false;
    for (int frame = 0; frame < 400 && !seen; ++frame) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        th.samples().drain([&](const SimMsg& m) { seen = seen || (m.kind == MsgKind::Sample && std::abs(m.omega - omega) < 1e-12); });
    }
    return seen;
}

}  // namespace

TEST_CASE("command link: a value gives way only to a newer value of the same setting") {
    CHECK(supersedes(SimCommand::omega(2), SimCommand::omega(1)));
    CHECK(supersedes(SimCommand::set_param("k", 2), SimCommand::set_param("k", 1)));
    CHECK(!supersedes(SimCommand::set_param("k", 2), SimCommand::set_param("c", 1)));
    CHECK(!supersedes(SimCommand::xi(0.001), SimCommand::omega(1)));
    CHECK(!supersedes(SimCommand::reset(0, 0), SimCommand::reset(0, 0)));   // each reset counts
    CHECK(!supersedes(SimCommand::step_period(), SimCommand::step_period()));
}

TEST_CASE("command link: a full ring holds the slider's values back and the last one lands") {
    Stalled s;
    auto& [th, link] = s;
    // The slider dragged over 100 frames, a reset in the middle: one omega held (the newest), and the reset.
    for (int i = 1; i <= 100; ++i) {
        CHECK(link.send(SimCommand::omega(9.0 + 0.01 * i)));
        if (i == 50) CHECK(link.send(SimCommand::reset(-0.011, 0.0)));
    }
    CHECK(link.waiting() == 2);
    CHECK(link.deferred() == 101);
    CHECK(link.lost() == 0);
    CHECK(th.status().commands_dropped == 1);   // the first refusal; the rest queued behind it
    CHECK(!link.flush());                       // still full: a resend is not a new refusal
    CHECK(th.status().commands_dropped == 1);
    th.start();
    CHECK(lands(th, link, 9.0 + 0.01 * 100));
    th.stop();
}

TEST_CASE("command link: past the backlog's capacity a command is lost and counted; a slider's value still lands") {
    Stalled s;
    auto& [th, link] = s;
    CHECK(link.send(SimCommand::omega(11.0)));
    for (std::size_t i = 1; i < CommandLink::kBacklogCapacity; ++i) CHECK(link.send(SimCommand::reset(-0.011, 0.0)));
    CHECK(link.waiting() == CommandLink::kBacklogCapacity);
    CHECK(!link.send(SimCommand::step_period()));
    CHECK(link.lost() == 1);
    CHECK(link.send(SimCommand::omega(12.0)));   // takes the place of the held 11.0
    CHECK(link.lost() == 1);
    CHECK(link.waiting() == CommandLink::kBacklogCapacity);
    th.start();
    CHECK(lands(th, link, 12.0));
    th.stop();
}

TEST_CASE("command link: with no thread attached every command is held") {
    CommandLink link;
    CHECK(link.send(SimCommand::omega(10.0)));
    CHECK(link.waiting() == 1);
    CHECK(!link.flush());
}
