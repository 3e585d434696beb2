// Replay (app/gui/replay): the sample shown at a time, the clamping to what the history still holds, play
// back at a rate, the history rewound for the panels and truncated by "continue from here", the clip's
// frame plan; the clip writer's folder (complete or absent, never half-written); the engine's Restart.
#include <doctest/doctest.h>

#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include "../../app/gui/files/clip_writer.hpp"
#include "../../app/gui/sim/replay.hpp"
#include "../../app/gui/sim/sim_engine.hpp"

using namespace impactlab;
using namespace impactlab::gui;
namespace fs = std::filesystem;

namespace {
// Samples at t = t0 + k * dt, x = t (so a sample names its own time).
void fill(History<SimMsg>& h, double t0, double dt, int n) {
    for (int k = 0; k < n; ++k) {
        SimMsg m;
        m.t = t0 + dt * k;
        m.x = m.t;
        h.push(m);
    }
}

fs::path fresh_dir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("impactlab-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}
}  // namespace

TEST_CASE("replay: the sample at a time is the newest at or before it, clamped to the history") {
    History<SimMsg> h(16);
    fill(h, 1.0, 0.5, 10);   // 1.0 .. 5.5
    CHECK(sample_at(h, 1.0) == 0);
    CHECK(sample_at(h, 1.49) == 0);
    CHECK(sample_at(h, 1.5) == 1);
    CHECK(sample_at(h, 3.2) == 4);
    CHECK(sample_at(h, -7) == 0);
    CHECK(sample_at(h, 99) == 9);
    fill(h, 6.0, 0.5, 10);   // overwrites the 4 oldest: 3.0 .. 10.5 left
    CHECK(held_span(h).first == doctest::Approx(3.0));
    CHECK(held_span(h).last == doctest::Approx(10.5));
    CHECK(h[sample_at(h, 2.0)].t == doctest::Approx(3.0));
}

TEST_CASE("replay: enter at the newest sample, scrub, play at a rate up to the end, leave") {
    History<SimMsg> h(64);
    Replay r;
    CHECK_FALSE(r.enter(h, false));   // nothing recorded
    CHECK_FALSE(r.active());
    fill(h, 0.0, 0.1, 50);            // 0 .. 4.9
    REQUIRE(r.enter(h, false));
    CHECK(r.update(h, 0.016) == 49);
    CHECK(r.at_end());
    r.seek(1.0);
    CHECK(h[r.update(h, 0.016)].t == doctest::Approx(1.0));   // paused: the wall time does not move it
    r.set_rate(0.25);
    r.set_playing(true);
    CHECK(h[r.update(h, 2.0)].t == doctest::Approx(1.5));     // 2 s of wall time at 0.25x
    r.set_rate(1.0);
    r.update(h, 100.0);                                        // runs into the end: stops there
    CHECK(r.cursor() == doctest::Approx(4.9));
    CHECK_FALSE(r.playing());
    r.seek(-50);
    CHECK(r.update(h, 0) == 0);                                // clamped to the oldest
    r.set_rate(1e9);
    CHECK(r.rate() == Replay::kMaxRate);
    CHECK_FALSE(r.leave());                                    // the simulation was running before
    CHECK_FALSE(r.active());
}

TEST_CASE("replay: the history emptied under it (a reset) ends replay; overwritten samples clamp the cursor") {
    History<SimMsg> h(32);
    fill(h, 0.0, 1.0, 20);
    Replay r;
    REQUIRE(r.enter(h, true));
    r.seek(2.0);
    r.update(h, 0);
    fill(h, 20.0, 1.0, 30);   // the sim ran on: samples up to t = 17 are gone
    CHECK(h[r.update(h, 0)].t == doctest::Approx(18.0));
    h.clear();
    r.update(h, 0);
    CHECK_FALSE(r.active());
}

TEST_CASE("history: rewound for the panels, revealed after; dropping the newest starts a generation") {
    History<SimMsg> h(8);
    fill(h, 0.0, 1.0, 12);   // 4 .. 11 held
    const auto seq3 = h.seq_of(3);
    h.rewind_to(4);
    CHECK(h.size() == 4);
    CHECK(h.back().t == doctest::Approx(7.0));
    CHECK(h.seq_of(3) == seq3);          // the same sequence numbers: incremental drawing stays valid
    CHECK(h.seq_of(h.size()) == seq3 + 1);
    h.rewind_to(2);                      // a second rewind starts from the whole history
    CHECK(h.size() == 2);
    h.reveal();
    CHECK(h.size() == 8);
    CHECK(h.back().t == doctest::Approx(11.0));
    const auto gen = h.generation();
    h.drop_newest(3);
    CHECK(h.size() == 5);
    CHECK(h.back().t == doctest::Approx(8.0));
    CHECK(h.generation() == gen + 1);
    SimMsg m;
    m.t = 8.5;
    h.push(m);
    CHECK(h.back().t == doctest::Approx(8.5));
    CHECK(h.seq_of(h.size() - 1) == seq3 + 2);
}

TEST_CASE("clip plan: the last seconds before the cursor at fps and rate, limited to the history") {
    History<SimMsg> h(1024);
    fill(h, 0.0, 0.01, 1000);   // 0 .. 9.99 s
    ClipPlan p = plan_clip(h, 9.0, 2.0, 30.0, 1.0);
    CHECK(p.t0 == doctest::Approx(7.0));
    CHECK(p.t1 == doctest::Approx(9.0));
    CHECK(p.frames == 61);
    CHECK(p.time_of(p.frames - 1) == doctest::Approx(9.0));
    p = plan_clip(h, 9.0, 2.0, 30.0, 0.25);   // slow motion: four times the frames
    CHECK(p.frames == 241);
    p = plan_clip(h, 1.0, 5.0, 30.0, 1.0);    // more than the history holds before t = 1
    CHECK(p.t0 == doctest::Approx(0.0));
    CHECK(p.frames == 31);
    CHECK_THROWS_AS(plan_clip(h, 9.0, 0.0, 30.0, 1.0), std::invalid_argument);
    CHECK_THROWS_AS(plan_clip(h, 9.0, 2.0, 30.0, -1.0), std::invalid_argument);
    CHECK_THROWS_AS(plan_clip(h, 9.0, 9.0, 30.0, 0.02), std::invalid_argument);   // 13,500 frames
    History<SimMsg> empty(4);
    CHECK_THROWS_AS(plan_clip(empty, 0.0, 1.0, 30.0, 1.0), std::invalid_argument);
}

TEST_CASE("clip writer: numbered PNG frames in a folder that appears whole; errors leave nothing") {
    const fs::path out = fresh_dir("clip");
    const int w = 8, h = 6;
    std::vector<unsigned char> rgb(static_cast<std::size_t>(w * h * 3));
    for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<unsigned char>(i * 7);
    std::string err, summary;
    {
        ClipWriter cw;
        REQUIRE(cw.begin(out.string(), "clip-a", w, h, 30.0, false, err));
        CHECK_FALSE(fs::exists(out / "clip-a"));   // not before it is complete
        for (int k = 0; k < 3; ++k) REQUIRE(cw.add_frame(rgb.data(), err));
        REQUIRE(cw.finish(summary, err));
        CHECK(summary == "wrote 3 PNG frames to " + (out / "clip-a").string());
    }
    CHECK(fs::exists(out / "clip-a" / "frame-00001.png"));
    CHECK(fs::exists(out / "clip-a" / "frame-00003.png"));
    CHECK_FALSE(fs::exists(out / "clip-a" / "frame-00004.png"));
    {
        ClipWriter cw;   // an export abandoned half-way (the window closed): no trace
        REQUIRE(cw.begin(out.string(), "clip-b", w, h, 30.0, false, err));
        REQUIRE(cw.add_frame(rgb.data(), err));
    }
    std::size_t entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(out)) ++entries;
    CHECK(entries == 1);   // clip-a only: no clip-b, no staging folder
    ClipWriter cw;
    CHECK_FALSE(cw.begin(out.string(), "clip-a", w, h, 30.0, false, err));   // exists: never overwritten
    CHECK(err.find("already exists") != std::string::npos);
    CHECK_FALSE(cw.begin((out / "no" / "such").string(), "c", w, h, 30.0, false, err));
    CHECK(err.find("is not a folder") != std::string::npos);
    if (::geteuid() != 0) {   // root writes anywhere
        fs::create_directories(out / "ro");
        fs::permissions(out / "ro", fs::perms::owner_read | fs::perms::owner_exec);
        CHECK_FALSE(cw.begin((out / "ro").string(), "c", w, h, 30.0, false, err));
        CHECK(err.find("cannot write in") != std::string::npos);
        fs::permissions(out / "ro", fs::perms::owner_all);
    }
    CHECK(find_on_path("sh") != "");
    CHECK(find_on_path("impactlab-no-such-tool") == "");
    fs::remove_all(out);
}

TEST_CASE("engine: restart continues from a replayed instant (t, phi, x, v) with a new epoch") {
    SimEngine e(EngineConfig{});
    e.advance_to(3.0);
    const std::uint32_t epoch = e.epoch();
    REQUIRE(e.apply(SimCommand::restart(-0.009, 0.05, 1.25, 11.0)));
    CHECK(e.epoch() == epoch + 1);
    CHECK(e.state().t == doctest::Approx(1.25));
    CHECK(e.state().x == doctest::Approx(-0.009));
    CHECK(e.state().v == doctest::Approx(0.05));
    CHECK(e.phi() == doctest::Approx(11.0));
    CHECK(e.drive().omega(1.25) == doctest::Approx(9.0));   // the rate it ran at
    // The next section is the first 2 pi n after phi = 11.
    CHECK(e.state().next_section == 2);
    e.advance_to(2.0);
    CHECK(e.state().t == doctest::Approx(2.0));
}
