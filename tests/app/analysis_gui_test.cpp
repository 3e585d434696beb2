// The visualiser's analysis views, GL-free half: a scan CSV read back as a plane (and its errors naming file
// and line), the click-to-parameter mapping, where the bifurcation diagram cuts a plane, and the workers
// (continuation, plane, basins) handing their results over once, cancelled or failed.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "../../app/gui/analysis/analysis_jobs.hpp"
#include "../../app/gui/analysis/plane_curves.hpp"
#include "../../app/gui/analysis/plane_data.hpp"
#include "impactlab/params.hpp"
#include "impactlab/scan.hpp"

using namespace impactlab;
using namespace impactlab::gui;

namespace {

std::string temp_file(const std::string& name, const std::string& text) {
    const std::string path = "/tmp/impactlab_analysis_gui_test_" + name;
    std::ofstream(path) << text;
    return path;
}

// The message load_plane_csv throws for a file, or "" when it loads.
std::string load_error(const std::string& path) {
    try {
        load_plane_csv(path);
    } catch (const PlaneError& e) {
        return e.what();
    }
    return "";
}

// A plane of the given axes (no measures): what the click and cut mappings look at.
PlaneData grid(std::string x, std::string y, std::vector<double> xs, std::vector<double> ys) {
    return PlaneData{"test", std::move(x), std::move(y), std::move(xs), std::move(ys), {}, {}};
}

ScanSpec small_spec() {
    ScanSpec s;
    s.x = parse_scan_axis("omega:8:14:5");
    s.y = parse_scan_axis("xI:-0.004:0.004:3");
    s.measures = parse_scan_measures("period,impacts,xrange");
    s.transient = 10;
    s.record = 20;
    return s;
}

}  // namespace

TEST_CASE("a scan CSV written by the core reads back as the same plane") {
    const Params p = make_version("A1C");
    const ScanSpec spec = small_spec();
    std::vector<std::vector<ScanPoint>> rows;
    for (int j = 0; j < spec.y.n; ++j) rows.push_back(scan_row(p, spec, j));
    std::ostringstream csv;
    write_scan_csv(spec, rows, csv);
    const PlaneData loaded = load_plane_csv(temp_file("ok.csv", csv.str()));
    const PlaneData direct = plane_from_scan(spec, rows, "computed");
    CHECK(loaded.x_name == "omega");
    CHECK(loaded.y_name == "xI");
    REQUIRE(loaded.nx() == 5);
    REQUIRE(loaded.ny() == 3);
    CHECK(loaded.measures == direct.measures);
    CHECK(loaded.measures == std::vector<std::string>{"period", "impacts", "xmin", "xmax"});
    CHECK(loaded.xs == direct.xs);
    CHECK(loaded.ys == direct.ys);
    CHECK(loaded.values == direct.values);   // printed to round-trip: bit-identical
    // The period-1 left well at omega = 8 is what the sweep shows there.
    CHECK(loaded.values[0][0] == 1.0);
}

TEST_CASE("a bad plane CSV names the file and the line") {
    const std::string head = "omega,xI,period\n";
    CHECK(load_error("/nonexistent/plane.csv") == "/nonexistent/plane.csv: cannot read it (No such file or directory)");
    const std::string empty = temp_file("empty.csv", "");
    CHECK(load_error(empty).rfind(empty + ":0: empty file", 0) == 0);
    const std::string bad_head = temp_file("head.csv", "x,y,period\n1,2,3\n");
    CHECK(load_error(bad_head).rfind(bad_head + ":1: the header 'x,y,period' does not start with two different axes", 0) == 0);
    const std::string fields = temp_file("fields.csv", head + "1,0,1\n2,0\n");
    CHECK(load_error(fields) == fields + ":3: expected 3 fields (3 columns in the header), got 2");
    const std::string nan = temp_file("nan.csv", head + "1,0,1\n2,0,1\n1,1,x7\n");
    CHECK(load_error(nan) == nan + ":4: 'x7' in column period is not a number");
    const std::string cut = temp_file("cut.csv", head + "1,0,1\n2,0,1\n3,0,1\n1,1,1\n2,1,2\n");
    CHECK(load_error(cut).rfind(cut + ":6: the last row (xI = 1.000000, begun on line 5) has 2 of 3 points", 0) == 0);
    const std::string off = temp_file("off.csv", head + "1,0,1\n2,0,1\n1,1,1\n2.5,1,1\n");
    CHECK(load_error(off).rfind(off + ":5: (2.5, 1) is not on the grid", 0) == 0);
    const std::string down = temp_file("down.csv", head + "1,0,1\n2,0,1\n1,-1,1\n2,-1,1\n");
    CHECK(load_error(down) == down + ":4: xI = -1 does not increase from row to row (the row before began on line 2)");
    const std::string back = temp_file("back.csv", head + "2,0,1\n1,0,1\n");
    CHECK(load_error(back).rfind(back + ":3: omega = 1 does not increase along the row", 0) == 0);
    const std::string none = temp_file("none.csv", head + "\n");
    CHECK(load_error(none) == none + ":2: no data rows after the header");
    // Blank lines and CRLF are tolerated.
    CHECK(load_error(temp_file("crlf.csv", "omega,xI,period\r\n1,0,1\r\n\r\n2,0,2\r\n")) == "");
}

