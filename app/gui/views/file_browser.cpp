#include "file_browser.hpp"

#include <imgui.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <system_error>

#include "render/theme.hpp"

namespace impactlab::gui {

namespace fs = std::filesystem;

void FileBrowser::open_dir(const std::string& dir) {
    std::error_code ec;
    dir_ = fs::absolute(dir.empty() ? fs::path(".") : fs::path(dir), ec).lexically_normal().string();
    refresh();
}

void FileBrowser::refresh() {
    entries_ = list_files(dir_, extensions_, error_);
    listed_at_ = ImGui::GetCurrentContext() ? ImGui::GetTime() : 0.0;
    std::error_code ec;
    listed_stamp_ = fs::last_write_time(dir_, ec);
}

void FileBrowser::refresh_if_changed() {
    // A file created, renamed into place or removed changes the folder's time; only then is it listed again
    // (a folder of 200,000 files takes a good part of a second to list and sort).
    listed_at_ = ImGui::GetTime();
    std::error_code ec;
    const fs::file_time_type stamp = fs::last_write_time(dir_, ec);
    if (ec || stamp != listed_stamp_) refresh();
}

bool FileBrowser::draw(const char* id, char* path, std::size_t cap, float rows) {
    if (dir_.empty()) {   // the folder of the path typed, else the working directory
        std::error_code ec;
        const fs::path p(path);
        open_dir(!p.empty() && p.has_parent_path() && fs::is_directory(p.parent_path(), ec) ? p.parent_path().string() : ".");
    }
    if (ImGui::GetTime() - listed_at_ > 2.0) refresh_if_changed();   // a file written meanwhile shows up
    bool open = false;
    ImGui::TextDisabled("%s", dir_.c_str());
    if (!error_.empty()) ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(palette().warn), "%s", error_.c_str());
    const float h = rows * ImGui::GetTextLineHeightWithSpacing();
    rows_.clear();
    if (ImGui::BeginChild(id, ImVec2(ImGui::GetContentRegionAvail().x, h), true)) {
        std::string go;   // a folder clicked: opened after the loop (the list is being walked)
        const ImGuiIO& io = ImGui::GetIO();
        // Only the rows in view are built (a folder of 200,000 files drew at 1.6 fps row by row).
        ImGuiListClipper clipper;
        clipper.Begin(static_cast<int>(entries_.size()));
        while (clipper.Step()) {
            for (int i = clipper.DisplayStart; i < clipper.DisplayEnd; ++i) {
                const FileEntry& e = entries_[static_cast<std::size_t>(i)];
                char label[300];
                if (e.dir) std::snprintf(label, sizeof label, "%s/", e.name.c_str());
                else std::snprintf(label, sizeof label, "%s  (%.1f kB)", e.name.c_str(), static_cast<double>(e.size) / 1024.0);
                const std::string full = (fs::path(dir_) / e.name).lexically_normal().string();
                const bool chosen = !e.dir && full == path;
                if (ImGui::Selectable(label, chosen, ImGuiSelectableFlags_AllowDoubleClick)) {
                    switch (clicks_.click(dir_, e.name, e.dir, ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left), ImGui::GetTime(),
                                          static_cast<double>(io.MouseDoubleClickTime))) {
                        case RowAction::EnterDir: go = full; break;
                        case RowAction::Pick: std::snprintf(path, cap, "%s", full.c_str()); break;
                        case RowAction::Open:
                            std::snprintf(path, cap, "%s", full.c_str());
                            open = true;
                            break;
                        case RowAction::None: break;
                    }
                }
                const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
                rows_.push_back({e.dir ? e.name + "/" : e.name, lo.x, lo.y, hi.x, hi.y});
            }
        }
        if (entries_.empty() && error_.empty()) ImGui::TextDisabled("(no matching files)");
        if (!go.empty()) {   // the field follows: saving now writes into the folder entered
            open_dir(go);
            if (!default_name_.empty()) std::snprintf(path, cap, "%s", path_in_folder(dir_, path, default_name_).c_str());
        }
    }
    ImGui::EndChild();
    return open;
}

const FileBrowser::Row* FileBrowser::row(const std::string& name) const {
    for (const Row& r : rows_)
        if (r.name == name) return &r;
    return nullptr;
}

nlohmann::json FileBrowser::state() const {
    nlohmann::json names = nlohmann::json::array();
    for (const FileEntry& e : entries_) names.push_back(e.dir ? e.name + "/" : e.name);
    return {{"dir", dir_}, {"entries", std::move(names)}, {"error", error_}, {"rows_drawn", rows_.size()}};
}

}  // namespace impactlab::gui
