// The session window's state (app_session.cpp): open or not, saving or loading, the path typed and the
// folder's .json files, a request for after the panels drew, the file a save would replace, the last error.
// UI thread only.
#pragma once

#include <string>

#include "views/file_browser.hpp"

namespace impactlab::gui {

struct SessionWindow {
    bool open = false, saving = true;
    int request = 0;                   // 1 save, 2 load, 3 save over the existing file (after the panels drew)
    std::string overwrite_pending;     // the existing file a save would replace, asked about ("" none)
    char path[512] = "impactlab-session.json";
    FileBrowser browser{{".json"}, "impactlab-session.json"};   // the folder's .json files
    std::string error;
};

}  // namespace impactlab::gui
