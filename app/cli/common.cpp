#include "common.hpp"

#include <sstream>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fcntl.h>
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

CheckedFileBuf::CheckedFileBuf(int fd) : fd_(fd), buf_(std::size_t{1} << 16) { setp(buf_.data(), buf_.data() + buf_.size()); }

CheckedFileBuf::~CheckedFileBuf() { close(); }

bool CheckedFileBuf::write_all(const char* s, std::size_t n) {
    while (n > 0 && err_ == 0) {
        const ssize_t k = ::write(fd_, s, n);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) {
            err_ = k < 0 ? errno : EIO;
            break;
        }
        s += k;
        n -= static_cast<std::size_t>(k);
    }
    return err_ == 0;
}

bool CheckedFileBuf::drain() {
    const bool ok = err_ == 0 && write_all(pbase(), static_cast<std::size_t>(pptr() - pbase()));
    setp(buf_.data(), buf_.data() + buf_.size());   // a failed file takes no more bytes, but the buffer is reused
    return ok;
}

CheckedFileBuf::int_type CheckedFileBuf::overflow(int_type c) {
    if (fd_ < 0 || !drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
        *pptr() = traits_type::to_char_type(c);
        pbump(1);
    }
    return traits_type::not_eof(c);
}

std::streamsize CheckedFileBuf::xsputn(const char* s, std::streamsize n) {
    if (fd_ < 0 || err_ != 0) return 0;
    if (n <= epptr() - pptr()) {
        traits_type::copy(pptr(), s, static_cast<std::size_t>(n));
        pbump(static_cast<int>(n));
        return n;
    }
    if (!drain() || !write_all(s, static_cast<std::size_t>(n))) return 0;   // a large piece goes straight out
    return n;
}

int CheckedFileBuf::sync() { return fd_ >= 0 && drain() ? 0 : -1; }

bool CheckedFileBuf::close() {
    if (fd_ < 0) return err_ == 0;
    drain();
    // close() reports what a delayed write found (NFS, quotas): checked like the writes.
    if (::close(fd_) != 0 && err_ == 0) err_ = errno;
    fd_ = -1;
    return err_ == 0;
}

OutputFile::OutputFile(const std::string& path, const std::string& flag, std::ios::openmode mode)
    : std::ostream(nullptr), path_(path), uncaught_(std::uncaught_exceptions()) {
    if (path.empty()) throw UsageError(flag + ": an empty file name");
    check_not_input(path, flag);
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw UsageError(flag + ": '" + path + "' is a directory, not a file name");
    tmp_ = partial_path(path);
    const int fd = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC | ((mode & std::ios::app) ? O_APPEND : O_TRUNC), 0666);
    if (fd < 0) {
        discard_partial(tmp_);
        throw UsageError(flag + ": cannot write '" + path + "' (its directory is missing or not writable)");
    }
    buf_ = std::make_unique<CheckedFileBuf>(fd);
    rdbuf(buf_.get());
}

OutputFile::OutputFile(OutputFile&& o) noexcept
    : std::ostream(std::move(o)), buf_(std::move(o.buf_)), path_(std::move(o.path_)), tmp_(std::move(o.tmp_)), uncaught_(o.uncaught_),
      done_(o.done_) {
    rdbuf(buf_.get());   // (basic_ostream's move leaves the buffer behind)
    o.rdbuf(nullptr);
    o.done_ = true;
}

namespace {
// The first output that could not be written, reported by finish_outputs (its partial file is gone already).
std::string& failed_output() {
    static std::string message;
    return message;
}
// What the system said about the last failed write ("No space left on device"), or a guess without it.
std::string write_failure(const std::string& path, int err) {
    return path + ": write failed (" + (err != 0 ? std::string(std::strerror(err)) : std::string("disk full?")) + ")";
}
}  // namespace

bool OutputFile::close_checked(int& err) {
    flush();
    const bool ok = buf_ && buf_->close() && static_cast<bool>(*this);
    err = buf_ ? buf_->error() : 0;
    return ok;
}

void OutputFile::check() {
    flush();
    if (buf_ && buf_->error() != 0) throw std::runtime_error(write_failure(path_, buf_->error()));
}

void OutputFile::commit() {
    if (done_) return;
    done_ = true;
    int err = 0;
    if (!close_checked(err)) {
        discard_partial(tmp_);
        throw std::runtime_error(write_failure(path_, err));
    }
    commit_partial(tmp_, path_);   // staged in main's OutputGroup: renamed with the command's other outputs
}

OutputFile::~OutputFile() {
    if (done_) return;
    done_ = true;
    if (std::uncaught_exceptions() > uncaught_) {   // the command failed: leave the old file as it was
        if (buf_) buf_->close();
        discard_partial(tmp_);
        return;
    }
    int err = 0;
    if (!close_checked(err)) {
        discard_partial(tmp_);
        if (failed_output().empty()) failed_output() = write_failure(path_, err);
        return;
    }
    commit_partial(tmp_, path_);
}

bool finish_outputs(OutputGroup& outputs, bool success) {
    bool ok = true;
    if (success && !failed_output().empty()) {
        std::fprintf(stderr, "impactlab: error: %s\n", printable(failed_output()).c_str());
        ok = success = false;
    }
    if (!success) {
        outputs.discard();
        return ok;
    }
    try {
        outputs.commit();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "impactlab: error: %s\n", printable(e.what()).c_str());
        return false;
    }
    return true;
}

OutputFile open_out(const std::string& path, const std::string& flag) {
    OutputFile out(path, flag);
    out.precision(10);
    return out;
}

void check_start(const Params& p, double x, const std::string& command, const std::string& flag, bool defaulted) {
    if (!p.has_bumper() || !p.rigid() || x <= p.xI) return;
    char buf[300];
    if (defaulted)   // the user gave no start: blame the bumper's position, and say how to start
        std::snprintf(buf, sizeof buf,
                      "%s: the default start x = %.6g m lies beyond the bumper at xI = %.6g m (%s): give %s X with X <= xI", command.c_str(),
                      x, p.xI, p.name.substr(0, 60).c_str(), flag.c_str());
    else
        std::snprintf(buf, sizeof buf, "%s: %s: x = %.6g m lies beyond the bumper at xI = %.6g m (%s); start at x <= xI", command.c_str(),
                      flag.c_str(), x, p.xI, p.name.substr(0, 60).c_str());
    throw UsageError(buf);
}

void check_run_span(const Params& p, double t_begin, double t_end, const std::string& command) {
    try {
        validate_over(p, t_begin, t_end, p.name);
    } catch (const ParamError& e) {
        throw UsageError(command + ": " + e.what());
    }
    // A drift's clock (t0, the record's start for a fitted model) travels with the model: a run on another
    // clock is said so, as the drift then acts as it would have at t - t0 of the record.
    for (const auto& e : p.effects)
        for (std::size_t i = 0; i < kMaxLawParams && e.law && e.law->names[i]; ++i)
            if (std::string(e.law->names[i]) == "t0" && e.p[i] != t_begin)
                std::fprintf(stderr,
                             "%s: note: effects.%s.t0 = %.6g s (the clock of the record it was fitted to); this run starts at "
                             "t = %.6g s, where the drift stands as it did %.6g s %s that record's start\n",
                             command.c_str(), e.law->id, e.p[i], t_begin, std::fabs(e.p[i] - t_begin), e.p[i] > t_begin ? "before" : "after");
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
    if (!in.has_u() || in.free_run) throw UsageError(command + ": --input: " + in.source + " has no input column u (map one with --u-col)");
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
