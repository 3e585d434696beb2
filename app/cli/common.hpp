// Pieces every command shares: the model flags, a progress bar on stderr, CSV output.
#pragma once

#include <atomic>
#include <functional>
#include <chrono>
#include <fstream>
#include <memory>
#include <ostream>
#include <streambuf>
#include <optional>
#include <vector>
#include <string>
#include <thread>

#include "args.hpp"
#include "impactlab/atomic_file.hpp"
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

// Prints the command's help, and the flags it shares (kModelHelp) if given, when --help or -h is among args.
bool show_help_if_asked(const std::vector<std::string>& args, const char* text, const char* shared = nullptr);
Params model_from(const Args& a, const std::string& fallback = "A1H");
Tolerances tolerances_from(const Args& a);
std::set<std::string> with_model_flags(std::set<std::string> flags);
// Every file a command reads (a model file, a record, an input): an output that is one of them is refused.
// Main thread only.
void note_input(const std::string& path);
// Throws UsageError if `path` is one of the noted inputs (the same file by any name), naming the flag.
void check_not_input(const std::string& path, const std::string& flag);
// Before any computing: `path` can be created (a probe file beside it) and is no input; else UsageError.
void check_writable(const std::string& path, const std::string& flag);
// Before any computing: `dir` is a writable directory, or can be made in a writable one (--report).
void check_report_dir(const std::string& dir);

// An output written whole or not at all: the text goes to a hidden file beside PATH. commit(), or the end of
// its scope, checks every write and stages it in main's OutputGroup; all outputs of a command (CSVs, PNGs)
// are renamed into place together once the command has returned 0 and every one was written
// (finish_outputs). A command that throws, returns non-zero or fails a write leaves the old files as they
// were and nothing behind. Opening it checks that PATH is writable and no input.
// The bytes of an OutputFile: buffered writes to a file descriptor, each checked, the first failure's errno
// kept (std::filebuf keeps only a bad bit, and errno is gone by the time the stream is checked).
class CheckedFileBuf : public std::streambuf {
public:
    explicit CheckedFileBuf(int fd);
    ~CheckedFileBuf() override;
    CheckedFileBuf(const CheckedFileBuf&) = delete;
    CheckedFileBuf& operator=(const CheckedFileBuf&) = delete;
    // Writes what is buffered and closes the file; false if any write or the close failed.
    bool close();
    int error() const { return err_; }   // errno of the first failure, 0 if none

protected:
    int_type overflow(int_type c) override;
    std::streamsize xsputn(const char* s, std::streamsize n) override;
    int sync() override;

private:
    bool drain();
    bool write_all(const char* s, std::size_t n);
    int fd_;
    int err_ = 0;
    std::vector<char> buf_;
};

class OutputFile : public std::ostream {
public:
    OutputFile(const std::string& path, const std::string& flag, std::ios::openmode mode = std::ios::out);
    OutputFile(OutputFile&& o) noexcept;
    OutputFile& operator=(OutputFile&&) = delete;
    ~OutputFile() override;
    // Flushes, checks every write and the close, and stages the file for finish_outputs; throws
    // std::runtime_error naming PATH and the system's reason ("No space left on device") if one failed.
    void commit();
    // Throws that error now if a write has failed already (a command that checks before going on).
    void check();
    // errno of the first failed write, 0 if none (asked on the thread that writes).
    int error() const { return buf_ ? buf_->error() : 0; }
    const std::string& path() const { return path_; }

private:
    bool close_checked(int& err);
    std::unique_ptr<CheckedFileBuf> buf_;
    std::string path_, tmp_;
    int uncaught_ = 0;
    bool done_ = false;
};
// main(), after a command: with `success` and every write checked good, renames into place every output the
// command staged in `outputs` (OutputFiles, PNGs, reports); else removes them all. False, with a message on
// stderr, if an output could not be written or renamed.
bool finish_outputs(OutputGroup& outputs, bool success);
// Opens an OutputFile for CSV (10 significant digits) or throws UsageError naming it.
OutputFile open_out(const std::string& path, const std::string& flag = "--out");
// Throws UsageError when a start x (given by `flag`) lies beyond a rigid bumper, where the simulator would move
// it onto the bumper unasked (a compliant bumper may be pressed, so any x is a start there).
// `defaulted`: the flag was not given, x is its default (the message then says so and names the flag to give).
void check_start(const Params& p, double x, const std::string& command, const std::string& flag, bool defaulted = false);
// Before a run over [t_begin, t_end] s: every law that changes with time stays a force a rig can take over that
// span (UsageError naming the effect's key and the time), and a drift whose clock t0 is not the run's start is
// noted on stderr.
void check_run_span(const Params& p, double t_begin, double t_end, const std::string& command);
// The most rows an output may have (synth's cap too): a CSV of a few GB, which some commands hold in memory.
inline constexpr double kMaxRows = 5e7;
// Throws UsageError unless `rows` <= kMaxRows, naming `flags`, the flags whose values multiply to it
// ("--duration / --dt"), so that the message says what to change.
void check_rows(const std::string& command, double rows, const std::string& flags);
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
