// A simple file browser under a path field (the session window, the measured data): the folder of the path
// typed, listed by file_list.hpp; a click on a folder opens it (and the field's file name moves into it), a
// click on a file puts its path in the field, a double-click on the row its first click picked also says
// "open" (RowClicks: the rest of a double-click that opened a folder acts on nothing). No dependency beyond Dear ImGui. UI thread only.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "files/file_list.hpp"

namespace impactlab::gui {

class FileBrowser {
public:
    // default_name: the file name the field gets in a folder entered when it names none ("": the field is
    // left as it is when a folder is entered).
    FileBrowser(std::vector<std::string> extensions, std::string default_name)
        : extensions_(std::move(extensions)), default_name_(std::move(default_name)) {}
    // Lists `dir` from now on (--browse DIR).
    void open_dir(const std::string& dir);
    // Draws the list, `rows` lines high, for the path in `path` (its folder when the browser has none of its
    // own yet); true when a file was double-clicked (the caller loads `path`).
    bool draw(const char* id, char* path, std::size_t cap, float rows = 8);
    const std::string& dir() const { return dir_; }
    nlohmann::json state() const;
    // A row as last drawn (screen pixels), by its listed name ("sub/" for a folder); null if not shown.
    struct Row {
        std::string name;
        float x0, y0, x1, y1;
    };
    const Row* row(const std::string& name) const;   // for --state-json: the folder and its entries ("name/" for folders)

private:
    void refresh();
    void refresh_if_changed();
    std::vector<std::string> extensions_;
    std::string default_name_;
    RowClicks clicks_;
    std::vector<Row> rows_;
    std::string dir_;                 // absolute, "" until first drawn
    std::vector<FileEntry> entries_;
    std::string error_;
    double listed_at_ = -1;                            // [s] ImGui time of the listing (looked at again every 2 s)
    std::filesystem::file_time_type listed_stamp_{};   // the folder's time when listed
};

}  // namespace impactlab::gui
