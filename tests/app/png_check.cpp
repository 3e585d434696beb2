// Checks that a screenshot is a real picture, not a blank or single-colour frame: it must load, have the
// expected size (if given), show many distinct colours and a spread of brightness.
// usage: impactlab_png_check FILE.png [WIDTH HEIGHT]; exit 0 if the picture passes, 1 if not, 2 on usage.
#include <stb_image.h>   // libstb exports the implementation

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <unordered_set>

int main(int argc, char** argv) {
    if (argc != 2 && argc != 4) {
        std::fprintf(stderr, "usage: impactlab_png_check FILE.png [WIDTH HEIGHT]\n");
        return 2;
    }
    int w = 0, h = 0, n = 0;
    unsigned char* px = stbi_load(argv[1], &w, &h, &n, 3);
    if (!px) {
        std::fprintf(stderr, "png_check: %s: cannot load (%s)\n", argv[1], stbi_failure_reason());
        return 1;
    }
    int rc = 0;
    if (argc == 4 && (w != std::atoi(argv[2]) || h != std::atoi(argv[3]))) {
        std::fprintf(stderr, "png_check: %s is %dx%d, expected %sx%s\n", argv[1], w, h, argv[2], argv[3]);
        rc = 1;
    }
    std::unordered_set<unsigned> colours;
    double sum = 0, sum2 = 0;
    const long total = static_cast<long>(w) * h;
    for (long i = 0; i < total; ++i) {
        const unsigned char* p = px + 3 * i;
        colours.insert((unsigned(p[0]) << 16) | (unsigned(p[1]) << 8) | p[2]);
        const double y = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
        sum += y;
        sum2 += y * y;
    }
    stbi_image_free(px);
    const double mean = sum / static_cast<double>(total);
    const double sd = std::sqrt(std::max(0.0, sum2 / static_cast<double>(total) - mean * mean));
    std::printf("png_check: %s: %dx%d, %zu distinct colours, luminance mean %.1f, sd %.1f\n", argv[1], w, h,
                colours.size(), mean, sd);
    if (colours.size() < 256) {
        std::fprintf(stderr, "png_check: too few colours: the frame looks blank\n");
        rc = 1;
    }
    if (sd < 8.0) {
        std::fprintf(stderr, "png_check: almost no contrast: the frame looks blank\n");
        rc = 1;
    }
    return rc;
}
