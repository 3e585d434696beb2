// A full disk on demand, for the disk-full tests (LD_PRELOAD): writes to regular files succeed until
// IMPACTLAB_TEST_WRITE_BUDGET bytes in all were written, then fail with ENOSPC, as on a file system that
// fills up midway. Writes to pipes and terminals (stdout, stderr) are never refused.
// With IMPACTLAB_TEST_WRITE_COUNT=FILE, the bytes written to regular files are written to FILE at exit (the
// test picks its budgets from a run's total). The program's own writes (libstdc++'s files, write(2)) call
// these; glibc's stdio inside libc does not, and the CLI writes no file through it.
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>

#include <dlfcn.h>
#include <sys/stat.h>
#include <sys/uio.h>
#include <unistd.h>

namespace {
std::atomic<long long> g_written{0};

bool regular(int fd) {
    struct stat st;
    return fstat(fd, &st) == 0 && S_ISREG(st.st_mode);
}

// How many of `n` bytes may go to `fd` now: n, fewer (the rest of the budget), or 0 (ENOSPC).
size_t allowed(int fd, size_t n) {
    if (n == 0 || !regular(fd)) return n;
    const char* b = getenv("IMPACTLAB_TEST_WRITE_BUDGET");
    if (b == nullptr) {
        g_written += static_cast<long long>(n);
        return n;
    }
    const long long budget = std::atoll(b);
    long long before = g_written.load();
    for (;;) {
        const long long room = budget - before;
        if (room <= 0) return 0;
        const size_t take = static_cast<long long>(n) < room ? n : static_cast<size_t>(room);
        if (g_written.compare_exchange_weak(before, before + static_cast<long long>(take))) return take;
    }
}

template <class F>
F real(const char* name) {
    return reinterpret_cast<F>(dlsym(RTLD_NEXT, name));
}
}  // namespace

extern "C" {

ssize_t write(int fd, const void* buf, size_t n) {
    static const auto next = real<ssize_t (*)(int, const void*, size_t)>("write");
    const size_t k = allowed(fd, n);
    if (k == 0 && n > 0) {
        errno = ENOSPC;
        return -1;
    }
    return next(fd, buf, k);
}

ssize_t writev(int fd, const struct iovec* iov, int cnt) {
    static const auto next = real<ssize_t (*)(int, const struct iovec*, int)>("writev");
    size_t n = 0;
    for (int i = 0; i < cnt; ++i) n += iov[i].iov_len;
    const size_t k = allowed(fd, n);
    if (k == n) return next(fd, iov, cnt);
    if (k == 0) {
        errno = ENOSPC;
        return -1;
    }
    // A short write: the first k bytes, as a file system that filled up would take.
    struct iovec part[64];
    int m = 0;
    for (size_t left = k; m < cnt && m < 64 && left > 0; ++m) {
        part[m] = iov[m];
        if (part[m].iov_len > left) part[m].iov_len = left;
        left -= part[m].iov_len;
    }
    return next(fd, part, m);
}

ssize_t pwrite64(int fd, const void* buf, size_t n, off_t off) {
    static const auto next = real<ssize_t (*)(int, const void*, size_t, off_t)>("pwrite64");
    const size_t k = allowed(fd, n);
    if (k == 0 && n > 0) {
        errno = ENOSPC;
        return -1;
    }
    return next(fd, buf, k, off);
}
}  // extern "C"

__attribute__((destructor)) static void report_count() {
    const char* f = std::getenv("IMPACTLAB_TEST_WRITE_COUNT");
    if (f == nullptr) return;
    std::FILE* o = std::fopen(f, "w");
    if (o == nullptr) return;
    std::fprintf(o, "%lld\n", g_written.load());
    std::fclose(o);
}
