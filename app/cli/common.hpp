// Pieces every command shares: the model flags, a progress bar on stderr, CSV output.
#pragma once

#include <atomic>
#include <functional>
#include <chrono>
#include <fstream>
#include <optional>
#include <vector>
#include <string>
#include <thread>

#include "args.hpp"
#include "impactlab/identify_data.hpp"
#include "impactlab/params.hpp"
#include "impactlab/rosenbrock.hpp"
#include "impactlab/sweep.hpp"

namespace impactlab::cli {

// Flags every simulating command accepts.
inline const std::set<std::string> kModelFlags{"--model", "--xI", "--m0e", "--rtol"};
inline constexpr const char* kModelHelp =
    "  --model NAME|FILE.json  model version (A1C, A1C1, A3C, A1G, A1H, any XY of impactlab models) or a parameter file\n"
    "  --xI X                  bumper position [m] (default: the model's, 0)\n"
    "  --m0e M                 forcing amplitude m0*e [kg m] (default: the model's)\n"
    "  --rtol R                relative tolerance of the integrator (default 1e-8)\n";

Params model_from(const Args& a, const std::string& fallback = "A1H");
Tolerances tolerances_from(const Args& a);
std::set<std::string> with_model_flags(std::set<std::string> flags);
// Opens a file for writing or throws UsageError naming it.
std::ofstream open_out(const std::string& path);
// "a,b,,c" -> {a, b, c}.
std::vector<std::string> split_list(const std::string& s);

// A measured input u(t) read from a record (simulate, synth): --input FILE and its column mapping.
inline const std::set<std::string> kInputFlags{"--input", "--u-col", "--x-col", "--t-col", "--input-rate", "--u-scale"};
// The record named by --input, or nothing without it; the mapping flags alone are a usage error.
std::optional<identify::MeasuredData> input_from(const Args& a, const std::string& command);

// Draws a progress bar on stderr while a job runs longer than a second. Runs its own thread; the job
// updates `progress` from its thread.
class ProgressBar {
public:
    ProgressBar(const std::string& label, Progress& progress);
    // Any job's fraction (written by the job's thread); `stage` (optional, called on the bar's thread) names
    // what the job is doing now.
    ProgressBar(const std::string& label, const std::atomic<double>& fraction, std::function<std::string()> stage = {});
    ~ProgressBar();
    void finish();

private:
    std::string label_;
    const std::atomic<double>& fraction_;
    std::function<std::string()> stage_;
    std::atomic<bool> done_{false};
    std::thread thread_;
    bool drawn_ = false;
};

}  // namespace impactlab::cli
