// JSON in and out, with the engine's error wording ("path: what").
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace gmg {

// Parses the whole file as JSON. Throws gmg::Error naming the file: the reader's errors
// (engine/core/files.h), "path: byte N: invalid JSON (reason)" for a syntax error, and
// "path: byte N: invalid JSON (the number 1e309 is out of range for a double)" for a literal
// beyond double range (nlohmann would otherwise throw its own out_of_range exception with no
// file in it). N counts the bytes read up to and including the offending one (nlohmann's
// convention: the 1-based position of the token's last byte).
nlohmann::json read_json_file(const std::string& path);
nlohmann::ordered_json read_ordered_json_file(const std::string& path);

// Same for text already in memory; `name` labels errors.
nlohmann::json parse_json_text(const std::string& text, const std::string& name);
nlohmann::ordered_json parse_ordered_json_text(const std::string& text, const std::string& name);

// Serialises without ever throwing on bytes: invalid UTF-8 in a string is replaced by U+FFFD.
// indent < 0 gives one line.
std::string json_dump(const nlohmann::ordered_json& j, int indent = 2);
std::string json_dump(const nlohmann::json& j, int indent = 2);

// Writes j indented by 2 with a final newline, atomically (json_dump: invalid UTF-8 in a string,
// e.g. a Latin-1 file name, is replaced, never thrown on). What `gmg reenact --report` and the
// Python module's reports write.
void write_json_file(const std::string& path, const nlohmann::ordered_json& j);

}  // namespace gmg
