// The file browser's listing (file_list.hpp): folders first with ".." to go up, then the files with a wanted
// extension in any case, each group sorted by name; hidden entries left out; a missing folder said.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../../app/gui/file_list.hpp"

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
