// Behaviour pinned: the five CF diagrams of Fig. 3 (impactlab bifurcation --sweep up, the CLI's defaults) and
// the fit reports of the shared synthetic data (40 s of each, as shared_data_test fits them) hash to the
// values in tests/golden/hashes.txt, so a refactoring that changes a result by one bit says so here. A change
// of behaviour that is meant regenerates the file, and the commit shows the hashes that moved:
//
//   IMPACTLAB_UPDATE_GOLDEN=1 build/bin/impactlab_tests -ts=golden
//
// The hashes are of this machine's floating point (x86-64, the project's compiler and flags).
#include <doctest/doctest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>

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

TEST_CASE("golden: the fit reports of the shared synthetic data are unchanged" *
          doctest::skip(impactlab::test::shared_missing("data/synthetic/s1_quadratic_damping.csv.gz"))) {
    for (const char* file : {"s1_quadratic_damping", "s2_bumper_offset", "s3_noise_only"}) {
        id::LoadOptions lo;
        lo.row_begin = 30000;
        lo.row_end = 70000;
        id::MeasuredData d = id::load_measured(impactlab::test::shared_path(std::string("data/synthetic/") + file + ".csv.gz"), lo);
        d.source = std::string(file) + ".csv.gz";   // the report names it; not the checkout's path
        id::FitOptions fo;
        fo.plots = false;
        const id::FitReport r = id::run_fit(d, id::resolve_fit_model("A1H", id::Forcing::Unbalance), fo);
        // The wall-clock time is the one field that is not a result.
        const std::string json = std::regex_replace(id::report_json_text(r), std::regex("\"runtime_s\": [^,\\n]*"), "\"runtime_s\": 0");
        pin(std::string("fit_") + file, json);
    }
}

}  // TEST_SUITE
