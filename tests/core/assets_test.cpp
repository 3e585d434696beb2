// asset_path: an installed program finds its data under <program>/../share/impactlab, before the
// source tree's assets/.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "impactlab/assets.hpp"

TEST_CASE("asset_path: the source tree's assets, then share/impactlab beside the program") {
    namespace fs = std::filesystem;
    const std::string font = impactlab::asset_path("fonts/DejaVuSans.ttf");
    REQUIRE(!font.empty());
    CHECK(fs::is_regular_file(font));
    CHECK(impactlab::asset_path("fonts/no-such-file.ttf").empty());

    // As installed: PREFIX/bin/<program> and PREFIX/share/impactlab/<file>.
    const fs::path share = fs::read_symlink("/proc/self/exe").parent_path().parent_path() / "share" / "impactlab";
    const std::string name = "assets-test-" + std::to_string(::getpid()) + ".txt";
    fs::path made = share;   // the outermost folder this test creates (removed after), if any
    while (!fs::exists(made.parent_path())) made = made.parent_path();
    const bool existed = fs::exists(share);
    fs::create_directories(share);
    { std::ofstream(share / name) << "x"; }
    CHECK(impactlab::asset_path(name) == (share / name).string());
    fs::remove(share / name);
    if (!existed) fs::remove_all(made);
    CHECK(impactlab::asset_path(name).empty());
}
