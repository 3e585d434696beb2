#include "common.hpp"

#include <sstream>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <unistd.h>

#include "impactlab/atomic_file.hpp"
#include "impactlab/input_file.hpp"
#include "impactlab/params_json.hpp"

namespace impactlab::cli {

bool show_help_if_asked(const std::vector<std::string>& args, const char* text, const char* shared) {
    for (const auto& a : args)
        if (a == "--help" || a == "-h") {
            std::printf("%s", text);
            if (shared) std::printf("%s", shared);
            return true;
        }
    return false;
}

Params model_from(const Args& a, const std::string& fallback) {
    Params p;
    const std::string name = a.str("--model", fallback);
    note_input(name);
    try {
        p = resolve_model(name);
    } catch (const ParamError& e) {
        throw UsageError(std::string("--model: ") + e.what());
    }
    if (a.has("--xI")) {
        p.xI = a.num("--xI", 0.0, -0.05, 0.05);
        p.name += "(xI=" + a.str("--xI", "") + ")";
    }
    if (a.has("--m0e")) p.m0e = a.num("--m0e", p.m0e, 0.0, 10.0);
    validate(p, name);
    p.name = printable(p.name, 80);   // printed in every summary: a file's name may be long or hold escapes
    return p;
}

Tolerances tolerances_from(const Args& a) {
    Tolerances t;
    t.rtol = a.num("--rtol", t.rtol, 1e-13, 1e-2);
    return t;
}

std::set<std::string> with_model_flags(std::set<std::string> flags) {
    flags.insert(kModelFlags.begin(), kModelFlags.end());
    return flags;
}

namespace {
std::vector<std::string>& inputs() {
    static std::vector<std::string> list;
    return list;
}
bool same_file(const std::string& a, const std::string& b) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
    return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec);
}
}  // namespace

void note_input(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_regular_file(path, ec)) inputs().push_back(path);
}

void check_not_input(const std::string& path, const std::string& flag) {
    for (const auto& in : inputs())
        if (same_file(path, in))
            throw UsageError(flag + ": '" + path + "' is an input of this command ('" + in +
                             "'); writing it would destroy it: choose another output name");
}

void check_writable(const std::string& path, const std::string& flag) {
    namespace fs = std::filesystem;
    if (path.empty()) throw UsageError(flag + ": an empty file name");
    check_not_input(path, flag);
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw UsageError(flag + ": '" + path + "' is a directory, not a file name");
    const std::string probe = partial_path(path);
    {
        std::ofstream out(probe);
        if (!out) throw UsageError(flag + ": cannot write '" + path + "' (its directory is missing or not writable)");
    }
    discard_partial(probe);
}

void check_report_dir(const std::string& dir) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::exists(dir, ec)) {
        if (!fs::is_directory(dir, ec)) throw UsageError("--report: '" + dir + "' is a file, not a directory");
        check_writable((fs::path(dir) / "report.md").string(), "--report");
        return;
    }
    // Made and removed again (only what was made here): permission bits do not tell root about /proc.
    fs::path existing = fs::absolute(dir, ec);
    while (!existing.empty() && !fs::exists(existing, ec) && existing != existing.parent_path()) existing = existing.parent_path();
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir))
        throw UsageError("--report: cannot create the directory '" + dir + "'" + (ec ? " (" + ec.message() + ")" : ""));
    check_writable((fs::path(dir) / "report.md").string(), "--report");
    for (fs::path p = fs::absolute(dir, ec); !p.empty() && p != existing && p != p.parent_path(); p = p.parent_path())
        fs::remove(p, ec);
}

OutputFile::OutputFile(const std::string& path, const std::string& flag, std::ios::openmode mode)
    : path_(path), uncaught_(std::uncaught_exceptions()) {
    if (path.empty()) throw UsageError(flag + ": an empty file name");
    check_not_input(path, flag);
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw UsageError(flag + ": '" + path + "' is a directory, not a file name");
    tmp_ = partial_path(path);
    open(tmp_, mode);
    if (!is_open()) {
        discard_partial(tmp_);
        throw UsageError(flag + ": cannot write '" + path + "' (its directory is missing or not writable)");
    }
}

OutputFile::OutputFile(OutputFile&& o) noexcept
    : std::ofstream(std::move(o)), path_(std::move(o.path_)), tmp_(std::move(o.tmp_)), uncaught_(o.uncaught_), done_(o.done_) {
    o.done_ = true;
}

void OutputFile::commit() {
    if (done_) return;
    done_ = true;
    flush();
    const bool ok = static_cast<bool>(*this);
    close();
    if (!ok) {
        discard_partial(tmp_);
        throw std::runtime_error(path_ + ": write failed (disk full?)");
    }
    commit_partial(tmp_, path_);
}

namespace {
// Outputs whose scope ended without an exception, closed, waiting for the command's exit status.
struct PendingOutput {
    std::string tmp, path;
    bool written;
};
std::vector<PendingOutput>& pending_outputs() {
    static std::vector<PendingOutput> list;
    return list;
}
}  // namespace

