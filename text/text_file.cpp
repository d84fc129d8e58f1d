#include "text/text_file.h"

#include <cstdint>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/strings.h"

namespace gmg::text::detail {

namespace {

void append_utf8(std::string& out, std::uint32_t cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

std::string decode_utf16(const std::string& bytes, std::size_t begin, bool little_endian, const std::string& path) {
  if ((bytes.size() - begin) % 2 != 0)
    throw Error(path + ": UTF-16 text with an odd number of bytes (truncated file?)");
  auto unit = [&](std::size_t i) -> std::uint32_t {
    auto b0 = static_cast<unsigned char>(bytes[i]);
    auto b1 = static_cast<unsigned char>(bytes[i + 1]);
    return little_endian ? (b0 | (b1 << 8)) : ((b0 << 8) | b1);
  };
  std::string out;
  out.reserve((bytes.size() - begin) / 2);
  for (std::size_t i = begin; i < bytes.size(); i += 2) {
    std::uint32_t u = unit(i);
    if (u >= 0xD800 && u <= 0xDBFF) {  // high surrogate: needs a low one
      if (i + 3 < bytes.size()) {
        std::uint32_t lo = unit(i + 2);
        if (lo >= 0xDC00 && lo <= 0xDFFF) {
          append_utf8(out, 0x10000 + ((u - 0xD800) << 10) + (lo - 0xDC00));
          i += 2;
          continue;
        }
      }
      append_utf8(out, 0xFFFD);
    } else if (u >= 0xDC00 && u <= 0xDFFF) {  // lone low surrogate
      append_utf8(out, 0xFFFD);
    } else {
      append_utf8(out, u);
    }
  }
  return out;
}

}  // namespace

std::string decode_to_utf8(const std::string& bytes, const std::string& path) {
  auto byte = [&](std::size_t i) { return static_cast<unsigned char>(bytes[i]); };
  if (has_utf8_bom(bytes)) return std::string(strip_utf8_bom(bytes));
  if (bytes.size() >= 2 && byte(0) == 0xFF && byte(1) == 0xFE) return decode_utf16(bytes, 2, true, path);
  if (bytes.size() >= 2 && byte(0) == 0xFE && byte(1) == 0xFF) return decode_utf16(bytes, 2, false, path);
  // UTF-16 without a byte-order mark: the first character is ASCII, so one byte is NUL.
  if (bytes.size() >= 2 && byte(0) != 0 && byte(0) < 0x80 && byte(1) == 0) return decode_utf16(bytes, 0, true, path);
  if (bytes.size() >= 2 && byte(0) == 0 && byte(1) != 0 && byte(1) < 0x80) return decode_utf16(bytes, 0, false, path);
  return bytes;
}

std::string read_text_file(const std::string& path) { return decode_to_utf8(read_file_bytes(path), path); }

}  // namespace gmg::text::detail
