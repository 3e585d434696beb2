#include "impactlab/assets.hpp"

#include <filesystem>
#include <system_error>

namespace impactlab {

std::string asset_path(const std::string& relative) {
    namespace fs = std::filesystem;
    std::error_code ec;
    // Linux: the running program, whatever the working directory or the name it was started by.
    if (const fs::path exe = fs::read_symlink("/proc/self/exe", ec); !ec) {
        const fs::path installed = exe.parent_path().parent_path() / "share" / "impactlab" / relative;
        if (fs::is_regular_file(installed, ec)) return installed.string();
    }
#ifdef IMPACTLAB_ASSET_DIR
    const fs::path source = fs::path(IMPACTLAB_ASSET_DIR) / relative;
    if (fs::is_regular_file(source, ec)) return source.string();
#endif
    return "";
}

}  // namespace impactlab
