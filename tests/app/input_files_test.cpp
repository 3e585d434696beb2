// The visualiser's input files (--plane, --session, --data, a session's "data") go through the core's
// checked reader: a directory, a FIFO or a device is refused at once, naming the file, and never hangs.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

#include "../../app/gui/window/options.hpp"
#include "../../app/gui/analysis/plane_data.hpp"
#include "../../app/gui/files/session.hpp"
#include "impactlab/identify_data.hpp"

using namespace impactlab::gui;
namespace fs = std::filesystem;

namespace {

struct Scratch {
    fs::path dir = fs::temp_directory_path() / ("impactlab_gui_inputs_" + std::to_string(::getpid()));
    Scratch() {
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    ~Scratch() {
        std::error_code ec;
        fs::remove_all(dir, ec);
    }
    std::string fifo(const std::string& name) const {
        const std::string p = (dir / name).string();
        REQUIRE(::mkfifo(p.c_str(), 0600) == 0);
        return p;
    }
};

template <class E, class F>
std::string error_of(F&& f) {
    try {
        f();
    } catch (const E& e) {
        return e.what();
    }
    return "";
}

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("gui inputs: --plane of a directory, a FIFO or a device names the file and its kind") {
    const Scratch s;
    const std::string d = s.dir.string(), f = s.fifo("plane.csv");
    CHECK(error_of<PlaneError>([&] { load_plane_csv(d); }) == d + ": is a directory, not a file");
    CHECK(error_of<PlaneError>([&] { load_plane_csv(f); }) == f + ": is a named pipe (FIFO), not a regular file");
    CHECK(error_of<PlaneError>([&] { load_plane_csv("/dev/zero"); }) == "/dev/zero: is a device, not a regular file");
}

TEST_CASE("gui inputs: --session of a directory, a FIFO or a device; a session whose data is a FIFO") {
    const Scratch s;
    const std::string d = s.dir.string(), f = s.fifo("s.json");
    CHECK(error_of<SessionError>([&] { load_session(d, Session{}); }) == d + ": is a directory, not a file");
    CHECK(error_of<SessionError>([&] { load_session(f, Session{}); }) == f + ": is a named pipe (FIFO), not a regular file");
    CHECK(error_of<SessionError>([&] { load_session("/dev/zero", Session{}); }) == "/dev/zero: is a device, not a regular file");
    const std::string data = s.fifo("run.csv");
    const std::string text = "{\"format\": \"impactlab-gui session\", \"data\": \"" + data + "\"}";
    CHECK(has(error_of<SessionError>([&] { parse_session(text, Session{}, "s.json"); }),
              "key 'data': cannot read '" + data + "': is a named pipe (FIFO)"));
}

TEST_CASE("gui inputs: --data of a FIFO or a device is refused before the window opens; file flags only once") {
    const Scratch s;
    Options o;
    o.frames = 5;   // headless: checked before any window (by hand the window opens and the data panel says it)
    o.data = s.fifo("d.csv");
    CHECK(error_of<OptionsError>([&] { check_files(o); }) == "--data: cannot read '" + o.data + "': is a named pipe (FIFO), not a regular file");
    o.data = "/dev/zero";
    CHECK(has(error_of<OptionsError>([&] { check_files(o); }), "--data: cannot read '/dev/zero': is a device"));
    CHECK(error_of<OptionsError>([&] { parse_options({"--session", "a.json", "--session", "b.json"}); }) == "--session: given twice");
    CHECK(error_of<OptionsError>([&] { parse_options({"--data", "a.csv", "--paused", "--data", "b.csv"}); }) == "--data: given twice");
    CHECK(error_of<OptionsError>([&] { parse_options({"--plane", "a.csv", "--plane", "a.csv"}); }) == "--plane: given twice");
    // Started by hand the same FIFO is no error here: the data panel's loader refuses it (read_data_file
    // checks the kind first), so nothing blocks on it.
    o.frames = 0;
    o.data = s.fifo("d2.csv");
    CHECK_NOTHROW(check_files(o));
    CHECK_THROWS_WITH_AS(impactlab::identify::read_data_file(o.data), doctest::Contains("named pipe"), impactlab::identify::DataError);
}
