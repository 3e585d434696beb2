// Files written whole or not at all: the bytes go to a hidden partial file beside the target and are renamed
// over it once complete, so a failed run leaves an old file as it was (the CLI's outputs, PNGs, fit reports).
#pragma once

#include <string>

namespace impactlab {

// ".NAME.partial-PID" in the directory of `path` (the PID keeps two processes' partial files apart).
std::string partial_path(const std::string& path);
// Renames `partial` over `path`; if that fails, removes `partial` and throws std::runtime_error naming `path`.
void commit_partial(const std::string& partial, const std::string& path);
// Removes a partial file that will not be committed (no error if it is gone).
void discard_partial(const std::string& partial);

}  // namespace impactlab
