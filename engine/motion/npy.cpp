// NumPy .npy parsing and writing.
#include "engine/motion/npy.h"

#include <cmath>
#include <cstring>
#include <limits>

#include "engine/core/error.h"
#include "engine/core/limits.h"

namespace gmg {
namespace {

constexpr char kMagic[] = "\x93NUMPY";
constexpr std::size_t kMagicSize = 6;
constexpr std::uint64_t kMaxBytes = limits::kMaxNpyBytes;

struct Dtype {
  const char* name;
  std::size_t size;
  bool is_float;
};
constexpr Dtype kDtypes[] = {{"<f8", 8, true}, {"<f4", 4, true}, {"<i8", 8, false}, {"<i4", 4, false}};

std::string describe_dtype_problem(const std::string& d) {
  if (!d.empty() && d[0] == '>') return "big-endian dtype '" + d + "' is not supported (save it little-endian)";
  if (d.size() > 1 && (d[1] == 'U' || d[1] == 'S')) return "holds text (dtype '" + d + "'), not numbers";
  if (d.size() > 1 && d[1] == 'O') return "holds Python objects (dtype '" + d + "'), not numbers";
  return "dtype '" + d + "' is not supported (expected float64 '<f8', float32 '<f4', int64 '<i8' or int32 '<i4')";
}

// The header of an .npy file: the Python dict literal numpy writes,
// {'descr': '<f8', 'fortran_order': False, 'shape': (3, 4), }
class HeaderParser {
 public:
  HeaderParser(std::string_view text, const std::string& name) : s_(text), name_(name) {}

  void parse(std::string& descr, bool& fortran, std::vector<std::uint64_t>& shape) {
    bool seen_descr = false, seen_fortran = false, seen_shape = false;
    expect('{');
    while (!eat('}')) {
      const std::string key = string_literal("a key");
      expect(':');
      if (key == "descr") {
        skip_space();
        if (pos_ < s_.size() && s_[pos_] == '[') fail("a structured dtype is not supported (expected plain numbers)");
        descr = string_literal("the dtype");
        mark(seen_descr, key);
      } else if (key == "fortran_order") {
        fortran = boolean();
        mark(seen_fortran, key);
      } else if (key == "shape") {
        shape = tuple();
        mark(seen_shape, key);
      } else {
        fail("unexpected key '" + key + "' (expected 'descr', 'fortran_order', 'shape')");
      }
      if (!eat(',')) {
        expect('}');
        break;
      }
    }
    for (; pos_ < s_.size(); ++pos_)
      if (s_[pos_] != ' ' && s_[pos_] != '\n') fail("unexpected text after the header's closing '}'");
    if (!seen_descr || !seen_fortran || !seen_shape)
      fail(std::string("the header lacks '") +
           (!seen_descr     ? "descr"
            : !seen_fortran ? "fortran_order"
                            : "shape") +
           "'");
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw Error(name_ + ": malformed .npy header: " + what); }

  void mark(bool& seen, const std::string& key) const {
    if (seen) fail("key '" + key + "' given twice");
    seen = true;
  }

  void skip_space() {
    while (pos_ < s_.size() && (s_[pos_] == ' ' || s_[pos_] == '\n' || s_[pos_] == '\t')) ++pos_;
  }