OutputFile::~OutputFile() {
    if (done_) return;
    done_ = true;
    const bool failed = std::uncaught_exceptions() > uncaught_;
    if (!failed) flush();
    const bool written = static_cast<bool>(*this);
    close();
    if (failed) discard_partial(tmp_);   // the command failed: leave the old file as it was
    else pending_outputs().push_back({tmp_, path_, written});
}

bool finish_outputs(bool success) {
    bool ok = true;
    for (const PendingOutput& o : pending_outputs()) {
        if (!success || !o.written) {
            discard_partial(o.tmp);
            if (success) {
                std::fprintf(stderr, "impactlab: error: %s: write failed (disk full?)\n", o.path.c_str());
                ok = false;
            }
            continue;
        }
        try {
            commit_partial(o.tmp, o.path);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "impactlab: error: %s\n", e.what());
            ok = false;
        }
    }
    pending_outputs().clear();
    return ok;
}

OutputFile open_out(const std::string& path, const std::string& flag) {
    OutputFile out(path, flag);
    out.precision(10);
    return out;
}

void check_start(const Params& p, double x, const std::string& command, const std::string& flag) {
    if (!p.has_bumper() || !p.rigid() || x <= p.xI) return;
    char buf[200];
    std::snprintf(buf, sizeof buf, "%s: %s: x = %.6g m lies beyond the bumper at xI = %.6g m (%s); start at x <= xI",
                  command.c_str(), flag.c_str(), x, p.xI, p.name.substr(0, 60).c_str());
    throw UsageError(buf);
}

void check_rows(const std::string& command, double rows, const std::string& flags) {
    if (rows <= kMaxRows) return;
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s: %s asks for %.3g output rows, more than the %.0e an output may have", command.c_str(),
                  flags.c_str(), rows, kMaxRows);
    throw UsageError(std::string(buf) + ": change one of them");
}

std::vector<std::string> split_list(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, ','))
        if (!item.empty()) out.push_back(item);
    return out;
}

std::optional<identify::MeasuredData> input_from(const Args& a, const std::string& command) {
    const bool input = a.has("--input");
    for (const auto& f : kInputFlags)
        if (f != "--input" && a.has(f) && !input) throw UsageError(command + ": " + f + " needs --input");
    if (!input) return std::nullopt;
    identify::LoadOptions lo;
    lo.columns.u = a.str("--u-col", "");
    lo.columns.x = a.str("--x-col", "");
    lo.columns.t = a.str("--t-col", "");
    lo.rate = a.num("--input-rate", 0.0, 1e-6, 1e9);
    lo.u_scale = a.num("--u-scale", 1.0, -1e12, 1e12);
    lo.min_samples = 2;   // an input needs two samples to be a signal
    identify::MeasuredData in;
    note_input(a.str("--input", ""));
    try {
        in = identify::load_measured(a.str("--input", ""), lo);
    } catch (const identify::DataError& e) {
        throw UsageError(command + ": --input: " + e.what());
    }
    if (!in.has_u()) throw UsageError(command + ": --input: " + in.source + " has no input column u (map one with --u-col)");
    return in;
}

ProgressBar::ProgressBar(const std::string& label, Progress& progress) : ProgressBar(label, progress.fraction) {}

ProgressBar::ProgressBar(const std::string& label, const std::atomic<double>& fraction, std::function<std::string()> stage)
    : label_(label), fraction_(fraction), stage_(std::move(stage)) {
    // On a terminal the bar redraws in place; into a log file it writes a line per 10 %.
    const bool tty = isatty(fileno(stderr)) != 0;
    thread_ = std::thread([this, tty] {
        const auto start = std::chrono::steady_clock::now();
        int last_decile = -1;
        while (!done_.load()) {
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
            const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            if (elapsed < 1.0 || done_.load()) continue;
            const double f = std::clamp(fraction_.load(), 0.0, 1.0);
            const std::string now = stage_ ? stage_() : std::string();
            if (!tty) {
                const int decile = static_cast<int>(f * 10);
                if (decile != last_decile)
                    std::fprintf(stderr, "%s: %3d%%  %5.0f s%s%s\n", label_.c_str(), decile * 10, elapsed, now.empty() ? "" : "  ", now.c_str());
                last_decile = decile;
                continue;
            }
            const int width = 30, filled = static_cast<int>(f * width);
            std::fprintf(stderr, "\r%-28s [%s%s] %5.1f%%  %5.0f s  %-34.34s", label_.c_str(), std::string(filled, '#').c_str(),
                         std::string(width - filled, '.').c_str(), 100 * f, elapsed, now.c_str());
            std::fflush(stderr);
            drawn_ = true;
        }
    });
}

void ProgressBar::finish() {
    if (done_.exchange(true)) return;
    thread_.join();
    if (drawn_) std::fprintf(stderr, "\r%-28s done%86s\n", label_.c_str(), "");
    else if (!isatty(fileno(stderr))) std::fflush(stderr);
}

ProgressBar::~ProgressBar() { finish(); }

}  // namespace impactlab::cli
