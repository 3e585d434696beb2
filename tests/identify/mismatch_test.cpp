// The loop on records whose physics the model only approximates (../shared/data/mismatch: a bistable
// magneto-elastic cantilever with two modes, a non-polynomial magnetic force, piezo coupling and a high-passed
// measurement chain, fitted with the 1-DOF Duffing model forced by the measured input): the model written is
// never worse on any printed error, the wells measured from the data tell an asymmetric rig from a symmetric
// one, and a chaotic record's verdict says the model misses something. 16-20 s of each record.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "impactlab/identify.hpp"
#include "shared_data.hpp"

namespace id = impactlab::identify;
using impactlab::test::shared_missing;
using impactlab::test::shared_path;

namespace {

id::MeasuredData load(const std::string& name, long begin, long end) {
    id::LoadOptions lo;
    lo.columns.u = "u";
    lo.row_begin = begin;
    lo.row_end = end;
    return id::load_measured(shared_path("data/mismatch/" + name + ".csv.gz"), lo);
}

id::FitReport fit(const std::vector<std::string>& names, long begin, long end) {
    std::vector<id::MeasuredData> runs;
    for (const auto& n : names) runs.push_back(load(n, begin, end));
    id::FitOptions fo;
    fo.plots = false;
    fo.fit_baseline = true;
    return id::run_fit(id::join_records(runs), id::resolve_fit_model("duffing", id::Forcing::Input), fo);
}

// Every error the report prints is no higher after than before, or rose within its scatter and is said so.
void never_worse(const id::FitReport& r) {
    const id::ErrorSummary& a = r.error_after;
    // Against the model given, and against the fitted baseline when the report prints it.
    std::vector<const id::ErrorSummary*> refs{&r.error_before};
    if (r.baseline_column) refs.push_back(&r.error_baseline);
    for (const id::ErrorSummary* ref : refs) {
        const id::ErrorSummary& b = *ref;
        auto check = [&](const char* name, double vb, double va) {
            CAPTURE(name);
            if (!(vb >= 0) || !std::isfinite(vb)) return;
            const bool within = std::any_of(r.gate_within.begin(), r.gate_within.end(),
                                            [&](const std::string& w) { return w.rfind(name, 0) == 0; });
            CHECK((va <= vb * (1 + 1e-3) || within));
        };
        check("residual RMS", b.residual_rms_N, a.residual_rms_N);
        check("shooting RMS, 1 period", b.shooting_rms_1_m, a.shooting_rms_1_m);
        check("shooting RMS, 10 periods", b.shooting_rms_10_m, a.shooting_rms_10_m);
        check("shooting RMS at the judging horizon", b.shooting_rms_judge_m, a.shooting_rms_judge_m);
        check("free-run simulation RMS", b.simulation_rms_m, a.simulation_rms_m);
    }
}

bool names_asymmetry(const id::FitReport& r) {
    for (const auto& f : r.effects_found)
        if (f.id == "even_stiffness" || f.id == "constant_force" || f.id == "magnet_offset") return true;
    return r.wells_from_data.find("an asymmetry between the wells") != std::string::npos;
}

}  // namespace

TEST_CASE("mismatch: the asymmetric rig's pair of wells names an asymmetry, the left well stiffer; never a worse model" *
          doctest::skip(shared_missing("data/mismatch/asym_left.csv.gz"))) {
    const id::FitReport r = fit({"asym_left", "asym_right"}, 4096, 36864);
    never_worse(r);
    REQUIRE(r.data_wells.size() == 2);
    CHECK(r.data_wells[0].side == "left");
    CHECK(r.data_wells[1].side == "right");
    CHECK(r.data_wells[0].omega > r.data_wells[1].omega);
    CHECK(names_asymmetry(r));
    CHECK(r.wells_from_data.find("the left well is stiffer") != std::string::npos);
    CHECK(r.wells_from_data.find("k2 > 0") != std::string::npos);
    CHECK(r.data_regular);   // intra-well records: judged over whole periods, not as chaos
    CHECK(r.horizon_periods >= 1.0);
    CHECK(r.verdict.find("misses something") != std::string::npos);
}

TEST_CASE("mismatch: the symmetric rig's pair names no asymmetry; never a worse model" *
          doctest::skip(shared_missing("data/mismatch/sym_left.csv.gz"))) {
    const id::FitReport r = fit({"sym_left", "sym_right"}, 4096, 36864);
    never_worse(r);
    REQUIRE(r.data_wells.size() == 2);
    CHECK(r.data_wells[0].side == "left");
    CHECK(r.data_wells[1].side == "right");
    CHECK_FALSE(names_asymmetry(r));
    CHECK(r.wells_from_data.find("no asymmetry") != std::string::npos);
}

TEST_CASE("mismatch: a chaotic record is judged within its own horizon and its verdict says the model misses something" *
          doctest::skip(shared_missing("data/mismatch/sym_chaos_hp0p1.csv.gz"))) {
    const id::FitReport r = fit({"sym_chaos_hp0p1"}, 4096, 45056);
    never_worse(r);
    CHECK(r.data_horizon_measured);
    CHECK_FALSE(r.data_regular);
    CHECK(r.data_horizon_periods < 10.0);
    CHECK(r.verdict.find("misses something") != std::string::npos);
    CHECK(r.verdict.find("at its noise floor") == std::string::npos);
}

TEST_CASE("mismatch: an intra-well record keeps its fitted well, and a frequency it cannot pin is said to be so" *
          doctest::skip(shared_missing("data/mismatch/sym_right.csv.gz"))) {
    // A steady oscillation in one well: its x density has two humps (the turning points), which are no pair of
    // wells, so the baseline fit stands. On one forcing frequency k trades off against the gain: the model's
    // frequency is either the truth's (8.33 Hz, the README's, within 15 %) or the report says it is not pinned.
    const id::FitReport r = fit({"sym_right"}, 4096, 36864);
    never_worse(r);
    for (const std::string& n : r.notes) CHECK(n.find("a record that changes wells") == std::string::npos);
    CHECK(r.base_estimates.size() >= 2);
    REQUIRE(r.wells_after.wells.size() == 1);
    const double f = r.wells_after.wells[0].omega / (2 * 3.141592653589793);
    CAPTURE(f);
    CAPTURE(r.well_frequency);
    CHECK((std::abs(f - 8.33) <= 0.15 * 8.33 || r.well_frequency.find("not identifiable") != std::string::npos));
    // A model of this well, not the placeholder given: one period's shooting error within a tenth of the
    // record's 2.96 mm peak to peak (the model given misses by more than the motion).
    CHECK(r.error_after.shooting_rms_1_m < 2.96e-4);
}
