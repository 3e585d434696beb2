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

id::FitReport fit(const std::vector<std::string>& names, long begin, long end, double x_highpass_hz = 0.0) {
    std::vector<id::MeasuredData> runs;
    for (const auto& n : names) runs.push_back(load(n, begin, end));
    id::FitOptions fo;
    fo.plots = false;
    fo.fit_baseline = true;
    fo.x_highpass_hz = x_highpass_hz;
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
            CAPTURE(std::string(name));
            if (!(vb >= 0) || !std::isfinite(vb)) return;
            const bool within = std::any_of(r.gate_within.begin(), r.gate_within.end(),
                                            [&](const std::string& w) { return w.rfind(name, 0) == 0; });
            CHECK((va <= vb * (1 + 1e-3) || within));
        };
        check("residual RMS", b.residual_rms_N, a.residual_rms_N);
        check("shooting RMS at the judging horizon", b.shooting_rms_judge_m, a.shooting_rms_judge_m);
        // Past a chaotic record's horizon trajectories part whatever the model: its attractor judges there.
        const bool chaotic = r.data_horizon_measured && !r.data_regular;
        if (!chaotic || r.data_horizon_periods >= 1) check("shooting RMS, 1 period", b.shooting_rms_1_m, a.shooting_rms_1_m);
        if (!chaotic || r.data_horizon_periods >= 10) check("shooting RMS, 10 periods", b.shooting_rms_10_m, a.shooting_rms_10_m);
        if (!chaotic) {
            check("free-run simulation RMS", b.simulation_rms_m, a.simulation_rms_m);
        } else {
            check("attractor: x distribution", b.attractor_x_w1, a.attractor_x_w1);
            check("attractor: v distribution", b.attractor_v_w1, a.attractor_v_w1);
            check("attractor: power spectrum", b.attractor_spectrum_db, a.attractor_spectrum_db);
            if (r.data_well_changes_per_s > 0 && b.attractor_wells_per_s >= 0 && a.attractor_wells_per_s >= 0) {
                const double rd = r.data_well_changes_per_s;
                check("attractor: well changes per second", std::abs(std::log(std::max(b.attractor_wells_per_s, 1e-3) / rd)),
                      std::abs(std::log(std::max(a.attractor_wells_per_s, 1e-3) / rd)));
            }
        }
    }
}

bool names_asymmetry(const id::FitReport& r) {
    for (const auto& f : r.effects_found)
        if (f.id == "even_stiffness" || f.id == "constant_force" || f.id == "magnet_offset") return true;
    return r.wells_from_data.find("an asymmetry between the wells") != std::string::npos;
}

}  // namespace

