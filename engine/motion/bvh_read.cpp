// BVH reading: a tokenizer over the hierarchy, then one pass over the frame lines.
#include "engine/motion/bvh.h"

#include <charconv>
#include <cmath>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/math.h"
#include "engine/core/strings.h"

namespace gmg {
namespace {

// A cursor over the hierarchy part: whitespace-separated tokens with line numbers.
class Tokenizer {
 public:
  Tokenizer(const std::string& text, const std::string& name) : text_(text), name_(name) {}

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
    if (t != word) fail("expected '" + std::string(word) + "', found " + (t.empty() ? "end of file" : "'" + t + "'"));
  }

  double number(const char* what) {
    const std::string t = expect_any(what);
    double value = 0.0;
    const auto res = std::from_chars(t.data(), t.data() + t.size(), value);
    if (res.ec != std::errc() || res.ptr != t.data() + t.size())
      fail("expected a number for " + std::string(what) + ", found '" + t + "'");
    if (!std::isfinite(value)) fail(std::string(what) + " is not finite ('" + t + "')");
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

void parse_joint(Tokenizer& tok, Skeleton& sk, int parent) {
  Joint joint;
  joint.parent = parent;
  joint.name = tok.rest_of_line();
  if (joint.name.empty()) tok.fail("joint without a name");
  if (sk.find(joint.name) >= 0) tok.fail("duplicate joint name '" + joint.name + "'");
  tok.expect("{");
  tok.expect("OFFSET");
  joint.offset.x = tok.number("OFFSET x");
  joint.offset.y = tok.number("OFFSET y");
  joint.offset.z = tok.number("OFFSET z");
  std::string t = tok.expect_any("CHANNELS, JOINT, End Site or }");
  if (t == "CHANNELS") {
    const double count = tok.number("channel count");
    if (count < 0 || count > 6 || count != std::floor(count))
      tok.fail("channel count must be a whole number from 0 to 6, found " + std::to_string(count));
    bool seen[6] = {false, false, false, false, false, false};
    for (int i = 0; i < static_cast<int>(count); ++i) {
      const std::string name = tok.expect_any("a channel name");
      Channel c;
      if (!parse_channel(name, &c))
        tok.fail("unknown channel '" + name + "' (joint '" + joint.name + "' declares " +
                 std::to_string(static_cast<int>(count)) + " channels)");
      if (seen[static_cast<int>(c)]) tok.fail("channel '" + name + "' listed twice for joint '" + joint.name + "'");
      seen[static_cast<int>(c)] = true;
      joint.channels.push_back(c);
    }
    t = tok.expect_any("JOINT, End Site or }");
  }
  joint.rotation_order = rotation_order_from_channels(joint.channels);
  const int index = sk.joint_count();
  sk.joints.push_back(joint);
  while (t != "}") {
    if (t == "JOINT") {
      parse_joint(tok, sk, index);
    } else if (t == "End") {
      tok.expect("Site");
      tok.expect("{");
      tok.expect("OFFSET");
      glm::dvec3 end;
      end.x = tok.number("End Site OFFSET x");
      end.y = tok.number("End Site OFFSET y");
      end.z = tok.number("End Site OFFSET z");
      tok.expect("}");
      sk.joints[index].has_end_site = true;
      sk.joints[index].end_site = end;
    } else {
      tok.fail("expected JOINT, End Site or '}' in joint '" + joint.name + "', found '" + t + "'");
    }
    t = tok.expect_any("'}'");
  }
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
    double v = 0.0;
    const auto res = std::from_chars(p, token_end, v);
    if (res.ec != std::errc() || res.ptr != token_end)
      throw Error(error_at_line(
          name, line,
          "value " + std::to_string(values.size() + 1) + " is not a number: '" + std::string(p, token_end) + "'"));
    if (!std::isfinite(v))
      throw Error(error_at_line(
          name, line,
          "value " + std::to_string(values.size() + 1) + " is not finite: '" + std::string(p, token_end) + "'"));
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

}  // namespace

Motion bvh_parse(const std::string& text, const std::string& name) {
  Tokenizer tok(text, name);
  std::string t = tok.next();
  t = std::string(strip_utf8_bom(t));
  if (t != "HIERARCHY")
    tok.fail(t.empty() ? "empty file, expected HIERARCHY"
                       : "not a BVH file: expected HIERARCHY, found '" + t.substr(0, 40) + "'");
  tok.expect("ROOT");
  Motion m;
  parse_joint(tok, m.skeleton, -1);
  t = tok.expect_any("MOTION");
  if (t == "ROOT") tok.fail("more than one ROOT: only single-root skeletons are supported");
  if (t != "MOTION") tok.fail("expected MOTION, found '" + t + "'");
  tok.expect("Frames:");
  const double frames = tok.number("Frames");
  if (frames < 0 || frames != std::floor(frames) || frames > 1e8)
    tok.fail("invalid frame count " + std::to_string(frames));
  m.frame_count = static_cast<int>(frames);
  if (m.frame_count == 0) tok.fail("the file has zero frames");
  tok.expect("Frame");
  tok.expect("Time:");
  const double frame_time = tok.number("Frame Time");
  if (!(frame_time > 0.0)) tok.fail("Frame Time must be positive");
  double fps = 1.0 / frame_time;
  if (std::abs(fps - std::round(fps)) < 1e-3 * fps) fps = std::round(fps);
  m.fps = fps;
  tok.rest_of_line();

  const Skeleton& sk = m.skeleton;
  const int joints = sk.joint_count();
  const int channels = sk.channel_count();
  m.rotations.resize(static_cast<std::size_t>(m.frame_count) * joints);
  m.translations.resize(static_cast<std::size_t>(m.frame_count) * joints);
  m.euler_hints.resize(static_cast<std::size_t>(m.frame_count) * joints);

  std::size_t pos = tok.pos();
  if (pos < text.size() && text[pos] == '\n') ++pos;
  long line = tok.line() + 1;
  std::vector<double> values;
  values.reserve(static_cast<std::size_t>(channels));
  int frame = 0;
  while (pos < text.size()) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string::npos) eol = text.size();
    if (parse_frame_line(text.data() + pos, text.data() + eol, values, channels, name, line)) {
      if (frame >= m.frame_count)
        throw Error(error_at_line(
            name, line, "more frame lines than the " + std::to_string(m.frame_count) + " declared by 'Frames:'"));
      int c = 0;
      for (int j = 0; j < joints; ++j) {
        const Joint& joint = sk.joints[j];
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
        m.rotations[m.index(frame, j)] = euler_to_quat(angles, joint.rotation_order);
        m.euler_hints[m.index(frame, j)] = angles;
        m.translations[m.index(frame, j)] = translation;
      }
      ++frame;
    }
    pos = eol + 1;
    ++line;
  }
  if (frame < m.frame_count)
    throw Error(error_at_line(name, line - 1,
                              "truncated: 'Frames:' declares " + std::to_string(m.frame_count) +
                                  " frames but the file has " + std::to_string(frame)));
  return m;
}

Motion bvh_read(const std::string& path) { return bvh_parse(read_file_bytes(path), path); }

}  // namespace gmg
