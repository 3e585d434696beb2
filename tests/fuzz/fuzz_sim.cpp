// libFuzzer: a short simulation of a fuzzed parameter set. Whatever validation accepts runs 0.3 s at a fuzzed
// omega to a finite state, or ends in SimulationStalled: never a hang (a 2 s wall budget), never NaN.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "impactlab/drive.hpp"
#include "impactlab/params.hpp"
#include "impactlab/params_json.hpp"
#include "impactlab/simulator.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace impactlab;
    if (size < 2) return 0;
    const double omega = 25.0 * data[0] / 255.0;   // the paper's range
    const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
    Params p;
    try {
        p = params_from_json_text(text, "fuzz.json");
    } catch (const ParamError&) {
        return 0;
    }
    Tolerances tol;
    tol.max_wall_s = 2.0;
    Simulator sim(tol);
    const Drive drive(omega);
    State s;
    s.x = 0.001;
    Simulator::make_consistent(p, drive, s);
    try {
        sim.advance(p, drive, s, 0.3);
    } catch (const SimulationStalled&) {
        return 0;
    }
    if (!std::isfinite(s.x) || !std::isfinite(s.v)) __builtin_trap();
    return 0;
}
