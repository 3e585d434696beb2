// The scan CSV read back (core/src/scan/scan_csv.cpp): what write_scan_csv writes comes back as the same
// grid, and a file that is not a grid is refused with its line.
#include <doctest/doctest.h>

#include <sstream>

#include "impactlab/scan.hpp"

using namespace impactlab;

TEST_CASE("scan csv: write_scan_csv's text reads back as the same grid") {
    ScanSpec spec;
    spec.x = {ScanParam::Omega, 5.0, 7.0, 3};
    spec.y = {ScanParam::XI, -0.01, 0.01, 2};
    spec.measures.period = true;
    spec.measures.impacts = true;
    std::vector<std::vector<ScanPoint>> rows(2, std::vector<ScanPoint>(3));
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 3; ++i) {
            rows[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)].period = 1 + i + 3 * j;
            rows[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)].impacts = 0.1 * (i - j) + 1.0 / 3.0;
        }
    std::stringstream csv;
    write_scan_csv(spec, rows, csv);
    const ScanGrid g = read_scan_csv(csv, "mem.csv");
    CHECK(g.x_name == "omega");
    CHECK(g.y_name == "xI");
    REQUIRE(g.xs.size() == 3);
    REQUIRE(g.ys.size() == 2);
    CHECK(g.xs[1] == doctest::Approx(6.0));
    CHECK(g.ys[1] == doctest::Approx(0.01));
    REQUIRE(g.measures == std::vector<std::string>{"period", "impacts"});
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 3; ++i) {
            const std::size_t c = static_cast<std::size_t>(j * 3 + i);
            CHECK(g.values[0][c] == rows[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)].period);
            CHECK(g.values[1][c] == rows[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)].impacts);   // %.17g round-trips
        }
}

TEST_CASE("scan csv: a file that is not a grid is refused with its source and line") {
    std::istringstream bad_header("x,y,period\n1,2,3\n");
    CHECK_THROWS_WITH_AS(read_scan_csv(bad_header, "a.csv"), doctest::Contains("a.csv:1: "), ScanCsvError);
    std::istringstream short_row("omega,xI,period\n1,0,1\n2,0,1\n1,1,1\n");
    CHECK_THROWS_WITH_AS(read_scan_csv(short_row, "b.csv"), doctest::Contains("b.csv:4: the last row"), ScanCsvError);
    std::istringstream not_number("omega,xI,period\n1,0,x\n");
    CHECK_THROWS_WITH_AS(read_scan_csv(not_number, "c.csv"), doctest::Contains("c.csv:2: 'x' in column period is not a number"),
                         ScanCsvError);
}
