#include "impactlab/atomic_file.hpp"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <set>
#include <stdexcept>
#include <system_error>

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace impactlab {

namespace {

// The partial files in flight, kept where a signal handler may read them: fixed slots of plain characters
// and a lock-free state (0 free, 1 being written, 2 a name). A name that does not fit is not kept; it is then
// left behind by a signal, as before.
constexpr int kSlots = 64;
constexpr std::size_t kNameMax = 4096;
struct Slot {
    std::atomic<int> state{0};
    char name[kNameMax];
};
Slot g_slots[kSlots];
// Names are kept only once the handlers are in place: a program without them (the GUI, whose clip writer
// renames its staging folder itself) never fills the slots.
std::atomic<bool> g_handling{false};

void remember(const std::string& partial) {
    if (!g_handling.load(std::memory_order_acquire) || partial.size() >= kNameMax) return;
    for (Slot& s : g_slots) {
        int expected = 0;
        if (!s.state.compare_exchange_strong(expected, 1, std::memory_order_acquire)) continue;
        std::memcpy(s.name, partial.c_str(), partial.size() + 1);
        s.state.store(2, std::memory_order_release);
        return;
    }
}

void forget(const std::string& partial) {
    for (Slot& s : g_slots)
        if (s.state.load(std::memory_order_acquire) == 2 && partial == s.name) {
            s.state.store(0, std::memory_order_release);
            return;
        }
}

extern "C" void remove_partials_and_reraise(int sig) {
    // Only async-signal-safe calls here: unlink, then the signal again under its default action.
    for (Slot& s : g_slots)
        if (s.state.load(std::memory_order_acquire) == 2) ::unlink(s.name);
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

}  // namespace

namespace {
// The files staged by the open OutputGroup of this thread (the outermost decides), in order.
struct Staged {
    std::string partial, path;
};
thread_local int t_depth = 0;
thread_local std::vector<Staged> t_staged;

// ".NAME.partial-PID" (or an OutputGroup's backup ".NAME.partial-PID-old"): the PID, or 0 if `name` is
// neither.
long partial_pid(const char* name) {
    if (name[0] != '.') return 0;
    const char* tag = std::strstr(name, ".partial-");
    if (tag == nullptr) return 0;
    const char* digits = tag + 9;
    long pid = 0;
    const char* c = digits;
    for (; *c >= '0' && *c <= '9' && pid < (1L << 40); ++c) pid = pid * 10 + (*c - '0');
    return (c != digits && (*c == '\0' || std::strcmp(c, "-old") == 0)) ? pid : 0;
}

std::string errno_text(int err) { return std::strerror(err); }
}  // namespace

int remove_stale_partials(const std::string& dir) {
    // Read entry by entry (a folder of many files costs one pass); a PID that exists, or that we may not
    // signal, is left alone: it may be another user's run writing now.
    DIR* d = ::opendir(dir.empty() ? "." : dir.c_str());
    if (d == nullptr) return 0;
    std::vector<std::string> stale;
    while (const dirent* e = ::readdir(d)) {
        const long pid = partial_pid(e->d_name);
        if (pid <= 0 || pid == ::getpid()) continue;
        if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
        stale.emplace_back(e->d_name);
    }
    ::closedir(d);
    int removed = 0;
    for (const auto& name : stale) {
        std::error_code ec;
        if (std::filesystem::remove_all(std::filesystem::path(dir.empty() ? "." : dir) / name, ec) > 0 && !ec) ++removed;
    }
    return removed;
}

std::string partial_path(const std::string& path) {
    const std::filesystem::path p(path);
    {
        // Once per directory and process: the first output there clears what dead runs left.
        static std::mutex m;
        static std::set<std::string> cleaned;
        const std::string dir = p.parent_path().string();
        std::lock_guard<std::mutex> lock(m);
        if (cleaned.insert(dir).second) remove_stale_partials(dir);
    }
    std::string name = p.filename().string();
    name.insert(0, 1, '.');   // (not "." + name: GCC 12's -Wrestrict false positive)
    name.append(".partial-").append(std::to_string(::getpid()));
    std::string partial = (p.parent_path() / name).string();
    remember(partial);
    return partial;
}

void commit_partial(const std::string& partial, const std::string& path) {
    if (t_depth > 0) {
        t_staged.push_back({partial, path});
        return;
    }
    std::error_code ec;
    std::filesystem::rename(partial, path, ec);
    if (ec) {
        discard_partial(partial);
        throw std::runtime_error(path + ": cannot write it (" + ec.message() + ")");
    }
    forget(partial);
}

void discard_partial(const std::string& partial) {
    std::error_code ec;
    std::filesystem::remove(partial, ec);
    forget(partial);
}

void write_file_whole(const std::string& path, std::string_view bytes) {
    const std::string tmp = partial_path(path);
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) {
        const int err = errno;
        forget(tmp);
        throw std::runtime_error(path + ": cannot write it (" + errno_text(err) + ")");
    }
    int err = 0;
    for (std::size_t done = 0; done < bytes.size();) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            err = n < 0 ? errno : EIO;
            break;
        }
        done += static_cast<std::size_t>(n);
    }
    // close() reports what a delayed write found (NFS, quotas): checked like the writes.
    if (::close(fd) != 0 && err == 0) err = errno;
    if (err != 0) {
        discard_partial(tmp);
        throw std::runtime_error(path + ": write failed (" + errno_text(err) + ")");
    }
    commit_partial(tmp, path);
}

