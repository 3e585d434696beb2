// impactlab recovery: the recovery matrix of the measured-data loop (core: identify::run_recovery).
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "commands.hpp"
#include "common.hpp"
#include "impactlab/identify.hpp"

namespace impactlab::cli {

namespace {
constexpr const char* kRecoveryHelp =
    "usage: impactlab recovery [--versions A1C,A1C1,A3C,A1G,A1H] [--duration S] [--seed N] [--out TABLE.md]\n"
    "       impactlab recovery --null [--versions ...] [--seeds N] [--duration S] [--out TABLE.md]\n\n"
    "Injects every library effect at a moderate strength into each version with `synth` (steps at 9 and\n"
    "16 rad/s: periodic, then chaotic with impacts; sensor noise 3 um, 1 um quantisation), runs `fit` with\n"
    "the version's parameters fixed, and prints whether the effect is named first, its estimate against the\n"
    "truth (within 3 sigma?) and the held-out shooting RMS before and after. Exit 1 if any case fails.\n"
    "  --versions LIST   versions to test (default: the paper's five)\n"
    "  --duration S      length of each synthetic record [s] (default 60)\n"
    "  --seed N          noise seed (default 1)\n"
    "  --out FILE        also write the table as Markdown\n"
    "  --null            instead: noise-only data of each version with N seeds (default 10); anything named\n"
    "                    is a false finding. Exit 1 if there is one.\n";

}  // namespace

int cmd_recovery(const std::vector<std::string>& argv) {
    if (show_help_if_asked(argv, kRecoveryHelp)) return 0;
    const Args a("recovery", argv, {"--versions", "--duration", "--seed", "--seeds", "--out"}, {"--null"});
    if (!a.positional().empty()) throw UsageError("recovery: unexpected argument '" + a.positional()[0] + "'");
    const std::vector<std::string> versions = split_list(a.str("--versions", "A1C,A1C1,A3C,A1G,A1H"));
    for (const auto& v : versions) {
        try {
            (void)make_version(v);
        } catch (const ParamError& e) {
            throw UsageError(std::string("recovery: --versions: ") + e.what());
        }
    }
    const double duration = a.num("--duration", 60.0, 10.0, 3600.0);
    const int seed = a.integer("--seed", 1, 0, 1000000000);
    const std::string out_path = a.str("--out", "");
    std::optional<OutputFile> out;
    if (!out_path.empty()) out.emplace(out_path, "--out");
    if (a.has("--null")) {
        const int seeds = a.integer("--seeds", 10, 1, 1000);
        std::ostringstream md;
        md << "| version | seeds | false findings | model written = model given | 1-period shooting RMS [um] |\n|---|---|---|---|---|\n";
        int false_findings = 0;
        for (const auto& v : versions) {
            int found = 0, unchanged = 0;
            double rms_max = 0;
            std::string names;
            for (int sd = 1; sd <= seeds; ++sd) {
                const identify::NullResult r = identify::run_null(v, duration, static_cast<unsigned>(sd));
                found += r.found.empty() ? 0 : 1;
                unchanged += r.model_unchanged ? 1 : 0;
                rms_max = std::max(rms_max, r.rms_m);
                for (const auto& id : r.found) names += " " + id + "(seed " + std::to_string(sd) + ")";
            }
            false_findings += found;
            char line[512];
            std::snprintf(line, sizeof line, "| %s | %d | %d%s | %d of %d | <= %.3g |\n", v.c_str(), seeds, found, names.c_str(), unchanged, seeds,
                          rms_max * 1e6);
            md << line;
            std::printf("%s", line);
            std::fflush(stdout);
        }
        if (out) {
            *out << md.str();
            out->commit();
        }
        std::printf("%d false findings\n", false_findings);
        return false_findings ? 1 : 0;
    }
    std::ostringstream md;
    md << "| version | effect | truth | named first | estimate +/- sigma | within 3 sigma | held-out RMS before -> after [um] |\n"
          "|---|---|---|---|---|---|---|\n";
    int failed = 0, total = 0;
    for (const auto& c : identify::recovery_cases(versions)) {
        const identify::RecoveryResult r = identify::run_recovery(c, duration, static_cast<unsigned>(seed));
        ++total;
        if (!r.recovered()) ++failed;
        char line[512];
        std::snprintf(line, sizeof line, "| %s | %s | %s = %.4g | %s | %s | %s | %.3g -> %.3g |\n", c.version.c_str(), c.effect.c_str(),
                      c.param.c_str(), c.truth, r.named_first ? "yes" : (r.first.empty() ? "none" : r.first.c_str()),
                      r.named_first ? (std::to_string(r.estimate).substr(0, 10) + " +/- " + std::to_string(r.sigma).substr(0, 8)).c_str() : "-",
                      r.within ? "yes" : "no", r.rms_before_m * 1e6, r.rms_after_m * 1e6);
        md << line;
        std::printf("%s", line);
        std::fflush(stdout);
    }
    md << "\n" << total - failed << " of " << total << " cases recovered.\n";
    std::printf("%d of %d cases recovered\n", total - failed, total);
    if (out) {
        *out << md.str();
        out->commit();
    }
    return failed ? 1 : 0;
}

}  // namespace impactlab::cli
