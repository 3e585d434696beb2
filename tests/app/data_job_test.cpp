// The measured-data panel's GL-free half: the column-mapping fields onto identify's load options, an effect
// subset onto a model, and the worker that runs load / fit / evaluate and hands each result over once.
#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <string>

#include "../../app/gui/data/data_job.hpp"
#include "../../app/gui/window/options.hpp"

using namespace impactlab;
using namespace impactlab::gui;

namespace {

// A short synthetic record of A1H with quadratic damping (cq = 4) in the left well.
std::shared_ptr<const identify::MeasuredData> short_record(double cq) {
    identify::Model m = identify::resolve_fit_model("A1H", identify::Forcing::Unbalance);
    if (cq != 0) identify::apply_effect(m, "quadratic_damping", {{"cq", cq}});
    identify::SynthOptions o;
    o.duration = 12.0;
    o.knot_t = {0.0};
    o.knot_omega = {16.0};
    return std::make_shared<const identify::MeasuredData>(identify::synthesize(m, o));
}

}  // namespace

TEST_CASE("data panel: column fields map onto the loader's options") {
    DataColumns c;
    identify::LoadOptions o = load_options_from(c);
    CHECK(o.columns.t.empty());
    CHECK(o.columns.x.empty());
    CHECK(o.columns.phi.empty());
    CHECK(o.columns.u.empty());
    CHECK(o.rate == 0.0);

    // (Built whole: GCC 12's -Wrestrict misfires on assigning a literal to a std::string member at -O3.)
    const DataColumns mapped{std::string(), std::string("pos"), std::string("3"), false, 500.0, 1e-3};
    o = load_options_from(mapped);
    CHECK(o.columns.x == "pos");
    CHECK(o.columns.phi == "3");
    CHECK(o.rate == 500.0);
    CHECK(o.x_scale == 1e-3);

    // A non-standard file: no time column, x in mm, the angle in column 3.
    const std::string text = "pos,junk,angle\n-10.0,1,0.0\n-10.1,1,0.02\n-10.2,1,0.04\n-10.3,1,0.06\n";
    o.min_samples = 2;
    const identify::MeasuredData d = identify::parse_measured(text, "mem.csv", o);
    REQUIRE(d.size() == 4);
    CHECK(d.has_phi());
    CHECK(d.t[2] == doctest::Approx(2.0 / 500.0));
    CHECK(d.x[1] == doctest::Approx(-10.1e-3));

    // The forcing as a measured input u: with both columns present, phi is not taken.
    DataColumns cu;
    cu.forcing_is_u = true;
    o = load_options_from(cu);
    o.min_samples = 2;
    const identify::MeasuredData du = identify::parse_measured("t,x,phi,u\n0,0,0,1\n0.1,0,0,2\n0.2,0,0,3\n", "mem.csv", o);
    CHECK(du.has_u());
    CHECK_FALSE(du.has_phi());
    CHECK(model_for_data("A1H", du).forcing == identify::Forcing::Input);

    // A decay whose file has an unused column: "a free run" reads it as one (u = 0), else it is refused.
    DataColumns cf;
    const std::string decay = "t,x,temperature\n0,1,20\n0.1,0.5,20\n0.2,-0.2,20\n";
    o = load_options_from(cf);
    o.min_samples = 2;
    CHECK_THROWS_AS(identify::parse_measured(decay, "mem.csv", o), identify::DataError);
    cf.free_run = true;
    o = load_options_from(cf);
    o.min_samples = 2;
    const identify::MeasuredData df = identify::parse_measured(decay, "mem.csv", o);
    CHECK(df.free_run);
    CHECK(model_for_data("duffing", df).forcing == identify::Forcing::Input);

    // A mapping that names nothing is refused by the loader, with the problem.
    const DataColumns nothing{std::string(), std::string("nope"), std::string(), true, 0.0, 1.0};
    o = load_options_from(nothing);
    CHECK_THROWS_AS(identify::parse_measured("t,x,u\n0,0,1\n", "mem.csv", o), identify::DataError);
}

TEST_CASE("data panel: an effect subset is the baseline with those effects applied") {
    identify::FitReport r;
    r.before = identify::resolve_fit_model("A1H", identify::Forcing::Unbalance);
    identify::FoundEffect q;
    q.id = "quadratic_damping";
    q.parameters = {{"cq", 4.0}};
    identify::FoundEffect b;
    b.id = "bumper_offset";
    b.parameters = {{"dx", 5e-4}};
    r.effects_found = {q, b};
    CHECK(all_effects_mask(r) == 3u);

    const identify::Model none = model_for_subset(r, 0);
    CHECK(none.p.effects.empty());
    CHECK(none.p.xI == r.before.p.xI);

    const identify::Model only_q = model_for_subset(r, 1);
    REQUIRE(only_q.p.effects.size() == 1);
    CHECK(only_q.p.effects[0].p[0] == 4.0);
    CHECK(only_q.p.xI == r.before.p.xI);

    const identify::Model only_b = model_for_subset(r, 2);
    CHECK(only_b.p.effects.empty());
    CHECK(only_b.p.xI == doctest::Approx(r.before.p.xI + 5e-4));

    const identify::Model both = model_for_subset(r, 3);
    CHECK(both.p.effects.size() == 1);
    CHECK(both.p.xI == doctest::Approx(r.before.p.xI + 5e-4));
    CHECK(both.p.name.find("quadratic_damping") != std::string::npos);

    identify::FitReport empty;
    CHECK(all_effects_mask(empty) == 0u);

    identify::FoundEffect bad;
    bad.id = "no_such_effect";
    r.effects_found.push_back(bad);
    CHECK_THROWS(model_for_subset(r, 4));
}

