// Reading an input file (a record, a parameter or session file, a scan CSV) safely: its kind and size are
// checked before a byte is read, and it is read in pieces up to a cap, so a directory, a FIFO, a device or a
// huge file is refused with a message naming it instead of hanging or exhausting the memory.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace impactlab {

// The most an input may hold, on disk and, for gzip, once decompressed.
inline constexpr std::size_t kMaxInputBytes = std::size_t{1} << 30;

// what() is "PATH: REASON"; the two parts apart for a caller that words its own message.
struct InputFileError : std::runtime_error {
    InputFileError(const std::string& file, const std::string& why)
        : std::runtime_error((file.empty() ? std::string("''") : file) + ": " + why), path(file), reason(why) {}
    std::string path, reason;
};

// Throws InputFileError unless `path` can be opened for reading, is a regular file (not a directory, FIFO,
// socket or device) and holds at most `max_bytes`. Never blocks, whatever `path` names.
void check_input_file(const std::string& path, std::size_t max_bytes = kMaxInputBytes);
// The bytes of `path` after check_input_file's checks, read in pieces; a file that grows past `max_bytes`
// while being read (or a /proc file, whose size reads as 0) is refused at the cap.
std::string read_input_file(const std::string& path, std::size_t max_bytes = kMaxInputBytes);
// "1 GiB", "12.5 MiB", "300 bytes": a size in a message.
std::string size_text(std::size_t bytes);
// Text from an input (a name, a token, a message quoting one) made safe to print on a terminal: control
// characters, DEL and bytes that are not UTF-8 as \xNN (an escape sequence shows, it does not act; a file
// name in Latin-1 shows its bytes), cut after `max_bytes` with a note of how much was left out.
std::string printable(std::string_view text, std::size_t max_bytes = 4000);
// `text` with every byte that is not part of a well-formed UTF-8 sequence written as \xNN, the rest as it is:
// a file name carried as bytes becomes text a JSON file or a Markdown report can hold. Never throws.
std::string utf8_escaped(std::string_view text);
// The length of the well-formed UTF-8 sequence at text[i] (1 to 4), or 0 if the byte there starts none.
std::size_t utf8_sequence(std::string_view text, std::size_t i);

}  // namespace impactlab