OutputGroup::OutputGroup() : outermost_(t_depth == 0) { ++t_depth; }

OutputGroup::~OutputGroup() {
    if (outermost_) discard();
    --t_depth;
}

void OutputGroup::discard() {
    if (!outermost_) return;
    for (const Staged& s : t_staged) discard_partial(s.partial);
    t_staged.clear();
}

void OutputGroup::commit() {
    if (!outermost_) return;
    std::vector<Staged> staged;
    staged.swap(t_staged);
    // The old files are kept under a second name (a hard link) until every rename succeeded: a failure midway
    // puts them back, and a file that did not exist before is removed again.
    std::vector<std::string> backup(staged.size());
    for (std::size_t i = 0; i < staged.size(); ++i) {
        std::string b = staged[i].partial + "-old";
        if (::link(staged[i].path.c_str(), b.c_str()) == 0) {
            remember(b);
            backup[i] = std::move(b);
        }
    }
    auto drop_backups = [&] {
        for (const auto& b : backup)
            if (!b.empty()) discard_partial(b);
    };
    for (std::size_t i = 0; i < staged.size(); ++i) {
        std::error_code ec;
        std::filesystem::rename(staged[i].partial, staged[i].path, ec);
        if (!ec) {
            forget(staged[i].partial);
            continue;
        }
        for (std::size_t j = i; j < staged.size(); ++j) discard_partial(staged[j].partial);
        for (std::size_t j = 0; j < i; ++j) {
            std::error_code ec2;
            if (!backup[j].empty()) {
                std::filesystem::rename(backup[j], staged[j].path, ec2);
                if (!ec2) forget(backup[j]);
            } else {
                std::filesystem::remove(staged[j].path, ec2);
            }
        }
        drop_backups();
        throw std::runtime_error(staged[i].path + ": cannot write it (" + ec.message() + "); the files written with it were put back");
    }
    drop_backups();
}

void remove_partials_on_signal() {
    g_handling.store(true, std::memory_order_release);
    struct sigaction sa {};
    sa.sa_handler = remove_partials_and_reraise;
    sigemptyset(&sa.sa_mask);
    for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) {
        struct sigaction old {};
        sigaction(sig, nullptr, &old);
        if (old.sa_handler == SIG_IGN) continue;   // ignored by whoever started us (nohup, a background job)
        sigaction(sig, &sa, nullptr);
    }
}

}  // namespace impactlab
