// Files written whole or not at all: the bytes go to a hidden partial file beside the target and are renamed
// over it once complete, so a failed run leaves an old file as it was (the CLI's outputs, PNGs, fit reports).
#pragma once

#include <string>

namespace impactlab {

// ".NAME.partial-PID" in the directory of `path` (the PID keeps two processes' partial files apart). Once
// remove_partials_on_signal was called, the name is remembered until commit_partial or discard_partial.
std::string partial_path(const std::string& path);
// Renames `partial` over `path`; if that fails, removes `partial` and throws std::runtime_error naming `path`.
void commit_partial(const std::string& partial, const std::string& path);
// Removes a partial file that will not be committed (no error if it is gone).
void discard_partial(const std::string& partial);

// Installs handlers for SIGINT, SIGTERM and SIGHUP that remove every partial file not yet committed or
// discarded, then let the signal end the process as it would have (exit status 128 + signal in a shell).
// A signal the process ignores stays ignored. For programs whose only reaction to these signals is to stop
// (the CLI); call once, from main.
void remove_partials_on_signal();

}  // namespace impactlab
