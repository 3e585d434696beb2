// Behaviour pinned: the five CF diagrams of Fig. 3 (impactlab bifurcation --sweep up, the CLI's defaults),
// level by level (tests/golden/cf_levels.json), and the fit reports of the shared synthetic data (40 s of each,
// as shared_data_test fits them, tests/golden/fit_summaries.json), compared as numbers within stated
// tolerances, so they hold on any x86-64 whatever libm's processor-specific paths. A change of behaviour that
// is meant regenerates the files, and the commit shows the numbers that moved:
//
//   IMPACTLAB_UPDATE_GOLDEN=1 build/bin/impactlab_tests -ts=golden
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "../identify/shared_data.hpp"
#include "impactlab/identify.hpp"
#include "impactlab/params_json.hpp"
#include "impactlab/sweep.hpp"

namespace id = impactlab::identify;

TEST_SUITE("golden") {

// A CF diagram level by level (one level per omega): a level by its extremes within 1e-5 m; a chaotic one (more
// than 16 distinct section values on both sides) by its extremes and mean within a tenth of the diagram's span,
// since past the horizon the last bits of libm choose which points a chaotic level shows. Up to 5 % of the
// levels may differ: those next to a bifurcation or where attractors coexist, where the sweep's 20 transient
// periods may end on either side (with processor features masked, 2 to 6 of each diagram's 300 levels moved).
constexpr double kLevelTol = 1e-6;   // [m]
constexpr double kChaosTol = 0.1;    // of the diagram's span
constexpr double kLevelsAllowedToDiffer = 0.05;

nlohmann::json diagram_summary(const impactlab::Diagram& d) {
    std::map<double, std::vector<double>> by_omega;
    for (const auto& p : d.points) by_omega[p.omega].push_back(p.x);
    nlohmann::json levels = nlohmann::json::array();
    for (auto& [w, xs] : by_omega) {
        std::sort(xs.begin(), xs.end());
        int distinct = 0;
        for (std::size_t i = 0; i < xs.size(); ++i)
            if (i == 0 || xs[i] - xs[i - 1] > kLevelTol) ++distinct;
        double mean = 0;
        for (double x : xs) mean += x;
        mean /= static_cast<double>(xs.size());
        levels.push_back({w, distinct <= 16 ? distinct : 0, xs.front(), xs.back(), mean});
    }
    return levels;
}

TEST_CASE("golden: the CF diagrams of A1C, A1C1, A3C, A1G and A1H are unchanged, level by level within their tolerances") {
    const std::string path = std::string(IMPACTLAB_SOURCE_DIR) + "/tests/golden/cf_levels.json";
    nlohmann::json pinned = nlohmann::json::object();
    {
        std::ifstream in(path);
        if (in) pinned = nlohmann::json::parse(in);
    }
    const bool update = std::getenv("IMPACTLAB_UPDATE_GOLDEN") != nullptr;
    for (const char* model : {"A1C", "A1C1", "A3C", "A1G", "A1H"}) {
        const impactlab::Diagram d = impactlab::run_cf_sweep(impactlab::resolve_model(model), impactlab::CfSpec{});
        const nlohmann::json got = diagram_summary(d);
        if (update) {
            pinned[model] = got;
            continue;
        }
        CAPTURE(model);
        REQUIRE_MESSAGE(pinned.contains(model), "no pinned CF levels for " << model << " in " << path);
        const nlohmann::json& want = pinned[model];
        REQUIRE(want.size() == got.size());
        double lo = INFINITY, hi = -INFINITY;
        for (const auto& l : want) {
            lo = std::min(lo, l[2].get<double>());
            hi = std::max(hi, l[3].get<double>());
        }
        const double span = hi - lo;
        std::size_t differ = 0;
        for (std::size_t i = 0; i < want.size(); ++i) {
            const auto& a = want[i];
            const auto& b = got[i];
            REQUIRE(a[0].get<double>() == doctest::Approx(b[0].get<double>()).epsilon(1e-12));
            // The extremes decide (a long transient still in the record changes the count, not where the orbit
            // lies); a chaotic level on both sides is compared looser, by its extremes and mean.
            const bool chaotic = a[1].get<int>() == 0 && b[1].get<int>() == 0;
            const double tol = chaotic ? kChaosTol * span : 10 * kLevelTol;
            bool same = true;
            for (int k = 2; k <= (chaotic ? 4 : 3) && same; ++k) same = std::abs(a[k].get<double>() - b[k].get<double>()) <= tol;
            if (!same) {
                ++differ;
                MESSAGE(model << " omega " << a[0].get<double>() << ": pinned " << a.dump() << ", now " << b.dump());
            }
        }
        CHECK(static_cast<double>(differ) <= kLevelsAllowedToDiffer * static_cast<double>(want.size()));
    }
    if (update) {
        std::ofstream(path) << pinned.dump() << "\n";
        MESSAGE("golden: CF levels written to " << path);
    }
}

// The fit's results, compared as numbers with a stated tolerance (not bytes hashed): the effects named and
// turned down (exactly), each parameter and each printed error within kFitRelTol of the pinned value. The last
// bits of libm differ between processors; a result that flips with them is a defect of its decision, which
// these comparisons then show.
constexpr double kFitRelTol = 2e-3;

nlohmann::json fit_summary(const id::FitReport& r) {
    nlohmann::json j;
    j["found"] = nlohmann::json::object();
    for (const auto& f : r.effects_found)
        for (const auto& [n, v] : f.parameters) j["found"][f.id + "." + n] = v;
    std::vector<std::string> rejected;
    for (const auto& f : r.effects_rejected) rejected.push_back(f.id);
    std::sort(rejected.begin(), rejected.end());
    j["rejected"] = rejected;
    auto errors = [](const id::ErrorSummary& e) {
        // Not the 10-period shooting: past the chaotic stretches' horizon it follows libm's last bits (s3: 6.1
        // or 8.1 um).
        return nlohmann::json{{"residual_rms", e.residual_rms_N}, {"shooting_rms_1", e.shooting_rms_1_m}};
    };
    j["before"] = errors(r.error_before);
    j["after"] = errors(r.error_after);
    j["at_noise_floor"] = r.verdict.find("is at its noise floor") != std::string::npos;
    j["gate_passed"] = r.gate_passed.substr(0, r.gate_passed.find(" ("));   // the step, not its printed percentage
    return j;
}

void compare_summary(const std::string& name, const nlohmann::json& want, const nlohmann::json& got) {
    CAPTURE(name);
    CHECK(want["rejected"] == got["rejected"]);
    CHECK(want["at_noise_floor"] == got["at_noise_floor"]);
    CHECK(want["gate_passed"] == got["gate_passed"]);
    auto near = [&](const std::string& what, double a, double b) {
        CAPTURE(what);
        CAPTURE(a);
        CAPTURE(b);
        CHECK(std::abs(a - b) <= kFitRelTol * std::max(std::abs(a), std::abs(b)) + 1e-15);
    };
    CHECK(want["found"].size() == got["found"].size());
    for (const auto& [k, v] : want["found"].items()) {
        REQUIRE_MESSAGE(got["found"].contains(k), "effect parameter " << k << " is no longer found");
        near(k, v.get<double>(), got["found"][k].get<double>());
    }
    for (const char* side : {"before", "after"})
        for (const auto& [k, v] : want[side].items()) near(std::string(side) + "." + k, v.get<double>(), got[side][k].get<double>());
}

TEST_CASE("golden: the fit reports of the shared synthetic data are unchanged, within their stated tolerance" *
          doctest::skip(impactlab::test::shared_missing("data/synthetic/s1_quadratic_damping.csv.gz"))) {
    const std::string path = std::string(IMPACTLAB_SOURCE_DIR) + "/tests/golden/fit_summaries.json";
    nlohmann::json pinned = nlohmann::json::object();
    {
        std::ifstream in(path);
        if (in) pinned = nlohmann::json::parse(in);
    }
    const bool update = std::getenv("IMPACTLAB_UPDATE_GOLDEN") != nullptr;
    for (const char* file : {"s1_quadratic_damping", "s2_bumper_offset", "s3_noise_only"}) {
        id::LoadOptions lo;
        lo.row_begin = 30000;
        lo.row_end = 70000;
        id::MeasuredData d = id::load_measured(impactlab::test::shared_path(std::string("data/synthetic/") + file + ".csv.gz"), lo);
        d.source = std::string(file) + ".csv.gz";
        id::FitOptions fo;
        fo.plots = false;
        const id::FitReport r = id::run_fit(d, id::resolve_fit_model("A1H", id::Forcing::Unbalance), fo);
        const nlohmann::json got = fit_summary(r);
        if (update) {
            pinned[file] = got;
            continue;
        }
        REQUIRE_MESSAGE(pinned.contains(file), "no pinned fit summary for " << file << " in " << path);
        compare_summary(file, pinned[file], got);
    }
    if (update) {
        std::ofstream(path) << pinned.dump(2) << "\n";
        MESSAGE("golden: fit summaries written to " << path);
    }
}

}  // TEST_SUITE
