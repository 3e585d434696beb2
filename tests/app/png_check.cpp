// Checks that a screenshot is a real picture, not a blank or single-colour frame: it must load, have the
// expected size (if given), show many distinct colours and a spread of brightness. Each --region X Y W H
// (pixels from the top left) must pass the same test on its own, with at least 64 colours: a panel whose
// drawing went missing leaves a flat area even when the rest of the window is busy. A --busy X Y W H region
// (a picture that fills its area, such as the rig) must also have 1000 colours and no colour on more than
// half of it: the labels alone over a missing drawing pass the weaker test.
// usage: impactlab_png_check FILE.png [WIDTH HEIGHT] [--region|--busy X Y W H]...; exit 0 if the picture
// passes, 1 if not, 2 on usage.
#include <stb_image.h>   // libstb exports the implementation

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <algorithm>
#include <unordered_map>
#include <vector>

namespace {
struct Region {
    long x, y, w, h;
    bool busy = false;
};

// Distinct colours and luminance spread of the pixels of r in a w-wide RGB image; prints them and returns
// whether they pass.
bool real_picture(const unsigned char* px, long w, const Region& r, std::size_t min_colours, const char* what) {
    std::unordered_map<unsigned, long> colours;
    double sum = 0, sum2 = 0;
    for (long y = r.y; y < r.y + r.h; ++y)
        for (long x = r.x; x < r.x + r.w; ++x) {
            const unsigned char* p = px + 3 * (y * w + x);
            ++colours[(unsigned(p[0]) << 16) | (unsigned(p[1]) << 8) | p[2]];
            const double l = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
            sum += l;
            sum2 += l * l;
        }
    const double n = static_cast<double>(r.w * r.h);
    const double mean = sum / n;
    const double sd = std::sqrt(std::max(0.0, sum2 / n - mean * mean));
    long top = 0;
    for (const auto& [c, k] : colours) top = std::max(top, k);
    const double share = static_cast<double>(top) / n;
    std::printf("png_check: %s %ldx%ld at (%ld, %ld): %zu distinct colours, luminance mean %.1f, sd %.1f, commonest "
                "colour on %.0f%%\n", what, r.w, r.h, r.x, r.y, colours.size(), mean, sd, 100 * share);
    bool ok = true;
    if (r.busy && (colours.size() < 1000 || share > 0.5)) {
        std::fprintf(stderr, "png_check: %s: not a full picture (fewer than 1000 colours or one colour on over half)\n", what);
        ok = false;
    }
    if (colours.size() < min_colours) {
        std::fprintf(stderr, "png_check: %s: too few colours: it looks blank\n", what);
        ok = false;
    }
    if (sd < 8.0) {
        std::fprintf(stderr, "png_check: %s: almost no contrast: it looks blank\n", what);
        ok = false;
    }
    return ok;
}
}  // namespace

int main(int argc, char** argv) {
    std::vector<const char*> pos;
    std::vector<Region> regions;
    for (int i = 1; i < argc; ++i) {
        const bool busy = std::strcmp(argv[i], "--busy") == 0;
        if (busy || std::strcmp(argv[i], "--region") == 0) {
            if (i + 4 >= argc) {
                std::fprintf(stderr, "png_check: %s needs X Y W H\n", argv[i]);
                return 2;
            }
            Region r{std::atol(argv[i + 1]), std::atol(argv[i + 2]), std::atol(argv[i + 3]), std::atol(argv[i + 4]), busy};
            if (r.x < 0 || r.y < 0 || r.w <= 0 || r.h <= 0) {
                std::fprintf(stderr, "png_check: --region %s %s %s %s: not a rectangle\n", argv[i + 1], argv[i + 2],
                             argv[i + 3], argv[i + 4]);
                return 2;
            }
            regions.push_back(r);
            i += 4;
        } else {
            pos.push_back(argv[i]);
        }
    }
    if (pos.size() != 1 && pos.size() != 3) {
        std::fprintf(stderr, "usage: impactlab_png_check FILE.png [WIDTH HEIGHT] [--region|--busy X Y W H]...\n");
        return 2;
    }
    int w = 0, h = 0, n = 0;
    unsigned char* px = stbi_load(pos[0], &w, &h, &n, 3);
    if (!px) {
        std::fprintf(stderr, "png_check: %s: cannot load (%s)\n", pos[0], stbi_failure_reason());
        return 1;
    }
    int rc = 0;
    if (pos.size() == 3 && (w != std::atoi(pos[1]) || h != std::atoi(pos[2]))) {
        std::fprintf(stderr, "png_check: %s is %dx%d, expected %sx%s\n", pos[0], w, h, pos[1], pos[2]);
        rc = 1;
    }
    if (!real_picture(px, w, Region{0, 0, w, h}, 256, pos[0])) rc = 1;
    for (const Region& r : regions) {
        if (r.x + r.w > w || r.y + r.h > h) {
            std::fprintf(stderr, "png_check: region %ldx%ld at (%ld, %ld) is outside the %dx%d picture\n", r.w, r.h, r.x,
                         r.y, w, h);
            rc = 1;
            continue;
        }
        if (!real_picture(px, w, r, 64, r.busy ? "busy region" : "region")) rc = 1;
    }
    stbi_image_free(px);
    return rc;
}