TEST_CASE("a click on the plane picks the cell and sets the axes that are live parameters") {
    PlaneData p = grid("omega", "xI", {10, 11, 12, 13}, {-0.01, 0.0, 0.01});
    // Cells are equal slices of the area; fy runs from the bottom.
    auto c = plane_pick(p, 0.0, 0.0);
    REQUIRE(c);
    CHECK(c->i == 0);
    CHECK(c->j == 0);
    c = plane_pick(p, 1.0, 1.0);   // the far corner belongs to the last cell
    REQUIRE(c);
    CHECK(c->i == 3);
    CHECK(c->j == 2);
    c = plane_pick(p, 0.62, 0.5);
    REQUIRE(c);
    CHECK(c->i == 2);
    CHECK(c->j == 1);
    CHECK(c->x == 12);
    CHECK(c->y == 0.0);
    CHECK_FALSE(plane_pick(p, -0.01, 0.5));
    CHECK_FALSE(plane_pick(p, 0.5, 1.01));
    const PlaneClick k = plane_click(p, *c);
    REQUIRE(k.omega);
    REQUIRE(k.xI);
    CHECK(*k.omega == 12);
    CHECK(*k.xI == 0.0);
    CHECK(k.ignored.empty());
    // (m0e, omega): omega is set, m0e is named as not live.
    p = grid("m0e", "omega", {0.01, 0.03}, {12, 13, 14});
    const PlaneClick m = plane_click(p, PlaneCell{1, 2, 0.03, 14.0});
    CHECK(m.omega == 14.0);
    CHECK_FALSE(m.xI);
    CHECK(m.ignored == "m0e");
}

TEST_CASE("the bifurcation diagram cuts the plane along omega at the current xI") {
    // Cells from 9.5 to 13.5 in omega, -0.015 to 0.015 in xI.
    PlaneData p = grid("omega", "xI", {10, 11, 12, 13}, {-0.01, 0.0, 0.01});
    auto s = diagram_cut(p, 0.0, 25.0, 0.002, 0.025);
    REQUIRE(s);
    CHECK(s->x0 == 9.5);
    CHECK(s->x1 == 13.5);
    CHECK(s->y0 == 0.002);
    CHECK(s->y1 == 0.002);
    s = diagram_cut(p, 11.0, 12.0, 0.0, 0.025);
    REQUIRE(s);
    CHECK(s->x0 == 11.0);
    CHECK(s->x1 == 12.0);
    CHECK_FALSE(diagram_cut(p, 0.0, 25.0, 0.02, 0.025));   // xI off the plane
    CHECK_FALSE(diagram_cut(p, 14.0, 25.0, 0.0, 0.025));   // omega range beside it
    // Axes swapped: a vertical line.
    p = grid("xI", "omega", {-0.01, 0.0, 0.01}, {10, 11, 12, 13});
    s = diagram_cut(p, 0.0, 25.0, 0.002, 0.025);
    REQUIRE(s);
    CHECK(s->x0 == 0.002);
    CHECK(s->x1 == 0.002);
    CHECK(s->y0 == 9.5);
    CHECK(s->y1 == 13.5);
    // No omega axis: the diagram is one point of the plane.
    p = grid("xI", "m0e", {-0.01, 0.0, 0.01}, {0.02, 0.03});
    s = diagram_cut(p, 0.0, 25.0, 0.002, 0.025);
    REQUIRE(s);
    CHECK(s->x0 == s->x1);
    CHECK(s->y0 == 0.025);
}

TEST_CASE("the basins job hands its result over once; a failing job hands over its error") {
    const Params p = make_version("A1G");
    analysis::BasinSpec spec = basin_request(p, 13.0, 6, 1);
    CHECK(spec.x_max == 0.0);   // up to the bumper at xI = 0
    CHECK(spec.x_min == -0.03);
    Job<analysis::BasinResult> job;
    job.start([p, spec](Progress& prog) { return analysis::compute_basins(p, spec, &prog); });
    job.wait();
    CHECK_FALSE(job.running());
    CHECK(job.progress() == doctest::Approx(1.0));
    auto r = job.take_result();
    REQUIRE(r);
    CHECK(r->label.size() == 36u);
    for (int l : r->label) CHECK(l >= 0);
    CHECK_FALSE(r->attractors.empty());
    CHECK_FALSE(job.take_result());   // once
    CHECK(job.take_error().empty());

    spec.nx = 0;   // compute_basins refuses an empty grid
    job.start([p, spec](Progress& prog) { return analysis::compute_basins(p, spec, &prog); });
    job.wait();
    CHECK_FALSE(job.take_result());
    CHECK_FALSE(job.take_error().empty());
    CHECK(job.take_error().empty());   // once
}