TEST_CASE("mismatch: the asymmetric rig's pair of wells names an asymmetry, the left well stiffer, mirrored too; never a worse model" *
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
    // The chain centred each run's x; the runs' local laws, tied to one cubic, put them back at their wells, and
    // the model written holds the asymmetry: two wells, the left stiffer and deeper (truth 9.56 and 7.26 Hz,
    // 0.065 and 0.024 (m/s)^2), a positive gain (truth 1.13) and damping.
    REQUIRE(r.run_offsets.size() == 2);
    CHECK(r.run_offsets[0].offset < 0);
    CHECK(r.run_offsets[1].offset > 0);
    REQUIRE(r.wells_after.wells.size() == 2);
    const id::Well& left = r.wells_after.wells[0];
    const id::Well& right = r.wells_after.wells[1];
    CAPTURE(left.omega / (2 * 3.141592653589793));
    CAPTURE(right.omega / (2 * 3.141592653589793));
    CAPTURE(r.after.p.input_gain);
    CHECK(left.omega > right.omega + 3 * std::hypot(left.somega, right.somega));
    CHECK(left.depth > right.depth);
    CHECK(std::abs(left.omega / (2 * 3.141592653589793) - 9.56) < 0.15 * 9.56);
    CHECK(std::abs(right.omega / (2 * 3.141592653589793) - 7.26) < 0.15 * 7.26);
    CHECK(r.after.p.input_gain > 0.5 * 1.13);
    CHECK(r.after.p.input_gain < 2.0 * 1.13);
    CHECK(r.after.p.c > 0);

    // Mirrored (x, v, u -> -x, -v, -u), the right well's run first: put back at mirrored wells, with the same
    // gain and the opposite k2.
    id::MeasuredData run_l = load("asym_left", 4096, 36864), run_r = load("asym_right", 4096, 36864);
    for (id::MeasuredData* d : {&run_l, &run_r}) {
        for (double& x : d->x) x = -x;
        for (double& u : d->u) u = -u;
        for (double& v : d->v) v = -v;
    }
    id::FitOptions fo;
    fo.plots = false;
    fo.fit_baseline = true;
    const id::FitReport m = id::run_fit(id::join_records({run_r, run_l}), id::resolve_fit_model("duffing", id::Forcing::Input), fo);
    REQUIRE(m.run_offsets.size() == 2);
    for (std::size_t k = 0; k < 2; ++k) {
        const id::RunOffset& a = r.run_offsets[k];
        const id::RunOffset& b = m.run_offsets[1 - k];
        CHECK(std::abs(b.offset + a.offset) < 0.1 * a.sigma);   // within a tenth of its own error
        CHECK(b.sigma == doctest::Approx(a.sigma).epsilon(0.05));
    }
    auto base = [](const id::FitReport& f, const char* name) {
        for (const auto& b : f.base_estimates)
            if (b.name == name) return b;
        return id::BaseEstimate{name, NAN, NAN, ""};
    };
    const id::BaseEstimate g = base(r, "gain"), gm = base(m, "gain"), k2 = base(r, "k2"), k2m = base(m, "k2");
    CHECK(gm.value == doctest::Approx(g.value).epsilon(1e-3));
    CHECK(k2m.value == doctest::Approx(-k2.value).epsilon(1e-3));
    CHECK(k2.value > 0);   // the hilltop's origin: the left well stiffer is k2 > 0 (README)
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

TEST_CASE("mismatch: a chaotic record gets a bistable model whose attractor matches the record's" *
          doctest::skip(shared_missing("data/mismatch/asym_chaos_hp0p1.csv.gz"))) {
    // The cubic cannot hold the magnets' wells apart (its equation-error fit is monostable); the generic force
    // of x can, and past the horizon the attractor judges it: the x distribution within a quarter of the
    // record's spread, the well changes within a factor 2, the spectrum within 25 dB. The asymmetric rig's left
    // well is the deeper and stiffer (README: 9.56 vs 7.26 Hz, 0.50 vs 0.19 mJ).
    // The record's own chain declared (x integrated from v, bins below 0.1 Hz zeroed): the free runs are
    // filtered alike, and the report says so.
    const id::FitReport r = fit({"asym_chaos_hp0p1"}, 4096, 86016, 0.1);
    CHECK(r.x_highpass_hz == 0.1);
    never_worse(r);
    CHECK_FALSE(r.data_regular);
    const id::ErrorSummary& a = r.error_after;
    CHECK(a.attractor_x_w1 < 0.25);
    CHECK(a.attractor_x_w1 < r.error_before.attractor_x_w1);
    REQUIRE(r.data_well_changes_per_s > 0);
    CHECK(a.attractor_wells_per_s > 0.5 * r.data_well_changes_per_s);
    CHECK(a.attractor_wells_per_s < 2.0 * r.data_well_changes_per_s);
    CHECK(a.attractor_spectrum_db < 25.0);
    REQUIRE(r.wells_after.wells.size() == 2);
    const id::Well& left = r.wells_after.wells[0];
    const id::Well& right = r.wells_after.wells[1];
    CHECK(left.omega > right.omega + 3 * std::hypot(left.somega, right.somega));
    CHECK(left.depth > right.depth + 3 * std::hypot(left.sdepth, right.sdepth));
    // The base stiffness beside a generic force of x is no finding, and the report says so.
    for (const auto& b : r.base_estimates)
        if (b.name == "k" || b.name == "a3") CHECK(b.stood_in_by.find("unexplained_x") != std::string::npos);
}

TEST_CASE("mismatch: runs that lie at their own wells (a sensor that keeps the offset) are cut into periods, not into one" *
          doctest::skip(shared_missing("data/mismatch/asym_left.csv.gz"))) {
    // The asymmetric pair with each run put back at its well (README: -12.6 and +11.3 mm): the step between
    // the runs once made the record's dominant period longer than either run, no shooting window was left,
    // and the fit ended without a report ("1-period shooting RMS came out nan").
    id::MeasuredData left = load("asym_left", 4096, 36864), right = load("asym_right", 4096, 36864);
    for (double& x : left.x) x -= 0.012648;
    for (double& x : right.x) x += 0.011314;
    id::FitOptions fo;
    fo.plots = false;
    fo.fit_baseline = true;
    const id::FitReport r = id::run_fit(id::join_records({left, right}), id::resolve_fit_model("duffing", id::Forcing::Input), fo);
    CHECK(r.period_s == doctest::Approx(1.0 / 6.5).epsilon(0.02));
    CHECK(std::isfinite(r.error_after.shooting_rms_1_m));
    CHECK(r.data_regular);
    never_worse(r);
}
