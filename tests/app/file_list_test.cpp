// The file browser's listing (file_list.hpp): folders first with ".." to go up, then the files with a wanted
// extension in any case, each group sorted by name; hidden entries left out; a missing folder said.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../../app/gui/files/file_list.hpp"

using namespace impactlab::gui;

TEST_CASE("file_list: folders first, wanted extensions only, hidden entries left out") {
    namespace fs = std::filesystem;
    const fs::path d = fs::temp_directory_path() / "impactlab_file_list_test";
    fs::remove_all(d);
    fs::create_directories(d / "zeta");
    fs::create_directories(d / "Alpha");
    fs::create_directories(d / ".git");
    for (const char* f : {"b.json", "A.JSON", "c.csv", ".hidden.json", "d.json.bak"}) std::ofstream(d / f) << "{}";
    std::string error;
    const std::vector<FileEntry> l = list_files(d.string(), {".json"}, error);
    CHECK(error.empty());
    std::vector<std::string> names;
    for (const FileEntry& e : l) names.push_back(e.name + (e.dir ? "/" : ""));
    CHECK(names == std::vector<std::string>{"../", "Alpha/", "zeta/", "A.JSON", "b.json"});
    CHECK(l.back().size == 2);
    const std::vector<FileEntry> data = list_files(d.string(), {".csv", ".gz"}, error);
    CHECK(data.back().name == "c.csv");
    CHECK(list_files((d / "missing").string(), {".json"}, error).empty());
    CHECK(error.find("cannot list") != std::string::npos);
    fs::remove_all(d);
}

TEST_CASE("RowClicks: a double-click acts on the row its first click picked, never on the row under a folder it opened") {
    RowClicks c;
    const double dt = 0.3;
    // The gesture: a double-click on "sub/" opens it at the first click; the second lands on
    // "live.json", now in that row, and must neither pick nor open it.
    CHECK(c.click("/d", "sub", true, false, 10.00, dt) == RowAction::EnterDir);
    CHECK(c.click("/d/sub", "live.json", false, true, 10.15, dt) == RowAction::None);
    // Later, a single click picks, a double-click on the same row opens.
    CHECK(c.click("/d/sub", "live.json", false, false, 12.00, dt) == RowAction::Pick);
    CHECK(c.click("/d/sub", "live.json", false, true, 12.10, dt) == RowAction::Open);
    // A double-click whose first click picked another row only picks.
    CHECK(c.click("/d/sub", "a.json", false, false, 14.00, dt) == RowAction::Pick);
    CHECK(c.click("/d/sub", "b.json", false, true, 14.10, dt) == RowAction::Pick);
    // The same name in another folder is another row.
    CHECK(c.click("/d/sub", "..", true, false, 16.00, dt) == RowAction::EnterDir);
    CHECK(c.click("/d", "b.json", false, true, 18.00, dt) == RowAction::Pick);
}

TEST_CASE("save_target and path_in_folder: saving into a folder means that folder") {
    namespace fs = std::filesystem;
    const fs::path d = fs::temp_directory_path() / "impactlab_save_target_test";
    fs::remove_all(d);
    fs::create_directories(d / "sub");
    CHECK(save_target((d / "sub").string(), "s.json") == (d / "sub" / "s.json").string());
    CHECK(save_target((d / "new").string() + "/", "s.json") == (d / "new" / "s.json").string());
    CHECK(save_target((d / "x.json").string(), "s.json") == (d / "x.json").string());
    CHECK(save_target("", "s.json") == "s.json");
    CHECK(path_in_folder((d / "sub").string(), (d / "live.json").string(), "s.json") == (d / "sub" / "live.json").string());
    CHECK(path_in_folder((d / "sub").string(), (d.string() + "/"), "s.json") == (d / "sub" / "s.json").string());
    fs::remove_all(d);
}
