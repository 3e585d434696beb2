// The measured-data loader: MODEL.md's CSV conventions, column mapping, gzip, and every refusal.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "impactlab/identify.hpp"
#include "impactlab/identify_data.hpp"
#include "shared_data.hpp"

namespace id = impactlab::identify;

namespace {

std::string rows(int n, double dt = 1e-3) {
    std::string s;
    for (int i = 0; i < n; ++i) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "%.6f,%.7f,%.6f\n", i * dt, 0.001 * std::sin(i * 0.01), 0.01 * i);
        s += buf;
    }
    return s;
}

// The DataError message of parsing `text`, or "" if it parses.
std::string refusal(const std::string& text, const id::LoadOptions& o = {}) {
    try {
        id::parse_measured(text, "f.csv", o);
    } catch (const id::DataError& e) {
        return e.what();
    }
    return "";
}

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("loader: the MODEL.md layout with comments, metadata and CRLF") {
    const std::string text = "# sample_rate: 1000\r\n# operator: someone\r\nt,x,phi\r\n" + rows(50);
    const id::MeasuredData d = id::parse_measured(text, "f.csv");
    CHECK(d.size() == 50);
    CHECK(d.has_phi());
    CHECK_FALSE(d.has_u());
    CHECK(d.meta.at("operator") == "someone");
    CHECK(d.line.front() == 4);
    CHECK(d.t[10] == doctest::Approx(0.010));
    CHECK(d.phi[3] == doctest::Approx(0.03));
}

TEST_CASE("loader: columns mapped by name or number, a sample rate, scales and a row range") {
    std::string text = "\"V1\",\"V2\",\n";
    for (int i = 0; i < 100; ++i) text += std::to_string(0.001 * i) + "," + std::to_string(0.5 * i) + ",\n";
    id::LoadOptions o;
    o.columns.x = "V2";
    o.columns.u.push_back('1');   // (a one-character literal trips a GCC 12 -Wrestrict false positive)
    o.rate = 100.0;
    o.x_scale = 1e-3;
    o.row_begin = 10;
    o.row_end = 60;
    const id::MeasuredData d = id::parse_measured(text, "silverbox-like.csv", o);
    REQUIRE(d.size() == 50);
    CHECK(d.has_u());
    CHECK(d.t.front() == doctest::Approx(0.10));
    CHECK(d.x.front() == doctest::Approx(5e-3));
    CHECK(d.u.back() == doctest::Approx(0.059));
}

TEST_CASE("loader: every broken file is refused with its line and the problem") {
    const std::string good = "t,x,phi\n" + rows(40);
    CHECK(refusal(good).empty());
    CHECK(has(refusal("t,phi\n" + rows(40)), "no position column 'x'"));
    CHECK(has(refusal("x,phi\n1,2\n"), "no time column"));
    // A column left unread may be the forcing under another name: the user says which, or that there is none.
    CHECK(has(refusal("t,x,accel\n" + rows(40)), "no forcing column"));
    CHECK(has(refusal("t,x,accel\n" + rows(40)), "--free"));
    id::LoadOptions declared_free;
    declared_free.free_run = true;
    CHECK(has(refusal("t,x,phi\n" + rows(40), declared_free), "column 'phi' is its forcing"));
    CHECK(has(refusal("t,x,phi,u\n0,0,0,0\n"), "both a 'phi' and a 'u'"));
    std::string text_in_number = good;
    text_in_number.replace(text_in_number.find("0.000000,0.0000000"), 18, "0.000000,abc");
    CHECK(has(refusal(text_in_number), "line 2: column 'x' (x): 'abc' is not a number"));
    std::string with_nan = "t,x,phi\n" + rows(5) + "0.005,nan,0.05\n" + rows(40).substr(0);
    CHECK(has(refusal(with_nan), "line 7"));
    CHECK(has(refusal(with_nan), "not a finite number"));
    CHECK(has(refusal("t,x,phi\n0,0,0\n1,0,0\n1,0,0\n" + rows(40)), "line 4: time does not increase"));
    CHECK(has(refusal("t,x,phi\n" + rows(5)), "only 5 samples"));
    id::LoadOptions nothing;
    nothing.columns.x = "position";
    CHECK(has(refusal(good, nothing), "names no column"));
    id::LoadOptions beyond;
    beyond.columns.x = "7";
    CHECK(has(refusal(good, beyond), "names no column"));
    CHECK(has(refusal("t,x,phi\n0,0,0\n0.001,0\n"), "line 3: 2 fields, but the header (line 1) has 3"));
    CHECK(has(refusal("t,x,phi\n0,0,0\n0.001,0,5\n"), "line 3: phi jumps"));
    CHECK(has(refusal("t,x,phi\n0,,0\n"), "line 2: column 'x' (x) is empty"));
    CHECK(has(refusal("t,x,x\n0,0,0\n"), "appears twice"));
    CHECK(has(refusal("# only a comment\n"), "no header row"));
    CHECK(has(refusal("t,x,phi\n"), "no data rows"));
    id::LoadOptions both;
    both.rate = 1000;
    CHECK(has(refusal(good, both), "both a time column and a sample rate"));
    id::LoadOptions range;
    range.row_begin = 100;
    CHECK(has(refusal(good, range), "outside the file's 40 data rows"));
}

