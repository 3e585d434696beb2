// impactlab: the command-line face of the core. Exit codes: 0 success, 1 runtime failure, 2 usage error.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "args.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "impactlab/atomic_file.hpp"
#include "impactlab/input_file.hpp"
#include "impactlab/params.hpp"
#include "program_assets.hpp"

namespace impactlab::cli {

const std::vector<Command>& commands() {
    static const std::vector<Command> table{
        {"models", "list the model versions and their parameters", cmd_models},
        {"simulate", "integrate one run at constant omega, write t,x,v,phi,regime as CSV", cmd_simulate},
        {"poincare", "Poincare section at constant omega, write n,x,v as CSV", cmd_poincare},
        {"bifurcation", "CF sweep up or down, or the EF ramp: omega,x,v as CSV (and a PNG)", cmd_bifurcation},
        {"figure3", "the paper's Fig. 3 as one PNG", cmd_figure3},
        {"fit", "close the loop with measured data: residual, missing effect, model with it, error before/after", cmd_fit},
        {"synth", "synthetic measured data with effects, sensor noise and quantisation (t,x,phi CSV)", cmd_synth},
        {"scan", "a parameter plane (omega, xI, m0e): period, Lyapunov exponent, impacts, x range per point; threads or MPI", cmd_scan},
        {"recovery", "the recovery matrix: every library effect injected into each version, is it named first?", cmd_recovery},
        {"orbit", "a periodic orbit by Newton on the k-th Poincare map: section point, Floquet multipliers", cmd_orbit},
        {"continue", "continuation of periodic orbits: branches, folds, period doublings, grazings (CSV, PNG)", cmd_continue},
        {"lyapunov", "largest Lyapunov exponent at one omega, or along a CF sweep", cmd_lyapunov},
        {"basins", "basins of attraction on a grid of starts (x0, v0): labels, legend of attractors (CSV, PNG)", cmd_basins},
    };
    return table;
}

}  // namespace impactlab::cli

namespace {
// A message may quote an input (a name, a token): printed cut and with its control characters escaped.
void report(const std::exception& e) {
    std::fprintf(stderr, "impactlab: error: %s\n", impactlab::printable(e.what()).c_str());
}

void usage() {
    std::printf("impactlab: simulator of a forced impact oscillator with a double-well magnetic stiffness\n\n"
                "usage: impactlab COMMAND [options]   (impactlab COMMAND --help for its options)\n\ncommands:\n");
    for (const auto& c : impactlab::cli::commands()) std::printf("  %-12s %s\n", c.name, c.summary);
}
}  // namespace

int main(int argc, char** argv) {
    using namespace impactlab::cli;
    if (argc < 2) {
        usage();
        return 2;
    }
    const std::string name = argv[1];
    if (name == "--help" || name == "-h" || name == "help") {
        usage();
        return 0;
    }
    const std::vector<std::string> rest(argv + 2, argv + argc);
    impactlab::remove_partials_on_signal();
    impactlab::use_program_fonts();   // the plots' text: the font installed beside this program
    for (const auto& c : commands()) {
        if (name != c.name) continue;
        int rc = 1;
        impactlab::OutputGroup outputs;   // every file the command writes, committed together at the end
        try {
            rc = c.run(rest);
        } catch (const UsageError& e) {
            report(e);
            rc = 2;
        } catch (const impactlab::ParamError& e) {
            report(e);
            rc = 2;
        } catch (const std::exception& e) {
            report(e);
            rc = 1;
        }
        // An output is renamed into place only now, and only if the command succeeded.
        return finish_outputs(outputs, rc == 0) ? rc : 1;
    }
    std::fprintf(stderr, "impactlab: error: unknown command '%s' (see impactlab --help)\n", impactlab::printable(name, 100).c_str());
    return 2;
}
