#include "impactlab/input_file.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace impactlab {

namespace {

std::string errno_text(int err) { return std::system_category().message(err); }

// An open descriptor, closed on every path out.
struct Fd {
    int fd = -1;
    ~Fd() {
        if (fd >= 0) ::close(fd);
    }
};

// Opens `path` without blocking (a FIFO with no writer would block a plain open) and checks its kind and size.
void open_checked(const std::string& path, std::size_t max_bytes, Fd& f) {
    if (path.empty()) throw InputFileError(path, "an empty file name");
    f.fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (f.fd < 0) {
        const int err = errno;
        throw InputFileError(path, "cannot read it (" + errno_text(err) + ")");
    }
    struct stat st {};
    if (::fstat(f.fd, &st) != 0) {
        const int err = errno;
        throw InputFileError(path, "cannot read it (" + errno_text(err) + ")");
    }
    if (S_ISDIR(st.st_mode)) throw InputFileError(path, "is a directory, not a file");
    if (S_ISFIFO(st.st_mode)) throw InputFileError(path, "is a named pipe (FIFO), not a regular file");
    if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) throw InputFileError(path, "is a device, not a regular file");
    if (!S_ISREG(st.st_mode)) throw InputFileError(path, "is not a regular file");
    if (static_cast<unsigned long long>(st.st_size) > max_bytes)
        throw InputFileError(path, size_text(static_cast<std::size_t>(st.st_size)) + ", more than the " +
                             size_text(max_bytes) + " an input may hold");
}

}  // namespace

std::string size_text(std::size_t bytes) {
    constexpr std::size_t KiB = 1024, MiB = KiB * 1024, GiB = MiB * 1024;
    char buf[48];
    if (bytes >= GiB && bytes % GiB == 0) std::snprintf(buf, sizeof buf, "%zu GiB", bytes / GiB);
    else if (bytes >= GiB) std::snprintf(buf, sizeof buf, "%.1f GiB", static_cast<double>(bytes) / GiB);
    else if (bytes >= MiB && bytes % MiB == 0) std::snprintf(buf, sizeof buf, "%zu MiB", bytes / MiB);
    else if (bytes >= MiB) std::snprintf(buf, sizeof buf, "%.1f MiB", static_cast<double>(bytes) / MiB);
    else std::snprintf(buf, sizeof buf, "%zu bytes", bytes);
    return buf;
}

std::size_t utf8_sequence(std::string_view text, std::size_t i) {
    const auto b = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char c = b(i);
    if (c < 0x80) return 1;
    std::size_t n = 0;
    unsigned char lo = 0x80, hi = 0xbf;   // the second byte's range (RFC 3629: no overlongs, no surrogates)
    if (c >= 0xc2 && c <= 0xdf) n = 2;
    else if (c >= 0xe0 && c <= 0xef) {
        n = 3;
        if (c == 0xe0) lo = 0xa0;
        if (c == 0xed) hi = 0x9f;
    } else if (c >= 0xf0 && c <= 0xf4) {
        n = 4;
        if (c == 0xf0) lo = 0x90;
        if (c == 0xf4) hi = 0x8f;
    } else {
        return 0;
    }
    if (i + n > text.size()) return 0;
    if (b(i + 1) < lo || b(i + 1) > hi) return 0;
    for (std::size_t k = 2; k < n; ++k)
        if (b(i + k) < 0x80 || b(i + k) > 0xbf) return 0;
    return n;
}

namespace {
// Appends text[0, keep) with bytes that are not UTF-8 (and, if `controls`, control characters) as \xNN.
void append_escaped(std::string& out, std::string_view text, bool controls) {
    for (std::size_t i = 0; i < text.size();) {
        const auto c = static_cast<unsigned char>(text[i]);
        const std::size_t n = utf8_sequence(text, i);
        if (n == 0 || (controls && (c < 0x20 || c == 0x7f))) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02x", c);
            out += buf;
            ++i;
            continue;
        }
        out.append(text.substr(i, n));
        i += n;
    }
}
}  // namespace

std::string utf8_escaped(std::string_view text) {
    std::string out;
    out.reserve(text.size() + 16);
    append_escaped(out, text, false);
    return out;
}

std::string printable(std::string_view text, std::size_t max_bytes) {
    std::string out;
    const std::size_t keep = std::min(text.size(), max_bytes);
    out.reserve(keep + 40);
    append_escaped(out, text.substr(0, keep), true);
    if (keep < text.size()) out += " ... (" + size_text(text.size() - keep) + " more)";
    return out;
}

void check_input_file(const std::string& path, std::size_t max_bytes) {
    Fd f;
    open_checked(path, max_bytes, f);
}

std::string read_input_file(const std::string& path, std::size_t max_bytes) {
    Fd f;
    open_checked(path, max_bytes, f);
    struct stat st {};
    ::fstat(f.fd, &st);
    constexpr std::size_t kPiece = std::size_t{1} << 20;
    std::string bytes;
    bytes.reserve(static_cast<std::size_t>(st.st_size) + kPiece);
    for (;;) {
        const std::size_t have = bytes.size();
        // Grown by hand: a doubling string would reach twice the cap just as the cap is reached.
        if (bytes.capacity() < have + kPiece)
            bytes.reserve(std::min(std::max(2 * bytes.capacity(), have + kPiece), max_bytes + kPiece));
        bytes.resize(have + kPiece);
        const ssize_t n = ::read(f.fd, &bytes[have], kPiece);
        if (n < 0) {
            const int err = errno;
            if (err == EINTR) {
                bytes.resize(have);
                continue;
            }
            throw InputFileError(path, "cannot read it (" + errno_text(err) + ")");
        }
        bytes.resize(have + static_cast<std::size_t>(n));
        if (n == 0) break;
        if (bytes.size() > max_bytes)
            throw InputFileError(path, "more than the " + size_text(max_bytes) + " an input may hold");
    }
    return bytes;
}

}  // namespace impactlab