TEST_CASE("a cancelled plane keeps the rows it finished and says so") {
    const Params p = make_version("A1C");
    PlaneRequest req;
    req.nx = 40;
    req.ny = 200;   // far more than finishes before the cancel
    req.threads = 1;
    Job<PlaneData> job;
    job.start([p, req](Progress& prog) { return compute_plane(p, "A1C", req, prog); });
    job.cancel();
    job.wait();
    auto r = job.take_result();
    REQUIRE(r);
    CHECK(r->source == "computed: A1C (cancelled, partial)");
    CHECK(r->nx() == 40);
    CHECK(r->ny() == 200);
    CHECK(std::isnan(r->values[0].back()));   // the last row was never computed
}

TEST_CASE("the continued branches over the diagram carry the first period doubling of A1C") {
    const Params p = make_version("A1C");
    Progress prog;
    const ContinuationOverlay o = compute_continuation(p, 9.0, 11.5, prog);
    CHECK_FALSE(o.cancelled);
    CHECK(o.omega_lo == 9.0);
    // The sweep's transition 10.75-10.83 (docs/analysis.md: 10.8613), far more precisely than its grid.
    const analysis::BifPoint* pd = nullptr;
    for (const auto& q : o.points)
        if (q.kind == analysis::BifKind::PeriodDoubling && q.period == 1) pd = &q;
    REQUIRE(pd);
    CHECK(pd->param == doctest::Approx(10.8613).epsilon(1e-4));
    // Period 1: one curve, stable below the doubling and unstable above it; period 2: two curves.
    int p1 = 0, p2 = 0;
    for (const BranchCurve& c : o.curves) {
        REQUIRE(c.param.size() == c.x.size());
        REQUIRE(c.param.size() == c.stable.size());
        if (c.period == 1) {
            ++p1;
            for (std::size_t i = 0; i < c.param.size(); ++i) {
                if (c.param[i] < pd->param - 1e-3) CHECK(c.stable[i]);
                if (c.param[i] > pd->param + 1e-3) CHECK_FALSE(c.stable[i]);
            }
        }
        if (c.period == 2) ++p2;
    }
    CHECK(p1 >= 1);
    CHECK(p2 >= 2);
    CHECK(p2 % 2 == 0);   // a period-2 branch is drawn as its two section points
}

TEST_CASE("a curve's start reads as auto or as a point continue prints, and anything else is refused") {
    auto a = parse_curve_start("auto");
    REQUIRE(a);
    CHECK(a->from == CurveStart::From::Auto);
    auto p = parse_curve_start("9.60049626,-0.0156163,-0.00744857");
    REQUIRE(p);
    CHECK(p->from == CurveStart::From::Point);
    CHECK(p->omega == 9.60049626);
    CHECK(p->period == 1);
    CHECK(curve_start_text(*p) == "9.60049626,-0.0156163,-0.00744857,1");
    auto k = parse_curve_start("9.6,-0.0156,-0.0074,2");
    REQUIRE(k);
    CHECK(k->period == 2);
    for (const char* bad : {"", "9.6,abc", "9.6,-0.0156", "9.6,-0.0156,-0.0074,0.5", "-1,0,0", "9.6,0,0,1,2", "9.6,0,0x",
                            // outside the physical range: omega below 0.05 rad/s, off the rail, too fast, not finite
                            "1e-300,-0.0157,0.0023", "1e-6,-0.0157,0.0023", "1e300,1e300,0", "9.6,0.5,0", "9.6,0,1e308", "nan,0,0"})
        CHECK_MESSAGE(!parse_curve_start(bad), bad);
}

TEST_CASE("the plane's curves refuse a plane without omega across, and a grazing without a bumper") {
    PlaneData pl;
    pl.x_name = "xI";
    pl.y_name = "m0e";
    pl.xs = {-0.01, 0.0};
    pl.ys = {0.02, 0.03};
    PlaneCurves curves;
    CHECK(curves.start(analysis::BifKind::Fold, pl, make_version("A1G"), "A1G", CurveStart{}) ==
          "fold curve: the plane's axes must be omega and xI or m0e");
    pl.x_name = "omega";
    pl.y_name = "xI";
    pl.xs = {8.5, 10.5};
    pl.ys = {-0.007, -0.004};
    Params free = make_version("A1G");
    free.impact = find_impact("none");
    CHECK(curves.start(analysis::BifKind::Grazing, pl, free, "A1G", CurveStart{}) == "grazing curve: A1G has no bumper");
    CHECK_FALSE(curves.any_running());
}