TEST_CASE("loader: gzip read directly, corrupt gzip refused") {
    const std::string text = "t,x,phi\n" + rows(300);
    const std::string gz = id::gzip_stored(text);
    CHECK(id::is_gzip(gz));
    CHECK(id::gunzip(gz, "a.gz") == text);
    std::string bad = gz;
    bad[bad.size() - 12] ^= 0x5a;   // a byte of the data: the CRC no longer matches
    CHECK_THROWS_AS(id::gunzip(bad, "bad.gz"), id::DataError);
    CHECK_THROWS_AS(id::gunzip(gz.substr(0, gz.size() - 5), "short.gz"), id::DataError);
    const auto path = std::filesystem::temp_directory_path() / "impactlab_loader_test.csv.gz";
    {
        std::ofstream out(path, std::ios::binary);
        out << gz;
    }
    const id::MeasuredData d = id::load_measured(path.string());
    CHECK(d.size() == 300);
    std::filesystem::remove(path);
    CHECK_THROWS_AS(id::load_measured("/nonexistent/file.csv"), id::DataError);
}

TEST_CASE("loader: gzip through zlib: round trip, concatenated members, truncation, a gzip bomb") {
    const std::string text = "t,x,phi\n" + rows(2000);
    const std::string gz = id::gzip_stored(text);
    CHECK(id::is_gzip(gz));
    CHECK(gz.size() < text.size());   // deflated now, not stored
    CHECK(id::gunzip(gz, "a.gz") == text);
    CHECK(id::gunzip(id::gzip_stored(""), "empty.gz").empty());

    // Two members one after the other (cat a.gz b.gz) read whole; zero padding after the last is allowed.
    const std::string second = rows(50);
    CHECK(id::gunzip(gz + id::gzip_stored(second), "two.gz") == text + second);
    CHECK(id::gunzip(gz + std::string(16, '\0'), "padded.gz") == text);

    // Truncated anywhere (inside the data or the trailer) or with garbage after a member: refused.
    for (std::size_t cut : {std::size_t{10}, gz.size() / 2, gz.size() - 8, gz.size() - 1}) {
        try {
            id::gunzip(gz.substr(0, cut), "short.gz");
            FAIL("a truncated gzip was accepted, cut at " << cut);
        } catch (const id::DataError& e) {
            CHECK(has(e.what(), "short.gz: corrupt gzip data"));
        }
    }
    CHECK_THROWS_AS(id::gunzip(gz + "garbage", "tail.gz"), id::DataError);
    CHECK_THROWS_AS(id::gunzip("", "nothing.gz"), id::DataError);

    // 64 MiB of zeros deflate to a few dozen KiB; with a 1 MiB cap gunzip refuses them early.
    const std::string bomb = id::gzip_stored(std::string(std::size_t{64} << 20, '\0'));
    CHECK(bomb.size() < (std::size_t{1} << 20));
    try {
        id::gunzip(bomb, "bomb.gz", std::size_t{1} << 20);
        FAIL("the gzip bomb was accepted");
    } catch (const id::DataError& e) {
        CHECK(has(e.what(), "bomb.gz: decompressed data exceed 1 MiB"));
    }
    // Exactly at the cap is fine.
    const std::string mib(std::size_t{1} << 20, 'x');
    CHECK(id::gunzip(id::gzip_stored(mib), "cap.gz", mib.size()) == mib);
    CHECK_THROWS_AS(id::gunzip(id::gzip_stored(mib), "cap.gz", mib.size() - 1), id::DataError);
}

TEST_CASE("loader: real deflate streams (the shared data files)" *
          doctest::skip(impactlab::test::shared_missing("data/synthetic/s3_noise_only.csv.gz"))) {
    const std::string f = impactlab::test::shared_path("data/synthetic/s3_noise_only.csv.gz");
    const std::string text = id::read_data_file(f);   // checks the CRC of the whole member
    CHECK(text.rfind("t,x,phi\n0.000000,", 0) == 0);
    CHECK(std::count(text.begin(), text.end(), '\n') == 126002);
}

TEST_CASE("noise floor: holds for white noise on a smooth record and on one with power up to 0.6 Nyquist") {
    std::mt19937_64 rng(9);
    std::normal_distribution<double> noise(0.0, 1.0);
    const std::size_t n = 40000;
    const double sigma = 2e-5;
    std::vector<double> smooth(n), busy(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double t = static_cast<double>(i) * 1e-3;   // 1 kHz, Nyquist 500 Hz
        smooth[i] = 0.01 * std::sin(2 * 3.141592653589793 * 2.0 * t) + sigma * noise(rng);
        busy[i] = sigma * noise(rng);
        for (int k = 1; k <= 30; ++k)   // lines up to 300 Hz, 1e-4 each: far above the noise in 4th differences
            busy[i] += 1e-4 * std::sin(2 * 3.141592653589793 * 10.0 * k * t + 0.7 * k * k);
    }
    CHECK(impactlab::identify::estimate_noise(smooth) == doctest::Approx(sigma).epsilon(0.1));
    CHECK(impactlab::identify::estimate_noise(busy) == doctest::Approx(sigma).epsilon(0.15));
}

