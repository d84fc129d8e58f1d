// BVH reading: a tokenizer over the hierarchy (read without recursion), then one pass over the
// frame lines. Every size a file claims is checked against engine/core/limits.h, and frames are
// stored as they are read, so memory follows the file's real size, never its header.
#include "engine/motion/bvh.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include <fast_float/fast_float.h>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/limits.h"
#include "engine/core/math.h"
#include "engine/core/strings.h"

namespace gmg {
namespace {

// A cursor over the hierarchy part: whitespace-separated tokens with line numbers.
class Tokenizer {
 public:
  Tokenizer(const std::string& text, const std::string& name) : text_(text), name_(name) {}

  // A token as a message quotes it: at most 40 bytes, non-printable bytes escaped (a binary file
  // given as a BVH must not print its bytes on the terminal).
  static std::string quote(const std::string& t) {
    return "'" + escape_nonprintable(t.substr(0, 40)) + (t.size() > 40 ? "...'" : "'");
  }

  // Next token, or "" at end of text.
  std::string next() {
    skip_space();
    token_line_ = line_;
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !is_ascii_space(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }

  std::string expect_any(const char* what) {
    std::string t = next();
    if (t.empty()) fail("unexpected end of file, expected " + std::string(what));
    return t;
  }

  void expect(const char* word) {
    const std::string t = next();
    if (t != word) fail("expected '" + std::string(word) + "', found " + (t.empty() ? "end of file" : quote(t)));
  }

  double number(const char* what) {
    const std::string t = expect_any(what);
    double value = 0.0;
    const auto res = std::from_chars(t.data(), t.data() + t.size(), value);
    if (res.ec != std::errc() || res.ptr != t.data() + t.size())
      fail("expected a number for " + std::string(what) + ", found " + quote(t));
    if (!std::isfinite(value)) fail(std::string(what) + " is not finite (" + quote(t) + ")");
    return value;
  }

  // Rest of the current line (after the last token), trimmed.
  std::string rest_of_line() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    return std::string(trim(std::string_view(text_).substr(start, pos_ - start)));
  }

  [[noreturn]] void fail(const std::string& what) const { throw Error(error_at_line(name_, token_line_, what)); }

  std::size_t pos() const { return pos_; }
  long line() const { return line_; }

 private:
  void skip_space() {
    while (pos_ < text_.size() && is_ascii_space(text_[pos_])) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }

