// Behaviour pinned: the five CF diagrams of Fig. 3 (impactlab bifurcation --sweep up, the CLI's defaults) hash
// to the values in tests/golden/hashes.txt, so a refactoring that changes a result by one bit says so here; the
// fit reports of the shared synthetic data (40 s of each, as shared_data_test fits them) are compared as
// numbers with tests/golden/fit_summaries.json, within a stated tolerance. A change
// of behaviour that is meant regenerates the file, and the commit shows the hashes that moved:
//
//   IMPACTLAB_UPDATE_GOLDEN=1 build/bin/impactlab_tests -ts=golden
//
// The hashes are of this machine's floating point (x86-64, the project's compiler and flags).
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

namespace {

const std::string kFile = std::string(IMPACTLAB_SOURCE_DIR) + "/tests/golden/hashes.txt";

std::string fnv1a(const std::string& s) {
    std::uint64_t h = 1469598103934665603ull;
    for (unsigned char c : s) {
        h ^= c;
        h *= 1099511628211ull;
    }
    char buf[24];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
}

std::map<std::string, std::string> read_hashes() {
    std::map<std::string, std::string> m;
    std::ifstream in(kFile);
    std::string name, hash;
    while (in >> name >> hash) m[name] = hash;
    return m;
}

// Compares `text`'s hash with the file's entry `name`, or records it when regenerating.
void pin(const std::string& name, const std::string& text) {
    static std::map<std::string, std::string> hashes = read_hashes();
    const std::string h = fnv1a(text);
    if (std::getenv("IMPACTLAB_UPDATE_GOLDEN")) {
        hashes[name] = h;
        std::ofstream out(kFile);
        for (const auto& [n, v] : hashes) out << n << ' ' << v << '\n';
        MESSAGE("golden: " << name << " " << h << " written to " << kFile);
        return;
    }
    CAPTURE(name);
    REQUIRE_MESSAGE(hashes.count(name) == 1, "no golden hash for " << name << " in " << kFile);
    CHECK(hashes[name] == h);
}

}  // namespace

TEST_SUITE("golden") {

TEST_CASE("golden: the CF diagrams of A1C, A1C1, A3C, A1G and A1H are unchanged") {
    for (const char* model : {"A1C", "A1C1", "A3C", "A1G", "A1H"}) {
        const impactlab::Diagram d = impactlab::run_cf_sweep(impactlab::resolve_model(model), impactlab::CfSpec{});
        std::ostringstream csv;
        impactlab::write_diagram_csv(d, csv);
        pin(std::string("cf_up_") + model, csv.str());
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
        return nlohmann::json{{"residual_rms", e.residual_rms_N}, {"shooting_rms_1", e.shooting_rms_1_m}, {"shooting_rms_10", e.shooting_rms_10_m}};
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
