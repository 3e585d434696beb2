// JSON text that never throws on bytes: nlohmann's dump() refuses a string that is not UTF-8 (a file name in
// Latin-1 read from the disk), so every string, keys too, is carried with such bytes written as \xNN first.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "impactlab/input_file.hpp"

namespace impactlab {

// Every string of `j` (values and keys) with its non-UTF-8 bytes as \xNN (utf8_escaped).
inline void escape_json_strings(nlohmann::json& j) {
    if (j.is_string()) {
        j = utf8_escaped(j.get_ref<const std::string&>());
    } else if (j.is_array()) {
        for (auto& e : j) escape_json_strings(e);
    } else if (j.is_object()) {
        nlohmann::json fixed = nlohmann::json::object();
        for (auto& [k, v] : j.items()) {
            escape_json_strings(v);
            fixed[utf8_escaped(k)] = std::move(v);
        }
        j = std::move(fixed);
    }
}

// j.dump(indent) after escape_json_strings: the text of any JSON value, never an exception.
inline std::string json_dump(nlohmann::json j, int indent) {
    escape_json_strings(j);
    return j.dump(indent);
}

}  // namespace impactlab
