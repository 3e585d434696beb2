// Input files are checked for kind and size before a byte is read and read up to a cap; a partial output
// file is removed when a signal stops the process.
#include <doctest/doctest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "impactlab/atomic_file.hpp"
#include "impactlab/identify_data.hpp"
#include "impactlab/input_file.hpp"

using namespace impactlab;
namespace fs = std::filesystem;

namespace {

// A fresh scratch directory per test, removed at the end.
struct Scratch {
    fs::path dir;
    explicit Scratch(const std::string& name) : dir(fs::temp_directory_path() / ("impactlab_input_test_" + name + "_" + std::to_string(::getpid()))) {
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    ~Scratch() {
        std::error_code ec;
        fs::remove_all(dir, ec);
    }
    std::string file(const std::string& name, const std::string& text) const {
        const std::string p = (dir / name).string();
        std::ofstream(p, std::ios::binary) << text;
        return p;
    }
};

std::string error_of(const std::string& path, std::size_t cap = kMaxInputBytes) {
    try {
        (void)read_input_file(path, cap);
    } catch (const InputFileError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("read_input_file: a regular file is read whole; what is no regular file is refused by kind") {
    const Scratch s("kind");
    const std::string text = "t,x,phi\n0,0,0\n";
    CHECK(read_input_file(s.file("ok.csv", text)) == text);
    CHECK(read_input_file(s.file("empty.csv", "")).empty());
    CHECK(error_of(s.dir.string()) == s.dir.string() + ": is a directory, not a file");
    const std::string fifo = (s.dir / "f.csv").string();
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    // No writer ever opens it: a plain open would block here for ever.
    CHECK(error_of(fifo) == fifo + ": is a named pipe (FIFO), not a regular file");
    CHECK_NOTHROW(check_input_file(s.file("ok2.csv", text)));
    CHECK_THROWS_WITH_AS(check_input_file(fifo), doctest::Contains("named pipe"), InputFileError);
    CHECK(error_of("/dev/zero") == "/dev/zero: is a device, not a regular file");
    CHECK(error_of((s.dir / "missing.csv").string()).find("missing.csv: cannot read it (No such file") != std::string::npos);
    CHECK(error_of("") == "'': an empty file name");
    // The error keeps the name and the reason apart for callers that word their own message.
    try {
        (void)read_input_file(fifo);
    } catch (const InputFileError& e) {
        CHECK(e.path == fifo);
        CHECK(e.reason == "is a named pipe (FIFO), not a regular file");
    }
}

TEST_CASE("read_input_file: the size is checked before reading, and the cap holds while reading") {
    const Scratch s("size");
    const std::string big = (s.dir / "big.csv").string();
    { std::ofstream(big) << ""; }
    fs::resize_file(big, (std::size_t{2} << 30));   // sparse: no 2 GiB are written or read
    CHECK(error_of(big) == big + ": 2 GiB, more than the 1 GiB an input may hold");
    const std::string five = s.file("five.csv", "12345");
    CHECK(error_of(five, 4) == five + ": 5 bytes, more than the 4 bytes an input may hold");
    CHECK(read_input_file(five, 5) == "12345");
    // A /proc file reports size 0 and is read up to the cap.
    CHECK(!read_input_file("/proc/self/status").empty());
    CHECK(error_of("/proc/self/status", 8) == "/proc/self/status: more than the 8 bytes an input may hold");
    // A file that cannot be read names itself, not the stream library.
    CHECK(error_of("/proc/self/mem").rfind("/proc/self/mem: cannot read it (", 0) == 0);
}

TEST_CASE("read_data_file: kind and size through the loader, gzip capped after decompression") {
    const Scratch s("data");
    CHECK_THROWS_WITH_AS(identify::read_data_file(s.dir.string()), doctest::Contains("is a directory"), identify::DataError);
    CHECK_THROWS_WITH_AS(identify::read_data_file("/dev/zero"), doctest::Contains("/dev/zero: is a device"), identify::DataError);
    const std::string gz = s.file("a.csv.gz", identify::gzip_stored("t,x,phi\n"));
    CHECK(identify::read_data_file(gz) == "t,x,phi\n");
}

TEST_CASE("size_text and printable: sizes in words, untrusted text cut and escaped") {
    CHECK(size_text(1) == "1 bytes");
    CHECK(size_text(std::size_t{1} << 30) == "1 GiB");
    CHECK(size_text(std::size_t{3} << 19) == "1.5 MiB");
    CHECK(printable("A1H") == "A1H");
    CHECK(printable("a\x1b[31mb\nc\x7f") == "a\\x1b[31mb\\x0ac\\x7f");
    const std::string huge(50000, 'n');
    const std::string cut = printable(huge, 100);
    CHECK(cut.size() < 140);
    CHECK(cut.find("(49900 bytes more)") != std::string::npos);
}

TEST_CASE("remove_partials_on_signal: a partial file is removed when SIGTERM or SIGINT stops the process") {
    const Scratch s("signal");
    for (const int sig : {SIGTERM, SIGINT}) {
        const std::string target = (s.dir / "out.csv").string();
        const std::string done_target = (s.dir / "done.csv").string();
        const pid_t child = ::fork();
        REQUIRE(child >= 0);
        if (child == 0) {   // the child: one committed file, one partial in flight, then the signal
            std::signal(sig, SIG_DFL);   // whatever the test runner left: the handler is what is tested
            remove_partials_on_signal();
            const std::string kept = partial_path(done_target);
            { std::ofstream(kept) << "whole\n"; }
            commit_partial(kept, done_target);
            const std::string tmp = partial_path(target);
            { std::ofstream(tmp) << "half a file"; }
            ::raise(sig);
            ::_exit(3);   // not reached: the signal ends the process
        }
        int status = 0;
        REQUIRE(::waitpid(child, &status, 0) == child);
        CHECK(WIFSIGNALED(status));
        CHECK(WTERMSIG(status) == sig);
        // Only the committed file is left: the partial ".out.csv.partial-PID" is gone, out.csv never made.
        std::vector<std::string> left;
        for (const auto& e : fs::directory_iterator(s.dir)) left.push_back(e.path().filename().string());
        CHECK(left == std::vector<std::string>{"done.csv"});
        fs::remove(done_target);
    }
}
