#include "impactlab/atomic_file.hpp"

#include <atomic>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>

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

std::string partial_path(const std::string& path) {
    const std::filesystem::path p(path);
    std::string name = p.filename().string();
    name.insert(0, 1, '.');   // (not "." + name: GCC 12's -Wrestrict false positive)
    name.append(".partial-").append(std::to_string(::getpid()));
    std::string partial = (p.parent_path() / name).string();
    remember(partial);
    return partial;
}

void commit_partial(const std::string& partial, const std::string& path) {
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

void remove_partials_on_signal() {
    g_handling.store(true, std::memory_order_release);
    struct sigaction sa {};
    sa.sa_handler = remove_partials_and_reraise;
    sigemptyset(&sa.sa_mask);
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
        struct sigaction old {};
        sigaction(sig, nullptr, &old);
        if (old.sa_handler == SIG_IGN) continue;   // ignored by whoever started us (nohup, a background job)
        sigaction(sig, &sa, nullptr);
    }
}

}  // namespace impactlab
