// Session files (app/gui/session): the round trip save -> load -> save gives the same text; a partial file
// changes only what it names; every bad file (missing, not JSON, unknown key, wrong type, omega or xI out
// of range, unknown model) is refused with the file, the key (or line) and the problem named.
#include <doctest/doctest.h>

#include <ctime>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

#include "../../app/gui/files/session.hpp"

using namespace impactlab::gui;
namespace fs = std::filesystem;

namespace {
Session sample() {
    Session s;
    s.model = "A3G";
    s.omega = 12.345678901234567;
    s.xI = -0.0015;
    s.speed = 0.25;
    s.paused = true;
    s.t = 1234.5678;
    s.x = -0.0107;
    s.v = 0.0321;
    s.phi = 15240.1;
    s.dark = false;
    s.ui_scale = 1.75;
    s.trail_periods = 20;
    s.strip_window = 2.5;
    s.views = {{"##bif", 10.5, 13.0, -0.015, 0.001}, {"##phase", -0.02, 0.001, -0.3, 0.3}};   // by id, as saved
    s.show_data = false;
    s.show_help = true;
    s.bif_protocol = "ef";
    s.bif_steps = 120;
    s.companion = "ghost";
    s.ghost_impact = "C1";
    s.presentation = true;
    s.hidden = {"controls", "strip"};
    s.maximised = "poincare";
    s.presentation_plot = "bifurcation";
    s.magnify = 2.5;
    s.magnify_presentation = 6;
    return s;
}

// The error message parse_session gives for `text` ("" if it parses).
std::string error_of(const std::string& text) {
    try {
        parse_session(text, Session{}, "s.json");
    } catch (const SessionError& e) {
        return e.what();
    }
    return "";
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }
}  // namespace

TEST_CASE("session: save, load, save again gives the same JSON, and the same state") {
    const fs::path dir = fs::temp_directory_path() / ("impactlab-session-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string a = (dir / "a.json").string(), b = (dir / "b.json").string();
    const Session s = sample();
    save_session(s, a);
    const Session back = load_session(a, Session{});
    CHECK(back == s);
    save_session(back, b);
    std::ifstream fa(a), fb(b);
    const std::string ta((std::istreambuf_iterator<char>(fa)), {}), tb((std::istreambuf_iterator<char>(fb)), {});
    CHECK(ta == tb);
    CHECK(has(ta, "\"format\": \"impactlab-gui session\""));
    // No partial file left beside them.
    std::size_t files = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++files;
    CHECK(files == 2);
    // An unwritable place: a SessionError naming the file, nothing written.
    CHECK_THROWS_WITH_AS(save_session(s, (dir / "no" / "x.json").string()),
                         doctest::Contains("x.json: cannot write it"), SessionError);
    fs::remove_all(dir);
}

TEST_CASE("session: absent keys keep the base state; a partial file changes only what it names") {
    Session base = sample();
    const Session s = parse_session(R"({"format": "impactlab-gui session", "omega": 11.5,
                                        "view": {"theme": "dark"}})", base, "p.json");
    CHECK(s.omega == 11.5);
    CHECK(s.dark);
    base.omega = 11.5;
    base.dark = true;
    CHECK(s == base);
    // The data file: null clears it.
    base.data = "somewhere.csv";
    CHECK(parse_session(R"({"format": "impactlab-gui session", "data": null})", base, "p.json").data.empty());
}

