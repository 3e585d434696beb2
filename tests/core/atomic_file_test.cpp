// Outputs committed as a unit (OutputGroup), every write checked (write_file_whole), partial files of dead
// processes removed, and names in any bytes carried as text (utf8_escaped, json_dump).
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "impactlab/atomic_file.hpp"
#include "impactlab/input_file.hpp"
#include "impactlab/json_text.hpp"
#include "impactlab/params.hpp"
#include "impactlab/params_json.hpp"
#include "impactlab/plot.hpp"

using namespace impactlab;
namespace fs = std::filesystem;

namespace {
struct Scratch {
    fs::path dir;
    explicit Scratch(const std::string& name)
        : dir(fs::temp_directory_path() / ("impactlab_atomic_test_" + name + "_" + std::to_string(::getpid()))) {
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    ~Scratch() {
        std::error_code ec;
        fs::permissions(dir, fs::perms::owner_all, fs::perm_options::add, ec);
        fs::remove_all(dir, ec);
    }
    std::string path(const std::string& name) const { return (dir / name).string(); }
    std::string write(const std::string& name, const std::string& text) const {
        std::ofstream(path(name), std::ios::binary) << text;
        return path(name);
    }
    std::string read(const std::string& name) const {
        std::ifstream f(path(name), std::ios::binary);
        return {std::istreambuf_iterator<char>(f), {}};
    }
    // Files whose name holds ".partial-": none may be left.
    int partials() const {
        int n = 0;
        for (const auto& e : fs::directory_iterator(dir)) n += e.path().filename().string().find(".partial-") != std::string::npos;
        return n;
    }
};
}  // namespace

TEST_CASE("OutputGroup: files are renamed into place together, or not at all") {
    const Scratch s("group");
    s.write("a.csv", "old a");
    s.write("b.png", "old b");
    {   // an exception after the first file: both old files stay, nothing is left behind
        try {
            OutputGroup g;
            write_file_whole(s.path("a.csv"), "new a");
            CHECK(s.read("a.csv") == "old a");   // staged, not yet in place
            throw std::runtime_error("the PNG failed");
        } catch (const std::runtime_error&) {
        }
        CHECK(s.read("a.csv") == "old a");
        CHECK(s.read("b.png") == "old b");
        CHECK(s.partials() == 0);
    }
    {   // committed: both new; an inner group joins the outer one
        OutputGroup g;
        write_file_whole(s.path("a.csv"), "new a");
        {
            OutputGroup inner;
            write_file_whole(s.path("b.png"), "new b");
            inner.commit();
        }
        CHECK(s.read("b.png") == "old b");
        g.commit();
        CHECK(s.read("a.csv") == "new a");
        CHECK(s.read("b.png") == "new b");
        CHECK(s.partials() == 0);
    }
}

TEST_CASE("OutputGroup: a rename that fails midway puts the files renamed before it back") {
    const Scratch s("rollback");
    s.write("a.csv", "old a");
    OutputGroup g;
    write_file_whole(s.path("a.csv"), "new a");
    write_file_whole(s.path("c.csv"), "new c");   // no old c.csv: it must be gone again
    write_file_whole(s.path("b.png"), "new b");
    // Something takes b.png's name meanwhile: a folder, which no file is renamed over (even by root).
    fs::create_directories(s.dir / "b.png" / "inside");
    CHECK_THROWS_WITH_AS(g.commit(), doctest::Contains("b.png: cannot write it"), std::runtime_error);
    CHECK(s.read("a.csv") == "old a");
    CHECK(!fs::exists(s.path("c.csv")));
    CHECK(fs::is_directory(s.dir / "b.png" / "inside"));
    CHECK(s.partials() == 0);
}

TEST_CASE("save_png, save_params, write_file_whole: a write that fails (/dev/full) throws naming the file and the reason") {
    // /dev/full takes the open and refuses every write with ENOSPC: the partial file is made a link to it, so
    // what is checked is the writes, not the open (stb's own PNG writer left them unchecked: an empty PNG).
    if (!fs::exists("/dev/full")) return;
    const Scratch s("full");
    auto on_full_disk = [&](const std::string& name, const auto& write) {
        const std::string target = s.write(name, "old");
        const std::string partial = partial_path(target);
        fs::create_symlink("/dev/full", partial);
        CHECK_THROWS_WITH(write(target), doctest::Contains((name + ": write failed (No space left on device)").c_str()));
        CHECK(s.read(name) == "old");
        CHECK(!fs::exists(fs::symlink_status(partial)));
    };
    plot::Image img;
    img.width = img.height = 2;
    img.rgba.assign(16, 255);
    on_full_disk("p.png", [&](const std::string& t) { plot::save_png(img, t); });
    on_full_disk("m.json", [&](const std::string& t) { save_params(make_version("A1H"), t); });
    on_full_disk("w.txt", [&](const std::string& t) { write_file_whole(t, "bytes"); });
}

TEST_CASE("remove_stale_partials: a dead process's partial files go, a live one's and other files stay") {
    const Scratch s("stale");
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    ::waitpid(child, nullptr, 0);   // a PID that no process has now
    const std::string dead = std::to_string(child), live = std::to_string(::getppid());
    s.write(".a.csv.partial-" + dead, "x");
    s.write(".a.csv.partial-" + dead + "-old", "x");
    fs::create_directories(s.dir / (".clip.partial-" + dead));
    s.write(".clip.partial-" + dead + "/f.png", "x");
    s.write(".b.csv.partial-" + live, "x");
    s.write("c.partial-" + dead, "x");             // not hidden: no partial name
    s.write(".d.csv.partial-" + dead + "x", "x");   // not a PID
    CHECK(remove_stale_partials(s.dir.string()) == 3);
    CHECK(!fs::exists(s.path(".a.csv.partial-" + dead)));
    CHECK(!fs::exists(s.path(".clip.partial-" + dead)));
    CHECK(fs::exists(s.path(".b.csv.partial-" + live)));
    CHECK(fs::exists(s.path("c.partial-" + dead)));
    CHECK(fs::exists(s.path(".d.csv.partial-" + dead + "x")));
}

TEST_CASE("utf8_escaped and printable: bytes that are not UTF-8 shown as \\xNN, UTF-8 kept") {
    CHECK(utf8_escaped("caf\xc3\xa9.csv") == "caf\xc3\xa9.csv");
    CHECK(utf8_escaped("caf\xe9.csv") == "caf\\xe9.csv");   // Latin-1
    CHECK(utf8_escaped("\xc0\xaf") == "\\xc0\\xaf");          // an overlong '/'
    CHECK(utf8_escaped("\xed\xa0\x80") == "\\xed\\xa0\\x80"); // a surrogate
    CHECK(utf8_escaped("\xf0\x9f\x98\x80") == "\xf0\x9f\x98\x80");
    CHECK(utf8_escaped("\xf0\x9f\x98") == "\\xf0\\x9f\\x98");   // cut short
    CHECK(printable("a\x1b" "b\xff") == "a\\x1bb\\xff");
}

TEST_CASE("json_dump: a name in any bytes is written escaped, never an exception") {
    nlohmann::json j = {{"source", std::string("r\xff" "e.csv")}, {"list", {std::string("\xfe")}}};
    j[std::string("k\xff")] = 1;
    std::string text;
    CHECK_NOTHROW(text = json_dump(j, 2));
    const auto back = nlohmann::json::parse(text);
    CHECK(back["source"] == "r\\xffe.csv");
    CHECK(back["list"][0] == "\\xfe");
    CHECK(back["k\\xff"] == 1);
}
