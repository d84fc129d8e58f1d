#include "engine/core/json.h"

#include "engine/core/error.h"
#include "engine/core/files.h"

namespace gmg {
namespace {

template <typename Json>
Json parse_as(const std::string& text, const std::string& name) {
  try {
    return Json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // e.what() is "[json.exception.parse_error.101] parse error at line 1, column 3: ..."; keep
    // the reason after the last ": ".
    std::string why = e.what();
    const std::size_t colon = why.rfind(": ");
    if (colon != std::string::npos) why = why.substr(colon + 2);
    throw Error(error_at_byte(name, static_cast<long long>(e.byte), "invalid JSON (" + why + ")"));
  } catch (const nlohmann::json::out_of_range&) {
    throw Error(name + ": invalid JSON: a number is out of range (beyond double precision)");
  } catch (const nlohmann::json::exception&) {
    throw Error(name + ": invalid JSON");
  }
}

}  // namespace

nlohmann::json parse_json_text(const std::string& text, const std::string& name) {
  return parse_as<nlohmann::json>(text, name);
}

nlohmann::json read_json_file(const std::string& path) { return parse_as<nlohmann::json>(read_file_bytes(path), path); }

nlohmann::ordered_json read_ordered_json_file(const std::string& path) {
  return parse_as<nlohmann::ordered_json>(read_file_bytes(path), path);
}

std::string json_dump(const nlohmann::ordered_json& j, int indent) {
  return j.dump(indent, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

std::string json_dump(const nlohmann::json& j, int indent) {
  return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace gmg
