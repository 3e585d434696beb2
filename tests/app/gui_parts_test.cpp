// The visualiser's other GL-free parts: the UI's history ring and CSV export, command-line options, and
// the presets (each must land on the attractor it names).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "../../app/gui/sim/history.hpp"
#include "../../app/gui/window/options.hpp"
#include "../../app/gui/sim/presets.hpp"
#include "impactlab/params.hpp"
#include "impactlab/sweep.hpp"

using namespace impactlab;
using namespace impactlab::gui;

namespace {
// What parse_options says of args: its error message, or "accepted".
std::string error(const std::vector<std::string>& args) {
    try {
        parse_options(args);
    } catch (const OptionsError& e) {
        return e.what();
    }
    return "accepted";
}
}  // namespace

TEST_CASE("history: overwrites the oldest, indexes oldest first, finds times") {
    History<int> h(4);
    CHECK(h.empty());
    for (int i = 0; i < 6; ++i) h.push(i);
    CHECK(h.size() == 4);
    CHECK(h[0] == 2);
    CHECK(h.back() == 5);
    CHECK(h.lower_bound(4.0, [](int v) { return static_cast<double>(v); }) == 2);
    CHECK(h.lower_bound(9.0, [](int v) { return static_cast<double>(v); }) == 4);
    CHECK(h.seq_of(0) == 2);   // sequence numbers count every push
    CHECK(h.seq_of(3) == 5);
    const auto gen = h.generation();
    h.clear();
    CHECK(h.size() == 0);
    CHECK(h.generation() == gen + 1);
    h.push(7);
    CHECK(h.seq_of(0) == 6);   // never reused after a clear
    for (int i = 8; i < 11; ++i) h.push(i);   // 7 8 9 10
    h.drop_oldest(3);
    CHECK(h.size() == 1);
    CHECK(h[0] == 10);
    CHECK(h.seq_of(0) == 9);   // the sequence numbers of what is left do not change
    h.drop_oldest(5);
    CHECK(h.empty());
    CHECK_THROWS_AS(History<int>(6), std::invalid_argument);
    CHECK_THROWS_AS(History<int>(0), std::invalid_argument);
}

TEST_CASE("history: trajectory and section CSV files have a header and one row per record") {
    History<SimMsg> traj(8), secs(8);
    for (int i = 0; i < 3; ++i) {
        SimMsg m;
        m.t = 0.001 * i;
        m.x = -0.01;
        traj.push(m);
    }
    SimMsg s;
    s.kind = MsgKind::Section;
    s.phi = 2 * 3.141592653589793 * 7;
    secs.push(s);
    const auto dir = std::filesystem::temp_directory_path();
    const std::string a = (dir / "impactlab_gui_test_traj.csv").string(), b = (dir / "impactlab_gui_test_secs.csv").string();
    REQUIRE(write_trajectory_csv(a, traj, "A1H"));
    REQUIRE(write_sections_csv(b, secs, "A1H"));
    auto lines = [](const std::string& path) {
        std::ifstream in(path);
        std::vector<std::string> out;
        for (std::string l; std::getline(in, l);)
            if (!l.empty() && l[0] != '#') out.push_back(l);
        return out;
    };
    const auto ta = lines(a), tb = lines(b);
    REQUIRE(ta.size() == 4);
    CHECK(ta[0] == "t,x,v,phi,omega,regime,bumper_force,energy,epoch");
    REQUIRE(tb.size() == 2);
    CHECK(tb[0] == "n,t,x,v,omega,regime");
    CHECK(tb[1].rfind("7,", 0) == 0);
    std::remove(a.c_str());
    std::remove(b.c_str());
    CHECK_FALSE(write_trajectory_csv("/nonexistent-dir/x.csv", traj, "A1H"));
}

