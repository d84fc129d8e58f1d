// Names of enum values, for modes that users choose by name (config keys, report fields).
//
// Each enum keeps one table of {value, name}; parsing and printing both go through it, so a
// mode's spelling exists once. Parsing is exact (names are lower-case snake_case).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace gmg {

template <typename E>
struct EnumName {
  E value;
  const char* name;
};

template <typename E, std::size_t N>
const char* enum_name(const EnumName<E> (&table)[N], E value) {
  for (const EnumName<E>& e : table)
    if (e.value == value) return e.name;
  return "?";
}

template <typename E, std::size_t N>
std::optional<E> enum_from_name(const EnumName<E> (&table)[N], std::string_view name) {
  for (const EnumName<E>& e : table)
    if (name == e.name) return e.value;
  return std::nullopt;
}

// "a, b or c": the choices, for error messages.
template <typename E, std::size_t N>
std::string enum_choices(const EnumName<E> (&table)[N]) {
  std::string out;
  for (std::size_t i = 0; i < N; ++i) {
    if (i > 0) out += i + 1 == N ? " or " : ", ";
    out += table[i].name;
  }
  return out;
}

}  // namespace gmg
