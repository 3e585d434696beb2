// bench_odeint: the CF diagrams of A1C and A1H written with Boost.Odeint (rosenbrock4, its controller and dense
// output; bench_odeint_backend.cpp), timed against impactlab's run_cf_sweep in the same process.
#include "peer_common.hpp"

int main(int argc, char** argv) {
    // Default rtol: the loosest of 1e-6, 3e-7, 1e-7, 3e-8, ... at which the settled period-1 section points agree
    // with impactlab's to about 1e-6 m (every run measures and prints it; the numbers are in bench/README.md):
    // 1e-7 for the stock rosenbrock4 (order 2 here, see bench_odeint_backend.cpp), 1e-6 with --fixed-gamma4.
    constexpr double kDefaultRtol = 1e-7, kDefaultRtolFixed = 1e-6;
    peer::Options o =
        peer::parse_options(argc, argv, "bench_odeint", kDefaultRtol, "--fixed-gamma4",
                            "--fixed-gamma4 rosenbrock4 with the sign of its gamma_4 coefficient corrected (Boost 1.74 "
                            "has +0.0362, RODAS -0.0362: order 2 on non-autonomous systems); default rtol 1e-6");
    if (o.extra && !o.rtol_given) o.rtol = kDefaultRtolFixed;
    try {
        return peer::peer_main(o, o.extra ? "odeint-fix" : "odeint",
                               o.extra ? "Boost.Odeint rosenbrock4 (gamma_4 sign corrected) + rosenbrock4_controller + "
                                         "dense output, events on the dense output, steps landing on the sections"
                                       : "Boost.Odeint rosenbrock4 (stock Boost 1.74) + rosenbrock4_controller + dense "
                                         "output, events on the dense output, steps landing on the sections",
                               [&o](peer::Model& M, const peer::CfGrid& grid, const peer::Accuracy& acc) {
                                   return peer::run_cf_odeint(M, grid, acc, o.extra);
                               });
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_odeint: %s\n", e.what());
        return 1;
    }
}
