#include "program_assets.hpp"

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "impactlab/plot.hpp"

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

std::vector<std::string> font_files() {
    std::vector<std::string> files;
    if (const char* env = std::getenv("IMPACTLAB_FONT"); env != nullptr && *env != '\0') files.emplace_back(env);
    if (std::string own = asset_path("fonts/DejaVuSans.ttf"); !own.empty()) files.push_back(std::move(own));
    files.emplace_back("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf");
    return files;
}

void use_program_fonts() { plot::set_font_files(font_files()); }

}  // namespace impactlab
