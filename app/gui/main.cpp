// impactlab-gui: the interactive visualiser. Exit codes: 0 success, 1 runtime failure, 2 usage error.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "window/app.hpp"
#include "window/bench.hpp"
#include "window/options.hpp"

int main(int argc, char** argv) {
    using namespace impactlab::gui;
    Options opt;
    try {
        opt = parse_options(std::vector<std::string>(argv + 1, argv + argc));
        if (!opt.help) check_files(opt);
    } catch (const OptionsError& e) {
        std::fprintf(stderr, "impactlab-gui: error: %s\n", e.what());
        return 2;
    }
    if (opt.help) {
        std::printf("%s", usage_text());
        return 0;
    }
    try {
        if (opt.bench_ring || opt.bench_sim) {
            if (opt.bench_ring) bench_ring();
            if (opt.bench_sim) bench_sim();
            if (!opt.bench_plot) return 0;
        }
        App app(opt);
        return app.run();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "impactlab-gui: error: %s\n", e.what());
        return 1;
    }
}
