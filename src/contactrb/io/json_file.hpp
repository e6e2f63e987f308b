#pragma once
// JSON files (solution.json, run summaries) through nlohmann::json (Debian
// nlohmann-json3-dev); callers include <nlohmann/json.hpp> to build the value.
#include <nlohmann/json_fwd.hpp>
#include <string>

namespace contactrb::io {

// Writes `value` (pretty-printed with `indent` spaces, compact when indent < 0) through a
// temporary file renamed at the end. Non-finite numbers are written as null (JSON has no
// nan or inf). Throws contactrb::Error naming the path when it cannot be written.
void write_json(const nlohmann::json& value, const std::string& path, int indent = 2);

// Reads a JSON file. Throws contactrb::Error naming the path for a missing file or a parse
// error (with the parser's message).
nlohmann::json read_json(const std::string& path);

}  // namespace contactrb::io
