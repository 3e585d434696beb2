// libFuzzer: the JSON parameter loader. Every input is a valid parameter set or a ParamError naming the file.
#include <cstddef>
#include <cstdint>
#include <string>

#include "impactlab/params.hpp"
#include "impactlab/params_json.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const impactlab::Params p = impactlab::params_from_json_text(text, "fuzz.json");
        impactlab::validate(p, "again");   // what loads passes its own validation
        (void)impactlab::params_to_json_text(p);
    } catch (const impactlab::ParamError&) {
    }
    return 0;
}