  bool eat(char c) {
    skip_space();
    if (pos_ < s_.size() && s_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }

  void expect(char c) {
    if (!eat(c)) fail(std::string("expected '") + c + "'");
  }

  std::string string_literal(const char* what) {
    skip_space();
    if (pos_ >= s_.size() || (s_[pos_] != '\'' && s_[pos_] != '"')) fail(std::string("expected ") + what);
    const char quote = s_[pos_++];
    const std::size_t end = s_.find(quote, pos_);
    if (end == std::string_view::npos) fail("unterminated string");
    std::string out(s_.substr(pos_, end - pos_));
    pos_ = end + 1;
    return out;
  }

  bool boolean() {
    skip_space();
    for (const auto& [word, value] : {std::pair<std::string_view, bool>{"True", true}, {"False", false}}) {
      if (s_.substr(pos_, word.size()) == word) {
        pos_ += word.size();
        return value;
      }
    }
    fail("'fortran_order' must be True or False");
  }

  std::vector<std::uint64_t> tuple() {
    std::vector<std::uint64_t> out;
    expect('(');
    while (!eat(')')) {
      skip_space();
      std::uint64_t v = 0;
      const std::size_t start = pos_;
      while (pos_ < s_.size() && s_[pos_] >= '0' && s_[pos_] <= '9') {
        if (v > kMaxBytes) fail("a dimension of the shape is too large");
        v = v * 10 + static_cast<std::uint64_t>(s_[pos_++] - '0');
      }
      if (pos_ == start) fail("the shape must be a tuple of whole numbers");
      out.push_back(v);
      if (!eat(',')) {
        expect(')');
        break;
      }
    }
    return out;
  }

  std::string_view s_;
  const std::string& name_;
  std::size_t pos_ = 0;
};

std::string shape_text(const std::vector<std::uint64_t>& shape) {
  std::string s = "(";
  for (std::size_t i = 0; i < shape.size(); ++i) s += (i ? ", " : "") + std::to_string(shape[i]);
  return s + (shape.size() == 1 ? ",)" : ")");
}

std::uint64_t read_le(const unsigned char* p, std::size_t n) {
  std::uint64_t v = 0;
  for (std::size_t i = n; i-- > 0;) v = (v << 8) | p[i];
  return v;
}

double decode(const unsigned char* p, const Dtype& t) {
  const std::uint64_t bits = read_le(p, t.size);
  if (t.is_float && t.size == 8) {
    double d;
    std::memcpy(&d, &bits, sizeof d);
    return d;
  }
  if (t.is_float) {
    const auto b32 = static_cast<std::uint32_t>(bits);
    float f;
    std::memcpy(&f, &b32, sizeof f);
    return f;
  }
  if (t.size == 8) return static_cast<double>(static_cast<std::int64_t>(bits));
  return static_cast<double>(static_cast<std::int32_t>(static_cast<std::uint32_t>(bits)));
}

void append_le(std::string& out, std::uint64_t v, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) out += static_cast<char>((v >> (8 * i)) & 0xFF);
}

// numpy's format 1.0 preamble: magic, version, header length, then the dict padded with spaces
// and a newline so the data starts at a multiple of 64 bytes.
std::string npy_preamble(const std::string& descr, const std::vector<std::uint64_t>& shape) {
  std::string dict = "{'descr': '" + descr + "', 'fortran_order': False, 'shape': " + shape_text(shape) + ", }";
  const std::size_t unpadded = kMagicSize + 4 + dict.size() + 1;
  dict.append((64 - unpadded % 64) % 64, ' ');
  dict += '\n';
  std::string out(kMagic, kMagicSize);
  out += '\x01';
  out += '\x00';
  append_le(out, dict.size(), 2);
  return out + dict;
}

// The parsed preamble of an .npy file: its header and where its data starts.
struct NpyHeader {
  std::string dtype;
  bool fortran = false;
  std::vector<std::uint64_t> shape;
  std::size_t data_offset = 0;
};

NpyHeader parse_preamble(std::string_view bytes, const std::string& name) {
  if (bytes.size() < kMagicSize + 4 || bytes.substr(0, kMagicSize) != std::string_view(kMagic, kMagicSize))
    throw Error(name + ": not a .npy array (no \\x93NUMPY magic)");
  const auto* u = reinterpret_cast<const unsigned char*>(bytes.data());
  const int major = u[6];
  if (major < 1 || major > 3)
    throw Error(name + ": .npy format version " + std::to_string(major) + "." + std::to_string(u[7]) +
                " is not supported (expected 1, 2 or 3)");
  const std::size_t length_size = major == 1 ? 2 : 4;
  if (bytes.size() < 8 + length_size) throw Error(name + ": truncated .npy header");
  const std::uint64_t header_size = read_le(u + 8, length_size);
  const std::uint64_t data_offset = 8 + length_size + header_size;
  if (data_offset > bytes.size())
    throw Error(name + ": truncated .npy header (it declares " + std::to_string(header_size) + " bytes, the file has " +
                std::to_string(bytes.size() - 8 - length_size) + ")");
  NpyHeader h;
  HeaderParser(bytes.substr(8 + length_size, header_size), name).parse(h.dtype, h.fortran, h.shape);
  h.data_offset = static_cast<std::size_t>(data_offset);
  return h;
}

// The element count of a shape, refused when the data would exceed kMaxBytes at `item_size` bytes each.
std::uint64_t element_count(const std::vector<std::uint64_t>& shape, std::size_t item_size, const std::string& name) {
  std::uint64_t count = 1;
  for (std::uint64_t d : shape) {
    if (d != 0 && count > kMaxBytes / d) throw Error(name + ": shape " + shape_text(shape) + " is too large");
    count *= d;
  }
  if (count > kMaxBytes / item_size) throw Error(name + ": shape " + shape_text(shape) + " is too large");
  return count;
}

void check_data_size(const NpyHeader& h, std::uint64_t need, std::size_t have, const std::string& name) {
  if (have != need)
    throw Error(name + ": shape " + shape_text(h.shape) + " of " + h.dtype + " needs " + std::to_string(need) +
                " bytes of data, the array has " + std::to_string(have) + (have < need ? " (truncated)" : ""));
}

}  // namespace

NpyArray npy_parse(std::string_view bytes, const std::string& name) {
  const NpyHeader h = parse_preamble(bytes, name);
  NpyArray a;
  a.dtype = h.dtype;
  a.shape = h.shape;
  const Dtype* type = nullptr;
  for (const Dtype& t : kDtypes)
    if (a.dtype == t.name) type = &t;
  if (!type) throw Error(name + ": " + describe_dtype_problem(a.dtype));
  if (h.fortran && a.shape.size() > 1)
    throw Error(name + ": Fortran-order arrays are not supported (save with numpy.ascontiguousarray)");
  const std::uint64_t count = element_count(a.shape, type->size, name);
  check_data_size(h, count * type->size, bytes.size() - h.data_offset, name);
  a.values.resize(static_cast<std::size_t>(count));
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data()) + h.data_offset;
  for (std::size_t i = 0; i < a.values.size(); ++i, p += type->size) a.values[i] = decode(p, *type);
  return a;
}

