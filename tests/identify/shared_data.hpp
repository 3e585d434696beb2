// Tests on the sibling ../shared data: where a file is missing (a clone without it) the test is reported as
// skipped, with a line on stderr that names the file; it never runs and passes on nothing.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>

namespace impactlab::test {

inline std::string shared_path(const std::string& rel) { return std::string(IMPACTLAB_SHARED_DIR) + "/" + rel; }

// For doctest::skip(...) at registration: true (skip) when the file is missing, and says so.
inline bool shared_missing(const std::string& rel) {
    const std::string path = shared_path(rel);
    if (std::filesystem::exists(path)) return false;
    std::fprintf(stderr, "[doctest] SKIPPED: shared data %s is missing; its test is skipped, not passed\n", path.c_str());
    return true;
}

}  // namespace impactlab::test
