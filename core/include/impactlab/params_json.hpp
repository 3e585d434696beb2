// Parameter sets as JSON (nlohmann-json): load, validate, save. Every error names the file and the key.
#pragma once

#include <string>

#include "impactlab/params.hpp"

namespace impactlab {

// Reads a parameter file; throws ParamError("FILE: ...") for a parse error (with line and column), a
// missing key, an unknown key, a wrong type, a non-finite number or a value out of range.
Params load_params(const std::string& path);
Params params_from_json_text(const std::string& text, const std::string& source);
std::string params_to_json_text(const Params& p);
void save_params(const Params& p, const std::string& path);
// A version name ("A1H") or a JSON file path (ends in .json): what every --model flag accepts.
Params resolve_model(const std::string& name_or_path);

}  // namespace impactlab
