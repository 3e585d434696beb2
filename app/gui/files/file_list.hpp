// A directory as the visualiser's file browser lists it: folders first (with ".." to go up), then the files
// whose names end in one of the wanted extensions (case-insensitive), each group sorted by name; hidden
// entries (a leading '.') left out. GL- and ImGui-free (the browser view draws it).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace impactlab::gui {

struct FileEntry {
    std::string name;          // "data.csv", or a folder's name ("..": the parent)
    bool dir = false;
    std::uintmax_t size = 0;   // [bytes] files only
};

// `error` says why a directory cannot be listed ("" when it can); the list is then empty.
std::vector<FileEntry> list_files(const std::string& dir, const std::vector<std::string>& extensions, std::string& error);

// What a click on a row of the browser means. A double-click acts only on the row its first click picked
// (in the same folder): the first click of a double-click on a folder opens it, and the second then lands
// on whatever row now lies under the mouse, which must neither pick nor open (nor save over) that file.
enum class RowAction { None, Pick, Open, EnterDir };
class RowClicks {
public:
    // A click at time t [s] on row `name` of folder `dir`; `double_click` as the toolkit says; clicks
    // closer than `double_time` [s] count as one gesture.
    RowAction click(const std::string& dir, const std::string& name, bool is_dir, bool double_click, double t,
                    double double_time);

private:
    std::string dir_, name_;   // the row the last click picked ("" none)
    double entered_at_ = -1e30;   // [s] when a click opened the folder now listed
};

// Where "Save" writes for the path typed: into a folder when the path is one (an existing folder, or a path
// ending in '/'), under `default_name`; else the path itself.
std::string save_target(const std::string& path, const std::string& default_name);
// The path once the browser entered folder `dir`: the same file name in that folder (saving into a folder
// means that folder), `default_name` when the path names no file.
std::string path_in_folder(const std::string& dir, const std::string& path, const std::string& default_name);

}  // namespace impactlab::gui
