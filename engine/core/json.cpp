#include "engine/core/json.h"

#include "engine/core/error.h"
#include "engine/core/files.h"

namespace gmg {
namespace {

// nlohmann reports the byte of a syntax error (parse_error::byte) but throws a number out of
// range (1e309) as out_of_range, without a position. Parsing the text again with this handler,
// which builds nothing and stops at the first error, recovers the position and the token.
class FirstError : public nlohmann::json_sax<nlohmann::json> {
 public:
  std::size_t byte = 0;
  std::string token;

  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override { return true; }
  bool key(string_t&) override { return true; }
  bool end_object() override { return true; }
  bool start_array(std::size_t) override { return true; }
  bool end_array() override { return true; }
  bool parse_error(std::size_t position, const std::string& last_token, const nlohmann::detail::exception&) override {
    byte = position;
    token = last_token;
    return false;
  }
};

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
    FirstError where;
    nlohmann::json::sax_parse(text, &where);
    std::string number = where.token.substr(0, 40);
    if (where.token.size() > 40) number += "...";
    throw Error(error_at_byte(name, static_cast<long long>(where.byte),
                              "invalid JSON (the number " + number + " is out of range for a double)"));
  } catch (const nlohmann::json::exception&) {
    throw Error(name + ": invalid JSON");
  }
}

}  // namespace

nlohmann::json parse_json_text(const std::string& text, const std::string& name) {
  return parse_as<nlohmann::json>(text, name);
}

nlohmann::ordered_json parse_ordered_json_text(const std::string& text, const std::string& name) {
  return parse_as<nlohmann::ordered_json>(text, name);
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

void write_json_file(const std::string& path, const nlohmann::ordered_json& j) {
  const std::string text = json_dump(j, 2) + "\n";
  write_file_atomically(path, [&](std::ostream& os) { os << text; });
}

}  // namespace gmg
