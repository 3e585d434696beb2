// libFuzzer: the gzip reader (zlib, streaming with a cap). Every input inflates within the cap or is refused.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "impactlab/identify_data.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    namespace id = impactlab::identify;
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    constexpr std::size_t kCap = std::size_t{1} << 24;
    try {
        if (id::gunzip(bytes, "fuzz.gz", kCap).size() > kCap) __builtin_trap();
    } catch (const id::DataError&) {
    }
    return 0;
}