TEST_CASE("session: bad files are refused naming the file, the key or line, and the problem") {
    CHECK(has(error_of("{\"format\": \"impactlab-gui session\",\n \"omega\": 45}"), "s.json: key 'omega': 45 is out of range [0, 30] rad/s"));
    CHECK(has(error_of(R"({"format": "impactlab-gui session", "xI": 0.5})"), "key 'xI': 0.5 is out of range [-0.02, 0.02] m"));
    CHECK(has(error_of(R"({"format": "impactlab-gui session", "omega": "fast"})"), "key 'omega': expected a number, got string"));
    CHECK(has(error_of(R"({"format": "impactlab-gui session", "model": "A9Z"})"), "key 'model': unknown model version 'A9Z' (one of"));
    CHECK(has(error_of(R"({"format": "impactlab-gui session", "colour": 3})"), "s.json: key 'colour': unknown key"));
    CHECK(has(error_of(R"({"format": "impactlab-gui session", "layout": {"hidden": ["rig", "legend"]}})"),
              "key 'layout.hidden': \"legend\" is not a panel (one of controls, rig,"));
    CHECK(has(error_of(R"({"format": "impactlab-gui session", "layout": {"maximised": "controls"}})"),
              "key 'layout.maximised': \"controls\" is not a panel"));
    CHECK(has(error_of(R"({"format": "impactlab-gui session", "layout": {"presentation_plot": "rig"}})"),
              "key 'layout.presentation_plot'"));
    CHECK(has(error_of(R"({"format": "impactlab-gui session", "layout": {"magnify": [1, 40]}})"),
              "key 'layout.magnify': [1, 40] is outside [1, 10]"));
    CHECK(has(error_of(R"({"format": "impactlab-gui session", "layout": {"mode": "cinema"}})"), "key 'layout.mode'"));
    CHECK(has(error_of(R"({"format": "impactlab-gui session", "view": {"zoom": {"##phase": {"x": [1, 0], "y": [0, 1]}}}})"),
              "key 'view.zoom.##phase.x': [1, 0] is empty"));
    CHECK(has(error_of(R"({"format": "impactlab-gui session", "view": {"scale": 2}})"), "key 'view.scale': unknown key"));
    CHECK(has(error_of(R"({"format": "impactlab-gui session", "state": {"x": 0.2}})"), "key 'state.x': 0.2 is out of range"));
    CHECK(has(error_of(R"({"format": "impactlab-gui session", "bifurcation": {"protocol": "sideways"}})"),
              "key 'bifurcation.protocol': 'sideways' is not one of cf-up, cf-down, ef"));
    CHECK(has(error_of(R"({"format": "impactlab-gui session", "companion": {"ghost_impact": "Q"}})"),
              "key 'companion.ghost_impact': 'Q' is not an impact law (one of"));
    CHECK(has(error_of(R"({"format": "impactlab-gui session", "version": 7})"), "key 'version': 7 is not supported"));
    CHECK(has(error_of(R"({"format": "impactlab-gui session", "data": "/nonexistent/run.csv"})"),
              "key 'data': cannot read '/nonexistent/run.csv'"));
    CHECK(has(error_of(R"({"model": "A1H"})"), "s.json: not a session file"));
    CHECK(has(error_of("[1, 2]"), "s.json: not a session file"));
    // Not JSON: the line and column where the parser stopped.
    CHECK(has(error_of("{\n  \"format\": \"impactlab-gui session\",\n  \"omega\": 9,,\n}"), "s.json: line 3, column 14: not valid JSON"));
    CHECK(has(error_of(""), "s.json: line 1"));
    // A number beyond a double is refused, not an abort; a key given twice is refused, naming it (also nested).
    CHECK(has(error_of(R"({"format": "impactlab-gui session", "omega": 1e999})"), "s.json: a number is out of range"));
    // An integer beyond long long is named as written, not as its wrapped value (-1).
    CHECK(has(error_of(R"({"format": "impactlab-gui session", "version": 18446744073709551615})"),
              "key 'version': 18446744073709551615 is out of range [1, 1000000]"));
    CHECK(has(error_of(R"({"format": "impactlab-gui session", "omega": 9, "omega": 12})"), "s.json: key 'omega' appears twice"));
    CHECK(has(error_of(R"({"format": "impactlab-gui session", "state": {"x": 0, "x": 0.01}})"), "key 'x' appears twice"));
    CHECK(error_of(R"({"format": "impactlab-gui session", "state": {"x": 0}, "view": {"x": 1}})").find("twice") == std::string::npos);
    CHECK_THROWS_WITH_AS(load_session("/nonexistent/session.json", Session{}),
                         doctest::Contains("/nonexistent/session.json: cannot read it"), SessionError);
    CHECK(error_of(session_text(sample())).empty());
}

TEST_CASE("session: a refused parameter names the file and its key once, then the core's reason") {
    const std::string e = error_of(R"({"format": "impactlab-gui session", "model": "A1C", "params": {"c": -5}})");
    CHECK(e == "s.json: key 'params.c': must lie in [0, 1e+06] N s/m (viscous resistance), got -5");
}


TEST_CASE("session: 400k empty objects are read in one linear pass, then refused by key") {
    std::string text = R"({"format": "impactlab-gui session", "junk": [)";
    text.reserve(text.size() + 3 * 400000 + 2);
    for (int i = 0; i < 400000; ++i) text += i ? ",{}" : "{}";
    text += "]}";
    const std::clock_t c0 = std::clock();
    CHECK(has(error_of(text), "s.json: key 'junk': unknown key"));
    // Generous (a sanitizer's build included): one pass takes a fraction of a second, nlohmann's callback
    // parser, which scans the whole parent array at each closed object, took 40 s.
    CHECK(static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC < 10.0);
}

TEST_CASE("session: a data file named in bytes that are not UTF-8 is saved escaped, never an exception") {
    const fs::path dir = fs::temp_directory_path() / ("impactlab-session-bytes-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    Session s = sample();
    s.data = "/tmp/r\xff" "e.csv";
    const std::string path = (dir / "s.json").string();
    CHECK_NOTHROW(save_session(s, path));
    std::ifstream f(path);
    const std::string text((std::istreambuf_iterator<char>(f)), {});
    CHECK(has(text, "\"data\": \"/tmp/r\\\\xffe.csv\""));
    fs::remove_all(dir);
}

TEST_CASE("session: a relative data path is saved relative to the session file, and opens from any working directory") {
    const fs::path dir = fs::temp_directory_path() / ("impactlab-session-rel-" + std::to_string(::getpid()));
    fs::create_directories(dir / "data");
    fs::create_directories(dir / "sessions");
    std::ofstream(dir / "data" / "run.csv") << "t,x,phi\n0,0,0\n";
    const fs::path cwd = fs::current_path();
    Session s = sample();
    s.data = fs::relative(dir / "data" / "run.csv", cwd).string();   // as typed in the working directory
    REQUIRE(fs::path(s.data).is_relative());
    save_session(s, (dir / "sessions" / "s.json").string());
    fs::current_path("/");   // another working directory
    std::string err;
    Session back;
    try {
        back = load_session((dir / "sessions" / "s.json").string(), Session{});
    } catch (const SessionError& e) {
        err = e.what();
    }
    fs::current_path(cwd);
    CHECK(err.empty());
    CHECK(fs::equivalent(back.data, dir / "data" / "run.csv"));
    fs::remove_all(dir);
}
