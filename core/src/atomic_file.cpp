#include "impactlab/atomic_file.hpp"

#include <filesystem>
#include <stdexcept>
#include <system_error>

#include <unistd.h>

namespace impactlab {

std::string partial_path(const std::string& path) {
    const std::filesystem::path p(path);
    std::string name = p.filename().string();
    name.insert(0, 1, '.');   // (not "." + name: GCC 12's -Wrestrict false positive)
    name.append(".partial-").append(std::to_string(::getpid()));
    return (p.parent_path() / name).string();
}

void commit_partial(const std::string& partial, const std::string& path) {
    std::error_code ec;
    std::filesystem::rename(partial, path, ec);
    if (ec) {
        discard_partial(partial);
        throw std::runtime_error(path + ": cannot write it (" + ec.message() + ")");
    }
}

void discard_partial(const std::string& partial) {
    std::error_code ec;
    std::filesystem::remove(partial, ec);
}

}  // namespace impactlab
