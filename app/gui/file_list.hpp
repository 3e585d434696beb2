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

}  // namespace impactlab::gui