TEST_CASE("data panel: robust extent ignores outliers and non-finite values") {
    std::vector<double> a(1000);
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = static_cast<double>(i) / 999.0;
    a[3] = 1e9;
    a[4] = std::nan("");
    const auto [lo, hi] = robust_extent({&a}, 0.01, 0.0);
    CHECK(lo >= 0.0);
    CHECK(hi <= 1.0);
    const std::vector<double> none;
    CHECK(robust_extent({&none}, 0.01, 0.1) == std::pair<double, double>{0.0, 0.0});
}

TEST_CASE("data panel: the worker hands results over whole, once; cancelled ones are discarded") {
    DataJob job;
    // A broken path: the loader's message comes back as the result's error.
    job.start_load("/nonexistent/run.csv", {});
    REQUIRE(job.wait(30.0));
    auto r = job.take_result();
    REQUIRE(r);
    CHECK(r->kind == DataJobResult::Kind::Load);
    CHECK_FALSE(r->error.empty());
    CHECK_FALSE(job.take_result());

    const auto data = short_record(4.0);
    identify::FitOptions fo;
    fo.plots = false;
    const identify::Model base = model_for_data("A1H", *data);

    // Cancelled: nothing arrives, and a new job can start at once.
    job.start_evaluate(data, base, fo, 0);
    job.cancel();
    CHECK_FALSE(job.running());
    CHECK_FALSE(job.take_result());

    // The fit, then the subsets "none" and "all" evaluated: they match the fit's before and after. While it
    // runs it reports a stage of the core's loop; at its end the whole fraction.
    job.start_fit(data, base, fo);
    CHECK(job.running());
    REQUIRE(job.wait(120.0));
    CHECK(job.fit_fraction() == doctest::Approx(1.0));
    CHECK(job.fit_stage() == static_cast<int>(identify::FitStage::Errors));
    r = job.take_result();
    REQUIRE(r);
    REQUIRE(r->error.empty());
    REQUIRE(r->report);
    const auto report = r->report;
    REQUIRE(!report->effects_found.empty());
    CHECK(report->effects_found[0].id == "quadratic_damping");

    const std::uint32_t all = all_effects_mask(*report);
    job.start_evaluate(data, model_for_subset(*report, all), fo, all);
    REQUIRE(job.wait(120.0));
    r = job.take_result();
    REQUIRE(r);
    CHECK(r->kind == DataJobResult::Kind::Evaluate);
    CHECK(r->mask == all);
    CHECK(r->errors.shooting_rms_10_m == doctest::Approx(report->error_after.shooting_rms_10_m).epsilon(0.05));
    CHECK(r->errors.shooting_rms_10_m < report->error_before.shooting_rms_10_m);

    // A superseded job's result never shows up: only the newest one does.
    job.start_evaluate(data, model_for_subset(*report, all), fo, all);
    job.start_evaluate(data, model_for_subset(*report, 0), fo, 0);
    REQUIRE(job.wait(120.0));
    r = job.take_result();
    REQUIRE(r);
    CHECK(r->mask == 0u);
    CHECK(r->errors.residual_rms_N == doctest::Approx(report->error_before.residual_rms_N).epsilon(0.05));
}

TEST_CASE("data panel: --data FILE on the command line") {
    CHECK(parse_options({"--data", "run.csv.gz"}).data == "run.csv.gz");
    CHECK(parse_options({}).data.empty());
    CHECK_THROWS_AS(parse_options({"--data"}), OptionsError);
}

TEST_CASE("data panel: the core's CLI flags are worded as the panel's fields") {
    using impactlab::gui::panel_wording;
    CHECK(panel_wording("x beyond the rail; positions in mm? --x-scale 1e-3") ==
          "x beyond the rail; positions in mm? \"x scale\" (Column mapping) 1e-3");
    CHECK(panel_wording("no time column 't' and no sample rate (give --rate HZ or map --t-col)") ==
          "no time column 't' and no sample rate (give a sample rate (Column mapping) or map the time column (Column mapping))");
    CHECK(panel_wording("both: say which is the forcing (--phi-col or --u-col)") ==
          "both: say which is the forcing (the forcing column and \"forcing is an input u\" (Column mapping))");
    CHECK(panel_wording("map one with --phi-col or --u-col, or declare a free run with --free)") ==
          "map one with the forcing column and \"forcing is an input u\" (Column mapping), or declare a free run with \"a free run\" (Column mapping))");
    // No field in the panel: the flag is named as the command line's.
    CHECK(panel_wording("a corrupt sample; remove the row or select rows with --rows") ==
          "a corrupt sample; remove the row or select rows with the command line's --rows");
    CHECK(panel_wording("plain message, x - y -- nothing") == "plain message, x - y -- nothing");
}