  const std::string& text_;
  const std::string& name_;
  std::size_t pos_ = 0;
  long line_ = 1;
  long token_line_ = 1;
};

bool parse_channel(const std::string& t, Channel* out) {
  static const char* names[] = {"Xposition", "Yposition", "Zposition", "Xrotation", "Yrotation", "Zrotation"};
  const std::string lower = ascii_lower(t);
  for (int i = 0; i < 6; ++i) {
    if (lower == ascii_lower(names[i])) {
      *out = static_cast<Channel>(i);
      return true;
    }
  }
  return false;
}

glm::dvec3 read_offset(Tokenizer& tok, const char* x, const char* y, const char* z) {
  glm::dvec3 v;
  v.x = tok.number(x);
  v.y = tok.number(y);
  v.z = tok.number(z);
  return v;
}

// "CHANNELS n name...": up to 6 channels, each at most once.
void read_channels(Tokenizer& tok, Joint& joint) {
  const double count = tok.number("channel count");
  if (count < 0 || count > 6 || count != std::floor(count))
    tok.fail("channel count must be a whole number from 0 to 6, found " + format_number(count));
  bool seen[6] = {false, false, false, false, false, false};
  for (int i = 0; i < static_cast<int>(count); ++i) {
    const std::string name = tok.expect_any("a channel name");
    Channel c;
    if (!parse_channel(name, &c))
      tok.fail("unknown channel " + Tokenizer::quote(name) + " (joint " + Tokenizer::quote(joint.name) + " declares " +
               std::to_string(static_cast<int>(count)) + " channels)");
    if (seen[static_cast<int>(c)])
      tok.fail("channel " + Tokenizer::quote(name) + " listed twice for joint " + Tokenizer::quote(joint.name));
    seen[static_cast<int>(c)] = true;
    joint.channels.push_back(c);
  }
}

// Reads a joint's name line, "{", OFFSET and CHANNELS (the keyword ROOT or JOINT is read) and
// appends it to sk. Returns the token after its header: JOINT, End, } or anything to complain
// about.
std::string begin_joint(Tokenizer& tok, Skeleton& sk, int parent) {
  if (sk.joint_count() >= limits::kMaxJoints)
    tok.fail("more than " + std::to_string(limits::kMaxJoints) + " joints (gmg reads skeletons of up to " +
             std::to_string(limits::kMaxJoints) + ")");
  Joint joint;
  joint.parent = parent;
  joint.name = tok.rest_of_line();
  if (joint.name.empty()) tok.fail("joint without a name");
  if (sk.find(joint.name) >= 0) tok.fail("duplicate joint name " + Tokenizer::quote(joint.name));
  tok.expect("{");
  tok.expect("OFFSET");
  joint.offset = read_offset(tok, "OFFSET x", "OFFSET y", "OFFSET z");
  std::string t = tok.expect_any("CHANNELS, JOINT, End Site or }");
  if (t == "CHANNELS") {
    read_channels(tok, joint);
    t = tok.expect_any("JOINT, End Site or }");
  }
  joint.rotation_order = rotation_order_from_channels(joint.channels);
  sk.joints.push_back(std::move(joint));
  return t;
}

// The joint tree after "ROOT", without recursion: `open` holds the joints whose "}" is still to
// come, innermost last, so a deeply nested file cannot overflow the stack.
void parse_hierarchy(Tokenizer& tok, Skeleton& sk) {
  std::vector<int> open;
  std::string t = begin_joint(tok, sk, -1);
  open.push_back(0);
  while (!open.empty()) {
    const int index = open.back();
    if (t == "}") {
      open.pop_back();
      if (!open.empty()) t = tok.expect_any("'}'");
    } else if (t == "JOINT") {
      if (static_cast<int>(open.size()) >= limits::kMaxHierarchyDepth)
        tok.fail("joints nested more than " + std::to_string(limits::kMaxHierarchyDepth) +
                 " deep (gmg reads hierarchies of up to " + std::to_string(limits::kMaxHierarchyDepth) + " levels)");
      t = begin_joint(tok, sk, index);
      open.push_back(sk.joint_count() - 1);
    } else if (t == "End") {
      tok.expect("Site");
      tok.expect("{");
      tok.expect("OFFSET");
      const glm::dvec3 end = read_offset(tok, "End Site OFFSET x", "End Site OFFSET y", "End Site OFFSET z");
      tok.expect("}");
      sk.joints[index].has_end_site = true;
      sk.joints[index].end_site = end;
      t = tok.expect_any("'}'");
    } else {
      tok.fail("expected JOINT, End Site or '}' in joint " + Tokenizer::quote(sk.joints[index].name) + ", found " +
               Tokenizer::quote(t));
    }
  }
}

// "MOTION", "Frames: N", "Frame Time: t": the declared frame count (checked against the limits
// and the file's size) and the frame rate.
int parse_motion_header(Tokenizer& tok, Motion& m, std::size_t file_size) {
  std::string t = tok.expect_any("MOTION");
  if (t == "ROOT") tok.fail("more than one ROOT: only single-root skeletons are supported");
  if (t != "MOTION") tok.fail("expected MOTION, found " + Tokenizer::quote(t));
  tok.expect("Frames:");
  const double frames = tok.number("Frames");
  if (frames < 0 || frames != std::floor(frames) || frames > limits::kMaxFrames)
    tok.fail("invalid frame count " + format_number(frames) + " (gmg reads 1 to " + std::to_string(limits::kMaxFrames) +
             " frames)");
  const int declared = static_cast<int>(frames);
  if (declared == 0) tok.fail("the file has zero frames");
  // What the frames would take in memory, against what a file of this size may claim
  // (engine/core/limits.h): a lying header is caught here, before anything is allocated.
  const std::uint64_t cell = sizeof(glm::dquat) + 2 * sizeof(glm::dvec3);
  const std::uint64_t need = static_cast<std::uint64_t>(declared) * m.skeleton.joints.size() * cell;
  const std::uint64_t allowed =
      std::max<std::uint64_t>(limits::kMotionFloorBytes, limits::kMotionBytesPerFileByte * file_size);
  if (need > allowed)
    tok.fail("'Frames: " + std::to_string(declared) + "' of " + std::to_string(m.skeleton.joint_count()) +
             " joints would take " + std::to_string(need >> 20) + " MB of memory, more than a file of " +
             std::to_string(file_size) + " bytes can hold (the header is wrong or the file is truncated)");
  tok.expect("Frame");
  tok.expect("Time:");
  const double frame_time = tok.number("Frame Time");
  if (!(frame_time > 0.0)) tok.fail("Frame Time must be positive");
  double fps = 1.0 / frame_time;
  if (std::abs(fps - std::round(fps)) < 1e-3 * fps) fps = std::round(fps);
  if (!(fps >= limits::kMinFps && fps <= limits::kMaxFps))
    tok.fail("Frame Time " + format_number(frame_time) + " s is " + format_number(fps) +
             " frames per second; gmg reads " + format_number(limits::kMinFps) + " to " +
             format_number(limits::kMaxFps) + " fps");
  m.fps = fps;
  tok.rest_of_line();
  return declared;
}

// Parses one frame line of exactly `expected` numbers into values. Returns false on a blank line.
bool parse_frame_line(const char* begin, const char* end, std::vector<double>& values, int expected,
                      const std::string& name, long line) {
  values.clear();
  const char* p = begin;
  while (true) {
    while (p < end && (*p == ' ' || *p == '\t' || *p == '\r')) ++p;
    if (p >= end) break;
    const char* token_end = p;
    while (token_end < end && *token_end != ' ' && *token_end != '\t' && *token_end != '\r') ++token_end;
    // fast_float: correctly rounded as std::from_chars (the same doubles), and faster on frame lines,
    // most of reading a long BVH (docs/decisions.md, "Implementation choices").
    double v = 0.0;
    const auto res = fast_float::from_chars(p, token_end, v);
    if (res.ec != std::errc() || res.ptr != token_end)
      throw Error(error_at_line(name, line,
                                "value " + std::to_string(values.size() + 1) +
                                    " is not a number: " + Tokenizer::quote(std::string(p, token_end))));
    if (!std::isfinite(v))
      throw Error(error_at_line(name, line,
                                "value " + std::to_string(values.size() + 1) +
                                    " is not finite: " + Tokenizer::quote(std::string(p, token_end))));
    values.push_back(v);
    p = token_end;
  }
  if (values.empty()) return false;
  if (static_cast<int>(values.size()) != expected)
    throw Error(error_at_line(name, line,
                              "frame has " + std::to_string(values.size()) + " values but the hierarchy declares " +
                                  std::to_string(expected) + " channels"));
  return true;
}

// Appends one frame of channel values to m (its joints' rotations, translations, Euler angles).
void append_frame(Motion& m, const std::vector<double>& values) {
  int c = 0;
  for (const Joint& joint : m.skeleton.joints) {
    glm::dvec3 translation = joint.offset;
    glm::dvec3 angles(0.0);
    int rot_index = 0;
    for (Channel ch : joint.channels) {
      const double v = values[c++];
      if (is_position_channel(ch)) {
        translation[channel_axis(ch)] = v;
      } else {
        angles[rot_index++] = v * kDegToRad;
      }
    }
    m.rotations.push_back(euler_to_quat(angles, joint.rotation_order));
    m.euler_hints.push_back(angles);
    m.translations.push_back(translation);
  }
  ++m.frame_count;
}

// The frame lines from byte `pos` (line `line`) on: exactly `declared` non-blank lines.
void read_frames(const std::string& text, std::size_t pos, long line, int declared, Motion& m,
                 const std::string& name) {
  const int channels = m.skeleton.channel_count();
  if (channels == 0) throw Error(error_at_line(name, line - 1, "the hierarchy declares no channels"));
  // Room for the frames the rest of the file can hold (a value takes at least two bytes, a digit
  // and a separator), so a lying header allocates nothing beyond the file's size.
  const std::size_t possible = (text.size() - std::min(pos, text.size())) / (2 * static_cast<std::size_t>(channels));
  const std::size_t frames = std::min(static_cast<std::size_t>(declared), possible + 1);
  const std::size_t cells = frames * m.skeleton.joints.size();
  m.rotations.reserve(cells);
  m.translations.reserve(cells);
  m.euler_hints.reserve(cells);
  std::vector<double> values;
  values.reserve(static_cast<std::size_t>(channels));
  while (pos < text.size()) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string::npos) eol = text.size();
    if (parse_frame_line(text.data() + pos, text.data() + eol, values, channels, name, line)) {
      if (m.frame_count >= declared)
        throw Error(error_at_line(name, line,
                                  "more frame lines than the " + std::to_string(declared) + " declared by 'Frames:'"));
      append_frame(m, values);
    }
    pos = eol + 1;
    ++line;
  }
  if (m.frame_count < declared)
    throw Error(error_at_line(name, line - 1,
                              "truncated: 'Frames:' declares " + std::to_string(declared) +
                                  " frames but the file has " + std::to_string(m.frame_count)));
}

}  // namespace

Motion bvh_parse(const std::string& text, const std::string& name) {
  return naming_memory_errors(name, "reading the motion", [&] {
    Tokenizer tok(text, name);
    const std::string t(strip_utf8_bom(tok.next()));
    if (t != "HIERARCHY")
      tok.fail(t.empty() ? "empty file, expected HIERARCHY"
                         : "not a BVH file: expected HIERARCHY, found " + Tokenizer::quote(t));
    tok.expect("ROOT");
    Motion m;
    parse_hierarchy(tok, m.skeleton);
    const int declared = parse_motion_header(tok, m, text.size());
    std::size_t pos = tok.pos();
    if (pos < text.size() && text[pos] == '\n') ++pos;
    read_frames(text, pos, tok.line() + 1, declared, m, name);
    return m;
  });
}

Motion bvh_read(const std::string& path) { return bvh_parse(read_file_bytes(path), path); }

}  // namespace gmg
