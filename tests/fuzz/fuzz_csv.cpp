// libFuzzer: the measured-data CSV loader. Every input either loads or is refused with a DataError; the first
// byte picks the options (column mapping, sample rate, scales) so those paths are fuzzed too.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "impactlab/identify_data.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    namespace id = impactlab::identify;
    if (size == 0) return 0;
    id::LoadOptions o;
    const std::uint8_t mode = data[0];
    if (mode & 1) o.min_samples = 2;
    if (mode & 2) o.columns.x = "2";
    if (mode & 4) o.rate = 1000.0, o.columns.t = "";
    if (mode & 8) o.x_scale = 1e-3;
    if (mode & 16) o.columns.u = "u";
    if (mode & 32) o.row_begin = 1, o.row_end = 40;
    const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
    try {
        const id::MeasuredData d = id::parse_measured(text, "fuzz.csv", o);
        for (double x : d.x)
            if (!(x == x)) __builtin_trap();   // a loaded record never holds NaN
    } catch (const id::DataError&) {
    }
    return 0;
}
