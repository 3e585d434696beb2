// The command table of the impactlab CLI: one function per command, each thin over core.
#pragma once

#include <string>
#include <vector>

namespace impactlab::cli {

using CommandFn = int (*)(const std::vector<std::string>& args);
struct Command {
    const char* name;
    const char* summary;
    CommandFn run;
};

int cmd_models(const std::vector<std::string>& args);
int cmd_simulate(const std::vector<std::string>& args);
int cmd_poincare(const std::vector<std::string>& args);
int cmd_bifurcation(const std::vector<std::string>& args);
int cmd_figure3(const std::vector<std::string>& args);
int cmd_fit(const std::vector<std::string>& args);
int cmd_synth(const std::vector<std::string>& args);
int cmd_recovery(const std::vector<std::string>& args);
int cmd_scan(const std::vector<std::string>& args);
int cmd_orbit(const std::vector<std::string>& args);
int cmd_continue(const std::vector<std::string>& args);
int cmd_lyapunov(const std::vector<std::string>& args);
int cmd_basins(const std::vector<std::string>& args);

const std::vector<Command>& commands();

}  // namespace impactlab::cli
