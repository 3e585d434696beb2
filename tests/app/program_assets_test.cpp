// The programs' data files: an installed program finds them under <program>/../share/impactlab, before the
// source tree's assets/, and hands core the font (core knows no path of its own).
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <unistd.h>

#include "impactlab/plot.hpp"
#include "program_assets.hpp"

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

TEST_CASE("font_files: $IMPACTLAB_FONT first, then the program's own font, then the system's") {
    const char* old = std::getenv("IMPACTLAB_FONT");
    const std::string saved = old != nullptr ? old : "";
    ::setenv("IMPACTLAB_FONT", "/no/such/font.ttf", 1);
    const auto files = impactlab::font_files();
    if (old != nullptr) ::setenv("IMPACTLAB_FONT", saved.c_str(), 1);
    else ::unsetenv("IMPACTLAB_FONT");
    REQUIRE(files.size() == 3);
    CHECK(files[0] == "/no/such/font.ttf");
    CHECK(files[1] == impactlab::asset_path("fonts/DejaVuSans.ttf"));
    CHECK(files[2] == "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf");
}

TEST_CASE("plot: core draws with the font the program handed in, the first that loads") {
    namespace plot = impactlab::plot;
    const std::string own = impactlab::asset_path("fonts/DejaVuSans.ttf");
    // test_main handed in font_files(); without $IMPACTLAB_FONT the program's own font is the one in use.
    if (std::getenv("IMPACTLAB_FONT") == nullptr) CHECK(plot::font_path() == own);
    CHECK(plot::first_usable_font({"/no/such/font.ttf", own}) == own);
    // A file that is not a font is passed over like a missing one.
    CHECK(plot::first_usable_font({impactlab::asset_path("icons/impactlab-64.png"), own}) == own);
    CHECK_THROWS_WITH_AS(plot::first_usable_font({"/no/such/font.ttf"}),
                         "impactlab::plot: no usable TrueType font found; tried: /no/such/font.ttf", std::runtime_error);
    CHECK_THROWS_WITH_AS(plot::first_usable_font({}), doctest::Contains("no font was handed in"), std::runtime_error);
    // Once a font is loaded, handing in others changes nothing: the glyph cache points into it.
    const std::string before = plot::font_path();
    plot::set_font_files({"/no/such/font.ttf"});
    CHECK(plot::font_path() == before);
}
