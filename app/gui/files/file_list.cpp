#include "file_list.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <system_error>

namespace impactlab::gui {

namespace {

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

bool wanted(const std::string& name, const std::vector<std::string>& extensions) {
    const std::string n = lower(name);
    for (const std::string& e : extensions)
        if (n.size() > e.size() && n.compare(n.size() - e.size(), e.size(), lower(e)) == 0) return true;
    return extensions.empty();
}

}  // namespace

std::vector<FileEntry> list_files(const std::string& dir, const std::vector<std::string>& extensions, std::string& error) {
    namespace fs = std::filesystem;
    error.clear();
    std::vector<FileEntry> dirs, files;
    std::error_code ec;
    const fs::path root = fs::absolute(dir.empty() ? fs::path(".") : fs::path(dir), ec);
    fs::directory_iterator it(root, fs::directory_options::skip_permission_denied, ec);
    if (ec) {
        error = "cannot list '" + dir + "': " + ec.message();
        return {};
    }
    for (const fs::directory_entry& e : it) {
        const std::string name = e.path().filename().string();
        if (name.empty() || name[0] == '.') continue;
        std::error_code e2;
        if (e.is_directory(e2)) dirs.push_back({name, true, 0});
        else if (e.is_regular_file(e2) && wanted(name, extensions)) files.push_back({name, false, e.file_size(e2)});
    }
    auto by_name = [](const FileEntry& a, const FileEntry& b) { return lower(a.name) < lower(b.name); };
    std::sort(dirs.begin(), dirs.end(), by_name);
    std::sort(files.begin(), files.end(), by_name);
    std::vector<FileEntry> out;
    if (root.lexically_normal().has_relative_path()) out.push_back({"..", true, 0});   // not at "/"
    out.insert(out.end(), dirs.begin(), dirs.end());
    out.insert(out.end(), files.begin(), files.end());
    return out;
}

RowAction RowClicks::click(const std::string& dir, const std::string& name, bool is_dir, bool double_click, double t,
                           double double_time) {
    if (t - entered_at_ <= double_time) return RowAction::None;   // the rest of the gesture that opened this folder
    if (is_dir) {
        entered_at_ = t;
        dir_.clear();
        name_.clear();
        return RowAction::EnterDir;
    }
    if (double_click && dir == dir_ && name == name_) return RowAction::Open;
    dir_ = dir;
    name_ = name;
    return RowAction::Pick;
}

std::string save_target(const std::string& path, const std::string& default_name) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (path.empty()) return default_name;
    if (path.back() == '/' || fs::is_directory(path, ec)) return (fs::path(path) / default_name).lexically_normal().string();
    return path;
}

std::string path_in_folder(const std::string& dir, const std::string& path, const std::string& default_name) {
    namespace fs = std::filesystem;
    std::string name = fs::path(path).filename().string();
    if (name.empty() || name == "." || name == "..") name = default_name;
    return (fs::path(dir) / name).lexically_normal().string();
}

}  // namespace impactlab::gui
