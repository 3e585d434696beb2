// impactlab scan: a row is the CF sweep, any thread count gives the same plane, the tile log is exact.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "impactlab/params.hpp"
#include "impactlab/scan.hpp"
#include "impactlab/sweep.hpp"

using namespace impactlab;

namespace {

ScanSpec small_plane() {
    ScanSpec s;
    s.x = parse_scan_axis("omega:9:13.5:7");
    s.y = parse_scan_axis("xI:-0.003:0.003:3");
    s.measures = parse_scan_measures("period,impacts,xrange");
    s.transient = 20;
    s.record = 30;
    return s;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("scan: a row at fixed xI is the CF sweep at the same omegas") {
    const ScanSpec spec = small_plane();
    for (const char* version : {"A1C", "A1G"}) {
        Params p = make_version(version);
        const int row = 2;
        const std::vector<ScanPoint> pts = scan_row(p, spec, row, {});
        REQUIRE(pts.size() == 7u);
        p.xI = spec.y.at(row);
        CfSpec cf;
        cf.omega_min = spec.x.lo;
        cf.omega_max = spec.x.hi;
        cf.steps = spec.x.n;
        cf.transient = spec.transient;
        cf.record = spec.record;
        const Diagram d = run_cf_sweep(p, cf);
        std::map<double, std::vector<double>> xs;
        for (const auto& pt : d.points) xs[pt.omega].push_back(pt.x);
        REQUIRE(xs.size() == 7u);
        int i = 0;
        for (const auto& [w, x] : xs) {
            CAPTURE(version);
            CAPTURE(w);
            CHECK(w == spec.x.at(i));
            const int distinct = count_period(x, 1e-5);
            // The sweep's count where the record recurs in order (settled); else the scan ran the point on.
            bool settled = distinct > 16;
            if (!settled) {
                settled = true;
                for (std::size_t k = static_cast<std::size_t>(distinct); k < x.size(); ++k)
                    settled = settled && std::abs(x[k] - x[k - static_cast<std::size_t>(distinct)]) <= 1e-5;
            }
            if (settled) CHECK(pts[static_cast<std::size_t>(i)].period == (distinct > 16 ? 0 : distinct));
            else MESSAGE(version << " at " << w << ": the record had not settled (" << distinct
                                 << " values); the scan says " << pts[static_cast<std::size_t>(i)].period);
            // The x range holds every section point.
            for (double xv : x) {
                CHECK(xv >= pts[static_cast<std::size_t>(i)].xmin - 1e-12);
                CHECK(xv <= pts[static_cast<std::size_t>(i)].xmax + 1e-12);
            }
            ++i;
        }
    }
}

TEST_CASE("scan: a point is labelled only once settled (A1C at 10.9-11.1 rad/s is period 2, not 5 or 10)") {
    // 20 transient periods leave these points in a slow transient: the record's 70 section values used to
    // fall into 5 or 10 clusters. orbit --omega 11 --period 2 finds a stable period 2, and --transient 200
    // gives 2 everywhere: run on until the record recurs in order, a cell says 2.
    ScanSpec spec;
    spec.x = parse_scan_axis("omega:10.9:11.1:3");
    spec.y = parse_scan_axis("xI:-0.001:0.001:3");
    spec.measures = parse_scan_measures("period");
    const Params p = make_version("A1C");
    for (int row = 0; row < spec.y.n; ++row) {
        const std::vector<ScanPoint> pts = scan_row(p, spec, row, {});
        REQUIRE(pts.size() == 3u);
        for (int i = 0; i < 3; ++i) {
            CAPTURE(row);
            CAPTURE(i);
            CHECK(pts[static_cast<std::size_t>(i)].period == 2);
        }
    }
}

TEST_CASE("scan: one thread and two threads give the same plane, bit for bit") {
    const ScanSpec spec = small_plane();
    const Params p = make_version("A1G");
    std::vector<std::vector<ScanPoint>> one(3), two(3);
    const std::vector<int> todo{0, 1, 2};
    scan_rows(p, spec, todo, 1, nullptr, {}, [&](int r, const std::vector<ScanPoint>& v) { one[static_cast<std::size_t>(r)] = v; });
    scan_rows(p, spec, todo, 2, nullptr, {}, [&](int r, const std::vector<ScanPoint>& v) { two[static_cast<std::size_t>(r)] = v; });
    std::ostringstream a, b;
    write_scan_csv(spec, one, a);
    write_scan_csv(spec, two, b);
    CHECK(a.str() == b.str());
    CHECK(a.str().rfind("omega,xI,period,impacts,xmin,xmax\n9,-0.003,", 0) == 0);
    // Impacts happen somewhere in this plane (A1G's bumper is reached at 13.5 rad/s), and never a negative count.
    double most = 0;
    for (const auto& row : one)
        for (const auto& pt : row) {
            CHECK(pt.impacts >= 0);
            most = std::max(most, pt.impacts);
        }
    CHECK(most > 0);
}

TEST_CASE("scan: the tile log round-trips exactly; a torn row is dropped; another scan's log is refused") {
    ScanSpec spec = small_plane();
    spec.x.n = 2;
    const Params p = make_version("A1H");
    const std::vector<ScanPoint> row{{1, NAN, 0.5, -0.0123456789012345, 1e-300}, {0, -2.5, 3, -1.0 / 3.0, 2.0 / 3.0}};
    const std::string header = scan_log_header(p, spec, {});
    std::stringstream log;
    log << header << '\n' << scan_log_line(1, row) << '\n';
    const std::string torn = scan_log_line(2, row);
    log << torn.substr(0, torn.size() - 10) << '\n';   // killed while writing row 2
    const auto back = read_scan_log(log, header, spec);
    REQUIRE(back.size() == 1u);
    CHECK(back[0].first == 1);
    for (std::size_t i = 0; i < row.size(); ++i) {
        CHECK(same_bits(back[0].second[i].xmin, row[i].xmin));
        CHECK(same_bits(back[0].second[i].xmax, row[i].xmax));
        CHECK(back[0].second[i].period == row[i].period);
    }
    CHECK(std::isnan(back[0].second[0].lyapunov));
    ScanSpec other = spec;
    other.record = 71;
    std::stringstream again;
    again << header << '\n';
    CHECK_THROWS_AS(read_scan_log(again, scan_log_header(p, other, {}), other), ScanError);
}

TEST_CASE("scan: the log header changes with every model parameter and tolerance that shapes the result") {
    const ScanSpec spec = small_plane();
    const Params p = make_version("A1H");
    const std::string h = scan_log_header(p, spec, {});
    Params stiffer = p;
    stiffer.k *= 1.5;   // a parameter file that kept the name "A1H"
    CHECK(scan_log_header(stiffer, spec, {}) != h);
    Params damped = p;
    damped.c *= 1.0 + 1e-15;
    CHECK(scan_log_header(damped, spec, {}) != h);
    Tolerances tol;
    tol.rtol = 1e-9;
    CHECK(scan_log_header(p, spec, tol) != h);
    Tolerances budget;
    budget.max_step_rate *= 2;
    CHECK(scan_log_header(p, spec, budget) != h);
    CHECK(scan_log_header(make_version("A1H"), spec, {}) == h);
    // A name with control characters stays on one line.
    Params odd = p;
    odd.name = "A1H\n\x1b[31mred";
    CHECK(scan_log_header(odd, spec, {}).find_first_of("\n\x1b") == std::string::npos);
}

TEST_CASE("scan: a tile log is read strictly, naming the line") {
    ScanSpec spec = small_plane();
    spec.x.n = 2;
    const Params p = make_version("A1H");
    const std::string header = scan_log_header(p, spec, {});
    const std::vector<ScanPoint> row{{1, NAN, 0.5, -0.01, 0.01}, {2, NAN, 1, -0.02, 0.02}};
    const std::string good = scan_log_line(0, row);
    const auto read = [&](const std::string& body) {
        std::stringstream log(header + "\n" + body);
        return read_scan_log(log, header, spec);
    };
    const auto refused = [&](const std::string& body, const char* what) {
        std::string msg;
        try {
            read(body);
        } catch (const ScanError& e) {
            msg = e.what();
        }
        INFO(body);
        CHECK(msg.find(what) != std::string::npos);
    };
    CHECK(read(good + "\n").size() == 1u);
    // A token the log never writes: a word read as 0 (chaos), 1e999 read as inf, decimal text.
    std::string word = good;
    word.replace(word.find("0x1p+0"), 6, "abc");
    refused(word + "\n" + good + "\n", "line 2: 'abc' is not a number");
    std::string huge = good;
    huge.replace(huge.find("0x1p+0"), 6, "1e999");
    refused(huge + "\n" + good + "\n", "'1e999' is not a number");
    std::string half = good;
    half.replace(half.find("0x1p+0"), 6, "0x1.8p+0");   // period 1.5
    refused(half + "\n", "period 0x1.8p+0 is not one a scan gives");
    // A point that had not settled (kNotSettled) is one a scan gives; -2 is not.
    const std::vector<ScanPoint> unsettled{{kNotSettled, NAN, 0.5, -0.01, 0.01}, {2, NAN, 1, -0.02, 0.02}};
    CHECK(read(scan_log_line(0, unsettled) + "\n")[0].second[0].period == kNotSettled);
    std::string minus2 = scan_log_line(0, unsettled);
    minus2.replace(minus2.find("-0x1p+0"), 7, "-0x1p+1");
    refused(minus2 + "\n", "period -0x1p+1 is not one a scan gives");
    refused("row 7 " + good.substr(6) + "\n", "'row 7' is not 'row N' with N in [0, 2]");
    refused("col 0 " + good.substr(6) + "\n", "is not 'row N'");
    refused(good.substr(0, good.size() - 4) + " 0x0p+0 end\n", "more fields");
    // A broken line before the last is no torn write.
    refused(good.substr(0, 20) + "\n" + scan_log_line(1, row) + "\n", "line 2: not a complete row");
    // The same row twice: the same values are harmless, other values are a contradiction.
    CHECK(read(good + "\n" + good + "\n").size() == 1u);
    std::vector<ScanPoint> other = row;
    other[1].impacts = 2;
    refused(good + "\n" + scan_log_line(0, other) + "\n", "line 3: row 0 appears again with other values (first on line 2)");
}

TEST_CASE("scan: a row message carries its row and every value exactly; a short one is refused") {
    ScanRowMessage m;
    m.row = 41;
    m.points = {{1, -0.25, 2, -3e-3, 4.5e-3}, {kNotSettled, NAN, 0, -INFINITY, 1e-300}};
    const std::vector<double> buf = m.pack();
    CHECK(buf.size() == ScanRowMessage::size(2));
    const ScanRowMessage back = ScanRowMessage::unpack(buf, 2);
    CHECK(back.row == 41);
    REQUIRE(back.points.size() == 2);
    for (std::size_t i = 0; i < 2; ++i) {
        const ScanPoint &a = m.points[i], &b = back.points[i];
        CHECK(same_bits(a.period, b.period));
        CHECK(same_bits(a.lyapunov, b.lyapunov));
        CHECK(same_bits(a.impacts, b.impacts));
        CHECK(same_bits(a.xmin, b.xmin));
        CHECK(same_bits(a.xmax, b.xmax));
    }
    CHECK_THROWS_AS(ScanRowMessage::unpack(buf, 3), ScanError);
}

TEST_CASE("scan: the last grid value is HI itself, inside the range the axis was checked in") {
    const ScanAxis a = parse_scan_axis("xI:-0.1:0.1:7");
    CHECK(a.at(6) == 0.1);
    CHECK(a.at(0) == -0.1);
    CHECK(a.at(3) == doctest::Approx(0.0));
}

TEST_CASE("scan: axes and measures are checked, naming the problem") {
    CHECK_THROWS_WITH_AS(parse_scan_axis("omega:0:25"), doctest::Contains("NAME:LO:HI:N"), ScanError);
    CHECK_THROWS_WITH_AS(parse_scan_axis("k:0:25:10"), doctest::Contains("not one of omega, xI, m0e"), ScanError);
    CHECK_THROWS_WITH_AS(parse_scan_axis("omega:5:1:10"), doctest::Contains("HI must exceed LO"), ScanError);
    CHECK_THROWS_WITH_AS(parse_scan_axis("omega:0:25:2.5"), doctest::Contains("integer"), ScanError);
    CHECK_THROWS_WITH_AS(parse_scan_axis("xI:-0.5:0.01:10"), doctest::Contains("[-0.1, 0.1]"), ScanError);
    CHECK_THROWS_WITH_AS(parse_scan_axis("omega:0:1e400:10"), doctest::Contains("not a finite number"), ScanError);
    CHECK_THROWS_WITH_AS(parse_scan_measures("period,colour"), doctest::Contains("'colour'"), ScanError);
    CHECK(parse_scan_measures("lyapunov").lyapunov);
    CHECK_FALSE(parse_scan_measures("lyapunov").period);
}

TEST_CASE("scan: a period-1 orbit hitting the bumper once a period counts exactly one impact per period") {
    // A1C at omega = 24 rad/s with the bumper at -8 mm: the period-1 orbit of the left well touches it once a
    // forcing period (a window of 69 periods counted over 70 gave 0.9857 before).
    ScanSpec spec;
    spec.x = parse_scan_axis("omega:24:24.1:2");
    spec.y = parse_scan_axis("xI:-0.008:-0.008:1");
    spec.measures = parse_scan_measures("period,impacts,xrange");
    for (const char* version : {"A1C", "A1G"}) {
        const std::vector<ScanPoint> pts = scan_row(make_version(version), spec, 0, {});
        REQUIRE(pts.size() == 2u);
        CAPTURE(version);
        CHECK(pts[0].period == 1);
        CHECK(pts[0].impacts == 1.0);
        CHECK(pts[0].xmax >= -0.008 - 1e-4);
    }
}