TEST_CASE("options: the fixed flags, values, and clear errors for bad ones") {
    const Options o = parse_options({"--frames", "120", "--screenshot", "out.png", "--model", "A1G", "--omega", "18",
                                     "--xI", "-0.004", "--size", "800x600", "--theme", "light"});
    CHECK(o.frames == 120);
    CHECK(o.screenshot == "out.png");
    CHECK(o.model == "A1G");
    CHECK(o.omega == 18.0);
    CHECK(o.xI == -0.004);
    CHECK(o.width == 800);
    CHECK(o.height == 600);
    CHECK(o.light);
    CHECK_THROWS_AS(parse_options({"--bogus"}), OptionsError);
    CHECK_THROWS_AS(parse_options({"--omega"}), OptionsError);
    CHECK_THROWS_AS(parse_options({"--omega", "fast"}), OptionsError);
    CHECK_THROWS_AS(parse_options({"--omega", "31"}), OptionsError);
    CHECK_THROWS_AS(parse_options({"--model", "A2Q"}), OptionsError);
    CHECK_THROWS_AS(parse_options({"--size", "big"}), OptionsError);
    CHECK_THROWS_AS(parse_options({"--screenshot", "x.png"}), OptionsError);   // needs --frames
    try {
        parse_options({"--speed", "1000"});
        FAIL("accepted --speed 1000");
    } catch (const OptionsError& e) {
        CHECK(std::string(e.what()).find("--speed") != std::string::npos);
    }
}

TEST_CASE("options: the W0:W1 ranges and the ramp's W1:RATE, with the flag in every error") {
    const Options o = parse_options({"--bif-range", "8:14", "--bif-box", "12:12.5", "--bif-zoom", "0:25", "--ramp",
                                     "20:0.05"});
    CHECK(o.bif_range_lo == 8.0);
    CHECK(o.bif_range_hi == 14.0);
    CHECK(o.bif_box_lo == 12.0);
    CHECK(o.bif_box_hi == 12.5);
    CHECK(o.bif_zoom_hi == 25.0);
    CHECK(o.ramp_to == 20.0);
    CHECK(o.ramp_rate == 0.05);
    CHECK(error({"--bif-range", "14:8"}) == "--bif-range: 14:8 is empty (W0 < W1 wanted)");
    CHECK(error({"--bif-box", "12:12.01"}) == "--bif-box: 12:12.01 is too narrow (W0 < W1 by at least 0.02 rad/s wanted)");
    CHECK(error({"--bif-zoom", "12"}) == "--bif-zoom: '12' is not W0:W1");
    CHECK(error({"--ramp", "11"}).find("--ramp: '11' is not W1:RATE") == 0);
    CHECK(error({"--ramp", "11:5"}).find("--ramp") == 0);    // rate beyond 2 rad/s per s
    CHECK(error({"--ramp", "40:0.1"}).find("--ramp") == 0);  // target beyond 30 rad/s
}

TEST_CASE("presets: every model's presets land on the attractor they name") {
    for (const char* name : {"A1H", "A1G", "A1C", "A1C1", "A3H", "A3G", "A3C", "A3C1"}) {
        const std::string model = name;
        const Params p = make_version(model);
        const auto list = presets_for(model);
        REQUIRE(list.size() == 4);
        for (const Preset& pr : list) {
            CAPTURE(model);
            CAPTURE(pr.label);
            State s;
            s.x = pr.x0;
            // As the app's reset does: from rest at x0, t = 0, phi = 0.
            const auto pts = poincare_section(p, pr.omega, 64, 400, s);
            // The period is the smallest k after which every point recurs in x and v (20 um, 0.2 mm/s):
            // counting clusters in x alone read A3H's period 6 (three close pairs) as 5.
            int period = 17;
            for (std::size_t k = 1; k <= 16 && period > 16; ++k) {
                bool recurs = true;
                for (std::size_t i = k; i < pts.size() && recurs; ++i)
                    recurs = std::abs(pts[i].x - pts[i - k].x) < 2e-5 && std::abs(pts[i].v - pts[i - k].v) < 2e-4;
                if (recurs) period = static_cast<int>(k);
            }
            if (pr.period > 0) CHECK(period == pr.period);
            else CHECK(period > 16);
        }
    }
}

TEST_CASE("options: a curve start outside the physical range and a --param without a value are refused, naming key and value") {
    CHECK(error({"--plane-fold", "1e-300,-0.0157,0.0023"}).find("--plane-fold: '1e-300,-0.0157,0.0023' is neither auto nor") == 0);
    CHECK(error({"--plane-grazing", "1e300,1e300,0"}).find("--plane-grazing: '1e300,1e300,0'") == 0);
    CHECK(error({"--param", "xI="}) == "--param xI: '' is not a number");
    CHECK(error({"--phi0", "1e-320"}) == "accepted");   // a subnormal is a number (an underflow, not an overflow)
}
