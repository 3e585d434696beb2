// The shared data: the three declared synthetic sets come out right (on 40 s of each, to keep the suite
// fast; `impactlab fit` on the whole files gives the same answers), and the Silverbox files load.
#include <doctest/doctest.h>

#include <filesystem>
#include <string>

#include "impactlab/identify.hpp"
#include "shared_data.hpp"

namespace id = impactlab::identify;

namespace {

using impactlab::test::shared_missing;
std::string shared(const std::string& rel) { return impactlab::test::shared_path(rel); }

id::FitReport fit_part(const std::string& file) {
    id::LoadOptions lo;
    lo.row_begin = 30000;   // t = 30 .. 70 s: the 13.5 rad/s plateau with impacts, and the ramp to 16
    lo.row_end = 70000;
    const id::MeasuredData d = id::load_measured(file, lo);
    id::FitOptions fo;
    fo.plots = false;
    return id::run_fit(d, id::resolve_fit_model("A1H", id::Forcing::Unbalance), fo);
}

}  // namespace

TEST_CASE("shared synthetic data: s1 quadratic damping, s2 bumper offset, s3 nothing" *
          doctest::skip(shared_missing("data/synthetic/s1_quadratic_damping.csv.gz"))) {
    const std::string s1 = shared("data/synthetic/s1_quadratic_damping.csv.gz");
    {
        const id::FitReport r = fit_part(s1);
        REQUIRE(r.effects_found.size() == 1);
        CHECK(r.effects_found[0].id == "quadratic_damping");
        CHECK(r.effects_found[0].parameters[0].second == doctest::Approx(4.0).epsilon(0.05));
    }
    {
        const id::FitReport r = fit_part(shared("data/synthetic/s2_bumper_offset.csv.gz"));
        REQUIRE(r.effects_found.size() == 1);
        CHECK(r.effects_found[0].id == "bumper_offset");
        CHECK(r.effects_found[0].parameters[0].second == doctest::Approx(5e-4).epsilon(0.02));
        CHECK(r.error_after.shooting_rms_1_m < 0.1 * r.error_before.shooting_rms_1_m);
    }
    {
        const id::FitReport r = fit_part(shared("data/synthetic/s3_noise_only.csv.gz"));
        CHECK(r.effects_found.empty());
    }
}

namespace {
id::LoadOptions silverbox_columns(long begin, long end, const char* x) {
    id::LoadOptions lo;
    lo.columns.x = x;
    lo.columns.u = "V1";
    lo.rate = 610.35;
    lo.row_begin = begin;
    lo.row_end = end;
    return lo;
}
}  // namespace

TEST_CASE("silverbox: the benchmark files load with an explicit column mapping" *
          doctest::skip(shared_missing("data/real/silverbox/SNLS80mV.csv.gz"))) {
    const std::string f = shared("data/real/silverbox/SNLS80mV.csv.gz");
    const id::MeasuredData d = id::load_measured(f, silverbox_columns(40650, 127400, "V2"));
    CHECK(d.size() == 86750);
    CHECK(d.has_u());
    CHECK(d.t[1] - d.t[0] == doctest::Approx(1.0 / 610.35));
    CHECK_THROWS_AS(id::load_measured(f, silverbox_columns(0, -1, "V3")), id::DataError);
    CHECK(id::load_measured(shared("data/real/silverbox/Schroeder80mV.csv.gz"), silverbox_columns(0, -1, "V2")).size() == 131072);
}
