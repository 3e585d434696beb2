// The bifurcation panel's GL-free half: the progressive hand-over of the diagram and of the Lyapunov strip
// (what the UI takes grows level by level, whole levels only, and ends as the core's own run of the same
// request, bit for bit), cancellation, the omega range check and the sub-range request a box makes.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "../../app/gui/analysis/bifurcation_job.hpp"
#include "impactlab/analysis.hpp"
#include "impactlab/params.hpp"
#include "impactlab/sweep.hpp"

using namespace impactlab;
using namespace impactlab::gui;

namespace {

bool same(const DiagramPoint& a, const DiagramPoint& b) { return a.omega == b.omega && a.x == b.x && a.v == b.v; }

bool same(const std::vector<DiagramPoint>& a, const std::vector<DiagramPoint>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (!same(a[i], b[i])) return false;
    return true;
}

BifRequest small_cf(BifProtocol proto) {
    BifRequest r;
    r.params = make_version("A1H");
    r.protocol = proto;
    r.omega_lo = 8.0;
    r.omega_hi = 14.0;
    r.steps = 30;
    r.transient = 10;
    r.record = 20;
    return r;
}

// What the UI sees polling a job as fast as it can: the size after every take that brought something.
struct Polled {
    std::vector<DiagramPoint> points;
    std::vector<DiagramLevel> judged;   // the levels' verdicts as they came
    std::vector<std::size_t> sizes;
    std::vector<int> levels;
};
Polled poll_until_done(BifurcationJob& job) {
    Polled p;
    for (;;) {
        const bool was_running = job.running();
        const std::size_t before = p.points.size();
        const int lv = job.take_new(p.points, &p.judged);
        if (p.points.size() != before) {
            p.sizes.push_back(p.points.size());
            p.levels.push_back(lv);
        }
        if (!was_running) break;   // everything published before the worker ended has been taken
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    return p;
}

// A request run to its end, polled as the UI polls it.
struct Finished {
    Polled polled;
    std::optional<Diagram> result;
};
Finished run_to_end(const BifRequest& req) {
    BifurcationJob job;
    job.start(req);
    Finished f;
    f.polled = poll_until_done(job);
    f.result = job.take_result();
    return f;
}

}  // namespace

TEST_CASE("the CF diagram arrives level by level and ends as run_cf_sweep of the same request, bit for bit") {
    for (BifProtocol proto : {BifProtocol::CfUp, BifProtocol::CfDown}) {
        const BifRequest req = small_cf(proto);
        BifurcationJob job;
        job.start(req);
        const Polled p = poll_until_done(job);
        const auto result = job.take_result();
        REQUIRE(result.has_value());
        CHECK(job.take_error().empty());
        CHECK_FALSE(result->cancelled);
        // It grew more than once (the UI saw partial diagrams), never shrank, and only by whole levels.
        CHECK(p.sizes.size() >= 2);
        for (std::size_t i = 1; i < p.sizes.size(); ++i) {
            CHECK(p.sizes[i] > p.sizes[i - 1]);
            CHECK(p.levels[i] > p.levels[i - 1]);
        }
        for (std::size_t i = 0; i < p.sizes.size(); ++i)
            CHECK(p.sizes[i] == static_cast<std::size_t>(p.levels[i] * req.record));
        CHECK(p.levels.back() == req.steps);
        // The pieces put together are the result, and the result is the core's run of the same request, its
        // levels judged with the same settle budget (the CLI's default, 10).
        CHECK(same(p.points, result->points));
        CHECK(req.settle == 10);
        const Diagram direct = run_cf_param_sweep(req.params, param_sweep(req), req.transient, req.record, nullptr, {},
                                                  nullptr, req.settle);
        CHECK(same(direct.points, result->points));
        // Every level's verdict arrived with its points, and they are the core's.
        REQUIRE(p.judged.size() == direct.levels.size());
        REQUIRE(result->levels.size() == direct.levels.size());
        int unsettled = 0, settled = 0;
        for (std::size_t j = 0; j < direct.levels.size(); ++j) {
            CHECK(p.judged[j].period == direct.levels[j].period);
            CHECK(p.judged[j].first == direct.levels[j].first);
            CHECK(p.judged[j].count == direct.levels[j].count);
            CHECK(result->levels[j].period == direct.levels[j].period);
            unsettled += direct.levels[j].period == kLevelNotSettled;
            settled += direct.levels[j].period > 0;
        }
        MESSAGE(std::string(bif_protocol_name(proto)), ": ", settled, " levels settled, ", unsettled, " not");
        CHECK(settled > 0);
        // Without a budget the levels are not judged, and the diagram is the protocol's plain run.
        BifRequest plain = req;
        plain.settle = 0;
        const Finished f0 = run_to_end(plain);
        REQUIRE(f0.result.has_value());
        CHECK(f0.polled.judged.empty());
        CHECK(f0.result->levels.empty());
        CHECK(same(run_cf_sweep(req.params, cf_spec(req)).points, f0.result->points));
        // The levels: omega_lo + (hi - lo) j / steps, j = 1..steps, in the sweep's direction.
        const double first = proto == BifProtocol::CfUp ? 8.0 + 6.0 / 30 : 14.0;
        const double last = proto == BifProtocol::CfUp ? 14.0 : 8.0 + 6.0 / 30;
        CHECK(p.points.front().omega == doctest::Approx(first).epsilon(1e-14));
        CHECK(p.points.back().omega == doctest::Approx(last).epsilon(1e-14));
    }
}

TEST_CASE("the paper's range gives the paper's grid: omega_j = 25 j / 300") {
    const CfSpec s = cf_spec(BifRequest{});
    CHECK(s.omega_min == 25.0 / 300.0);
    CHECK(s.omega_max == 25.0);
    CHECK(s.steps == 300);
    CHECK(s.transient == 20);
    CHECK(s.record == 70);
}

TEST_CASE("the EF ramp arrives in chunks and ends as run_ef_ramp, bit for bit") {
    BifRequest req;
    req.params = make_version("A1H");
    req.protocol = BifProtocol::Ef;
    req.omega_hi = 12.0;
    req.ef_rate = 0.02;   // 600 s of ramp: about 570 section points, a few chunks
    const EfSpec spec = ef_spec(req);
    CHECK(spec.omega_max == 12.0);
    CHECK(spec.t_ramp == doctest::Approx(600.0));
    BifurcationJob job;
    job.start(req);
    const Polled p = poll_until_done(job);
    const auto result = job.take_result();
    REQUIRE(result.has_value());
    CHECK(result->points.size() > 256);   // more than one chunk
    for (std::size_t i = 1; i < p.sizes.size(); ++i) CHECK(p.sizes[i] > p.sizes[i - 1]);
    CHECK(same(p.points, result->points));
    CHECK(same(run_ef_ramp(req.params, spec).points, result->points));
}

TEST_CASE("a cancelled diagram keeps exactly the levels it published") {
    BifRequest req = small_cf(BifProtocol::CfUp);
    req.steps = 2000;   // long enough to be cancelled half-way
    BifurcationJob job;
    job.start(req);
    std::vector<DiagramPoint> got;
    int levels = 0;
    for (int i = 0; i < 20000 && levels < 3; ++i) {
        levels = job.take_new(got);
        std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
    REQUIRE(levels >= 3);
    job.cancel();
    job.wait();
    levels = job.take_new(got);
    const auto result = job.take_result();
    REQUIRE(result.has_value());
    CHECK(result->cancelled);
    CHECK(levels < req.steps);
    CHECK(got.size() == static_cast<std::size_t>(levels * req.record));
    CHECK(same(got, result->points));
}

TEST_CASE("a new job drops the old one's feed: nothing of the old diagram arrives after the start") {
    BifRequest a = small_cf(BifProtocol::CfUp);
    a.steps = 2000;
    BifurcationJob job;
    job.start(a);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    BifRequest b = small_cf(BifProtocol::CfUp);
    b.omega_lo = 20.0;
    b.omega_hi = 21.0;
    b.steps = 5;
    job.start(b);
    const Polled p = poll_until_done(job);
    REQUIRE_FALSE(p.points.empty());
    for (const auto& q : p.points) CHECK(q.omega > 20.0);
    CHECK(same(p.points, job.take_result()->points));
}

TEST_CASE("the omega range: 0 <= lo < hi <= 30 rad/s, and a message naming what is wrong") {
    CHECK(check_omega_range(0, 25).empty());
    CHECK(check_omega_range(29.9, 30).empty());
    CHECK(check_omega_range(-1, 5).find("below 0") != std::string::npos);
    CHECK(check_omega_range(3, 31).find("above 30") != std::string::npos);
    CHECK(check_omega_range(5, 5).find("must be below") != std::string::npos);
    CHECK(check_omega_range(9, 4).find("must be below") != std::string::npos);
    CHECK(check_omega_range(NAN, 4).find("not a number") != std::string::npos);
    CHECK(check_omega_range(0, INFINITY).find("not a number") != std::string::npos);
}

TEST_CASE("a box on the diagram asks for its omega range with the same model, protocol, steps and periods") {
    BifRequest base = small_cf(BifProtocol::CfDown);
    base.steps = 200;
    base.params.xI = 0.002;
    const auto r = box_request(base, 14.0, 12.0);   // dragged right to left
    REQUIRE(r.has_value());
    CHECK(r->omega_lo == 12.0);
    CHECK(r->omega_hi == 14.0);
    CHECK(r->steps == 200);
    CHECK(r->transient == base.transient);
    CHECK(r->record == base.record);
    CHECK(r->settle == base.settle);
    CHECK(r->protocol == BifProtocol::CfDown);
    CHECK(r->params.name == base.params.name);
    CHECK(r->params.xI == 0.002);
    // The same 200 levels over the narrower range: 0.01 rad/s apart instead of 0.03.
    const CfSpec s = cf_spec(*r);
    CHECK(s.omega_min == doctest::Approx(12.01));
    CHECK(s.omega_max == 14.0);
    CHECK(s.steps == 200);
    CHECK(s.direction == SweepDirection::Down);
    // Clamped to what the panel allows; a slip narrower than kMinBoxSpan is no box.
    const auto left = box_request(base, -3.0, 2.0);
    REQUIRE(left.has_value());
    CHECK(left->omega_lo == 0.0);
    CHECK(left->omega_hi == 2.0);
    const auto right = box_request(base, 29.0, 35.0);
    REQUIRE(right.has_value());
    CHECK(right->omega_hi == 30.0);
    CHECK_FALSE(box_request(base, 10.0, 10.0 + 0.5 * kMinBoxSpan).has_value());
    CHECK_FALSE(box_request(base, 31.0, 40.0).has_value());   // all beyond 30: nothing left
    CHECK_FALSE(box_request(base, NAN, 3.0).has_value());
    CHECK(check_omega_range(r->omega_lo, r->omega_hi).empty());
}

TEST_CASE("the Lyapunov strip arrives omega by omega and ends as lyapunov_sweep of the same request") {
    LyapunovStripRequest req;
    req.params = make_version("A1H");
    req.omega_lo = 9.0;
    req.omega_hi = 17.0;
    req.steps = 4;
    req.transient = 10;
    req.record = 30;
    LyapunovStripJob job;
    job.start(req);
    std::vector<analysis::LyapunovPoint> got;
    std::vector<std::size_t> sizes;
    for (;;) {
        const bool was_running = job.running();
        const std::size_t before = got.size();
        const int done = job.take_new(got);
        if (got.size() != before) {
            sizes.push_back(got.size());
            CHECK(done == static_cast<int>(got.size()));
        }
        if (!was_running) break;
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    const auto result = job.take_result();
    REQUIRE(result.has_value());
    REQUIRE(result->size() == 4);
    CHECK(sizes.size() >= 2);
    for (std::size_t i = 1; i < sizes.size(); ++i) CHECK(sizes[i] > sizes[i - 1]);
    const auto direct = analysis::lyapunov_sweep(req.params, cf_spec(req));
    REQUIRE(direct.size() == 4);
    REQUIRE(got.size() == 4);
    for (std::size_t i = 0; i < 4; ++i) {
        CHECK(got[i].omega == (*result)[i].omega);
        CHECK(got[i].lambda_max == (*result)[i].lambda_max);
        CHECK(direct[i].omega == (*result)[i].omega);
        CHECK(direct[i].lambda_max == (*result)[i].lambda_max);
        CHECK(direct[i].period == (*result)[i].period);
    }
    CHECK(got.front().omega == doctest::Approx(11.0));   // 9 + 8 * 1/4
    CHECK(got.back().omega == 17.0);
    // A1H: period 1 at 11 rad/s (lambda < 0), chaos at 17 (lambda > 0): the strip's colours mean something.
    CHECK(got.front().lambda_max < 0);
    CHECK(got.back().lambda_max > 0);
}

TEST_CASE("a cancelled Lyapunov strip stops within a level and keeps the omegas it finished") {
    LyapunovStripRequest req;
    req.params = make_version("A1C");   // a compliant bumper: seconds per omega
    req.steps = 60;
    LyapunovStripJob job;
    job.start(req);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const auto t0 = std::chrono::steady_clock::now();
    job.cancel();
    job.wait();
    const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    CHECK(waited < 1.0);   // a level is cut short, not finished (an A1C level takes seconds)
    const auto result = job.take_result();
    REQUIRE(result.has_value());
    CHECK(result->size() < 60);
}

namespace {
// small_cf over xI in [-xI_max, xI_max] [m] at omega = 18 rad/s.
BifRequest small_xI(BifProtocol proto, double xI_max) {
    BifRequest r = small_cf(proto);
    r.over = SweepParam::XI;
    r.lo = -xI_max;
    r.hi = xI_max;
    r.omega = 18.0;
    return r;
}
}  // namespace

TEST_CASE("a diagram over xI at fixed omega arrives level by level, each point at its level's xI, as the core's sweep") {
    BifRequest req = small_xI(BifProtocol::CfDown, 0.004);
    req.steps = 9;
    const Finished f = run_to_end(req);
    const Polled& p = f.polled;
    const auto& result = f.result;
    REQUIRE(result.has_value());
    CHECK(result->over == SweepParam::XI);
    CHECK(p.levels.back() == 9);
    CHECK(same(p.points, result->points));
    const ParamSweep s = param_sweep(req);
    CHECK(s.omega == 18.0);
    CHECK(s.direction == SweepDirection::Down);
    const Diagram direct = run_cf_param_sweep(req.params, s, req.transient, req.record, nullptr, {}, nullptr, req.settle);
    CHECK(same(direct.points, result->points));
    CHECK(p.judged.size() == 9u);
    CHECK(result->levels.size() == 9u);
    // Down from hi to lo, both included (the CLI's --range), record points per level.
    REQUIRE(result->points.size() == 9u * static_cast<std::size_t>(req.record));
    CHECK(result->points.front().omega == 0.004);
    CHECK(result->points.back().omega == -0.004);
    CHECK(swept_range(req) == std::pair{-0.004, 0.004});
    // Over omega the request's levels are cf_spec's: the same sweep as before.
    const BifRequest w = small_cf(BifProtocol::CfUp);
    const ParamSweep sw = param_sweep(w);
    CHECK(sw.lo == cf_spec(w).omega_min);
    CHECK(sw.hi == cf_spec(w).omega_max);
}

TEST_CASE("a box over an xI diagram: the same request over the box's xI, clamped to the rail, narrow drags refused") {
    const BifRequest req = small_xI(BifProtocol::CfUp, 0.01);
    const auto box = box_request(req, 0.003, -0.002);
    REQUIRE(box.has_value());
    CHECK(box->lo == -0.002);
    CHECK(box->hi == 0.003);
    CHECK(box->omega == 18.0);
    CHECK(box->omega_lo == req.omega_lo);   // the omega range is not the box's
    CHECK(box_request(req, -0.5, 0.0)->lo == -kRailHalfTravel);
    CHECK_FALSE(box_request(req, 0.001, 0.00105).has_value());   // 0.05 mm: a click
}