std::string npy_parse_text(std::string_view bytes, const std::string& name) {
  const NpyHeader h = parse_preamble(bytes, name);
  std::uint64_t width = 0;
  const bool is_text = h.dtype.size() > 2 && h.dtype[0] == '<' && h.dtype[1] == 'U';
  for (std::size_t i = 2; is_text && i < h.dtype.size(); ++i) {
    if (h.dtype[i] < '0' || h.dtype[i] > '9' || width > 1000000) {
      width = 0;
      break;
    }
    width = width * 10 + static_cast<std::uint64_t>(h.dtype[i] - '0');
  }
  if (width == 0) throw Error(name + ": expected text (dtype '<U<length>'), found dtype '" + h.dtype + "'");
  if (element_count(h.shape, 4, name) != 1)
    throw Error(name + ": expected one text, found shape " + shape_text(h.shape));
  check_data_size(h, 4 * width, bytes.size() - h.data_offset, name);
  std::string out;
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data()) + h.data_offset;
  for (std::uint64_t i = 0; i < width; ++i, p += 4) {
    const std::uint64_t c = read_le(p, 4);
    if (c == 0) break;  // numpy pads a shorter text with NULs
    if (c > 0x7E || c < 0x20)
      throw Error(name + ": the text holds a character gmg does not keep (only printable ASCII)");
    out += static_cast<char>(c);
  }
  return out;
}

std::string npy_format(const std::string& dtype, const std::vector<std::uint64_t>& shape,
                       const std::vector<double>& values) {
  std::uint64_t count = 1;
  for (std::uint64_t d : shape) count *= d;
  if (count != values.size())
    throw Error("npy_format: shape " + shape_text(shape) + " does not hold " + std::to_string(values.size()) +
                " values");
  std::string out = npy_preamble(dtype, shape);
  if (dtype == "<f8") {
    for (double v : values) {
      std::uint64_t bits;
      std::memcpy(&bits, &v, sizeof bits);
      append_le(out, bits, 8);
    }
  } else if (dtype == "<f4") {
    for (double v : values) {
      const auto f = static_cast<float>(v);
      if (std::isfinite(v) && !std::isfinite(f)) throw Error("npy_format: " + std::to_string(v) + " exceeds float32");
      std::uint32_t bits;
      std::memcpy(&bits, &f, sizeof bits);
      append_le(out, bits, 4);
    }
  } else if (dtype == "<i4") {
    for (double v : values) {
      if (v != std::trunc(v) || v < std::numeric_limits<std::int32_t>::min() ||
          v > std::numeric_limits<std::int32_t>::max())
        throw Error("npy_format: " + std::to_string(v) + " is not a 32-bit integer");
      append_le(out, static_cast<std::uint32_t>(static_cast<std::int32_t>(v)), 4);
    }
  } else {
    throw Error("npy_format: cannot write dtype '" + dtype + "'");
  }
  return out;
}

std::string npy_format_text(const std::string& text) {
  std::string out = npy_preamble("<U" + std::to_string(text.size()), {});
  for (char c : text) append_le(out, static_cast<unsigned char>(c), 4);
  return out;
}

}  // namespace gmg