TEST_CASE("loader: hostile inputs: CR-only lines, 100k columns, scales that overflow, corrupt samples, time units") {
    // Old Mac line endings: read as lines, not as one header with a repeated name.
    std::string cr = "t,x,phi\n" + rows(100);
    std::replace(cr.begin(), cr.end(), '\n', '\r');
    CHECK(id::parse_measured(cr, "cr.csv").size() == 100);

    // A header of 100k columns is checked for repeats in linear time; a repeat names both columns.
    std::string wide = "t,x,phi";
    for (int k = 0; k < 100000; ++k) wide += ",c" + std::to_string(k);
    wide += "\n";
    for (const char* row : {"0,0.001,0", "0.001,0.002,0.01"}) {
        wide += row;
        for (int k = 0; k < 100000; ++k) wide += ",1";
        wide += "\n";
    }
    id::LoadOptions two;
    two.min_samples = 2;
    CHECK(id::parse_measured(wide, "wide.csv", two).size() == 2);
    const std::string dup = refusal("t,x,phi,x\n" + rows(40));
    CAPTURE(dup);
    CHECK(has(dup, "'x' appears twice (columns 2 and 4)"));

    // A scale that overflows is refused at the sample it overflows, not passed on as inf or NaN.
    id::LoadOptions huge;
    huge.x_scale = 1e308;
    const std::string over = refusal("t,x,phi\n" + rows(100), huge);
    CAPTURE(over);
    CHECK(has(over, "f.csv: line 3"));
    CHECK(has(over, "beyond 1e15"));
    id::LoadOptions tiny;
    tiny.x_scale = 1e-320;   // every nonzero x underflows to zero
    const std::string under = refusal("t,x,phi\n" + rows(100), tiny);
    CAPTURE(under);
    CHECK(has(under, "not a representable number"));

    // Values no sensor reads, and a single corrupt sample, named with their line.
    std::string spike = "t,x,phi\n" + rows(200);
    const std::string bad_row = "0.100000,1e298,1.000000\n";
    spike.replace(spike.find("0.100000,"), spike.find('\n', spike.find("0.100000,")) + 1 - spike.find("0.100000,"), bad_row);
    const std::string sp = refusal(spike);
    CAPTURE(sp);
    CHECK(has(sp, "line 102"));
    CHECK(has(sp, "beyond 1e15"));
    std::string glitch = "t,x,phi\n" + rows(200);
    glitch.replace(glitch.find("0.100000,"), glitch.find('\n', glitch.find("0.100000,")) + 1 - glitch.find("0.100000,"),
                   "0.100000,900000,1.000000\n");
    CHECK(has(refusal(glitch), "times the record's spread"));

    // Time near 1e300 (no longer "cannot create std::vector larger than max_size()"), or nanoseconds as s.
    std::string far = "t,x,phi\n";
    for (int i = 0; i < 40; ++i) far += std::to_string(1e300 * (1 + i)) + ",0.001," + std::to_string(0.01 * i) + "\n";
    const std::string f = refusal(far);
    CAPTURE(f);
    CHECK(has(f, "beyond 1e9 s"));
    id::LoadOptions ns;
    ns.t_scale = 1e-12;
    CHECK(has(refusal("t,x,phi\n" + rows(100), ns), "within 1 ns of the previous sample"));
}

TEST_CASE("loader: a record of the motion alone is a free run, its input zero; declared where other columns are present") {
    std::string two;   // t,x: a free decay
    for (int i = 0; i < 40; ++i) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.6f,%.7f\n", i * 1e-3, 0.001 * std::exp(-0.1 * i) * std::cos(0.5 * i));
        two += buf;
    }
    const id::MeasuredData d = id::parse_measured("t,x\n" + two, "decay.csv", {});
    REQUIRE(d.size() == 40);
    CHECK(d.free_run);
    REQUIRE(d.has_u());
    CHECK(std::all_of(d.u.begin(), d.u.end(), [](double u) { return u == 0.0; }));
    CHECK(id::forcing_of(d) == id::Forcing::Input);
    CHECK(d.meta.at("forcing").find("free run") != std::string::npos);
    // x alone at a given rate is motion only too.
    id::LoadOptions at_rate;
    at_rate.rate = 1000.0;
    std::string xs;
    for (int i = 0; i < 40; ++i) xs += std::to_string(0.001 * std::cos(0.5 * i)) + "\n";
    CHECK(id::parse_measured("x\n" + xs, "x.csv", at_rate).free_run);
    // An extra column, read as a free run only when the user says so.
    id::LoadOptions declared;
    declared.free_run = true;
    const id::MeasuredData e = id::parse_measured("t,x,temperature\n" + rows(40), "f.csv", declared);
    CHECK(e.free_run);
    CHECK(e.u.size() == 40);
    // A forced record is no free run.
    CHECK_FALSE(id::parse_measured("t,x,phi\n" + rows(40), "f.csv", {}).free_run);
}
