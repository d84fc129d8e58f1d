#include "engine/pipeline/control.h"

#include <algorithm>
#include <cmath>

#include "engine/assemble/inertialize.h"
#include "engine/assemble/layers.h"
#include "engine/core/error.h"
#include "engine/core/strings.h"
#include "engine/motion/rotation.h"
#include "engine/motion/up_axis.h"

namespace gmg {
namespace {

double number_in(const std::string& field, const std::string& text, const std::string& option) {
  const std::optional<double> v = parse_number(field);
  if (!v) throw Error(option + " '" + text + "': '" + field + "' is not a number");
  return *v;
}

std::string seconds(double s) { return format_number(s) + " s"; }

// a < b: the two stretches [a0, a1) and [b0, b1) share a frame.
bool overlap(int a0, int a1, int b0, int b1) { return a0 < b1 && b0 < a1; }

// One end of a splice: frames `first`, first + step, ... (`count` of them) of `cur` pulled to the
// base's frame `first`, in pose and in velocity (the step to the next frame, both taken the same
// way), the pull decaying as a critically damped spring.
void spring_end(Motion& cur, const Motion& base, int first, int step, int count, double y,
                const std::vector<char>& mask) {
  const int joints = cur.joint_count();
  const int next = count > 1 ? first + step : -1;
  for (int j = 0; j < joints; ++j) {
    if (!mask.empty() && !mask[static_cast<std::size_t>(j)]) continue;
    const glm::dquat target = base.rotation(first, j), now = cur.rotation(first, j);
    glm::dvec3 x = quat_to_expmap(target * glm::inverse(now)), v(0.0);
    if (next >= 0)
      v = quat_to_expmap(base.rotation(next, j) * glm::inverse(target)) -
          quat_to_expmap(cur.rotation(next, j) * glm::inverse(now));
    const glm::dvec3 tt = base.translation(first, j), tn = cur.translation(first, j);
    glm::dvec3 xt = tt - tn, vt(0.0);
    if (next >= 0) vt = (base.translation(next, j) - tt) - (cur.translation(next, j) - tn);
    for (int i = 0, f = first; i < count; ++i, f += step) {
      const std::size_t k = cur.index(f, j);
      cur.rotations[k] = glm::normalize(expmap_to_quat(x) * cur.rotations[k]);
      cur.translations[k] += xt;
      spring_decay(x, v, y, 1.0);
      spring_decay(xt, vt, y, 1.0);
    }
  }
}

}  // namespace

PinRequest parse_pin(const std::string& text, const std::string& option, bool by_word) {
  const std::size_t eq = text.find('=');
  const std::size_t colon = text.rfind(':');
  const std::string form = by_word ? "N=FROM:TO" : "T=FROM:TO or T=CLIP@FROM:TO";
  if (eq == std::string::npos || colon == std::string::npos || colon < eq)
    throw Error(option + " '" + text + "': expected " + form);
  PinRequest p;
  const std::string head = text.substr(0, eq);
  std::string span = text.substr(eq + 1);
  if (!by_word) {
    const std::size_t at = span.rfind('@');
    if (at != std::string::npos) {
      p.clip = span.substr(0, at);
      span = span.substr(at + 1);
      if (p.clip.empty()) throw Error(option + " '" + text + "': no clip name before '@'");
    }
  }
  const std::size_t c = span.rfind(':');
  if (c == std::string::npos) throw Error(option + " '" + text + "': expected " + form);
  p.from = number_in(span.substr(0, c), text, option);
  p.to = number_in(span.substr(c + 1), text, option);
  if (by_word) {
    const double n = number_in(head, text, option);
    if (n < 0 || n != std::floor(n) || n > 1e9)
      throw Error(option + " '" + text + "': the word number must be a whole number from 0");
    p.word = static_cast<int>(n);
  } else {
    p.at = number_in(head, text, option);
  }
  if (p.at < 0 || p.from < 0 || !(p.to > p.from))
    throw Error(option + " '" + text + "': times must be 0 or more, with FROM before TO");
  return p;
}

TimeRange parse_range(const std::string& text, const std::string& option) {
  const std::size_t c = text.find(':');
  if (c == std::string::npos) throw Error(option + " '" + text + "': expected FROM:TO (seconds)");
  const double from = number_in(text.substr(0, c), text, option), to = number_in(text.substr(c + 1), text, option);
  if (from < 0 || !(to > from)) throw Error(option + " '" + text + "': FROM must be 0 or more and before TO");
  return {from, to};
}

std::vector<Anchor> pin_anchors(const MotionGraph& g, const std::vector<PinRequest>& pins, int total_frames,
                                const std::string& speech, const std::string& graph_name) {
  const double fps = g.motion.fps;
  std::vector<Anchor> out;
  std::vector<std::string> names;
  for (const ClipInfo& c : g.clips) names.push_back(c.name);
  for (const PinRequest& p : pins) {
    const std::string what = "the pin at " + seconds(p.at) + " (" + (p.clip.empty() ? "" : p.clip + "@") +
                             format_number(p.from) + ":" + format_number(p.to) + ")";
    int first = 0, count = g.frame_count();
    if (!p.clip.empty()) {
      const auto c = std::find(names.begin(), names.end(), p.clip);
      if (c == names.end())
        throw Error(graph_name + ": " + what + " names no clip of the graph" + did_you_mean(p.clip, names));
      first = g.clips[static_cast<std::size_t>(c - names.begin())].first_frame;
      count = g.clips[static_cast<std::size_t>(c - names.begin())].frame_count;
    }
    Anchor a;
    a.kind = Fixed::Pin;
    a.start = static_cast<int>(std::lround(p.at * fps));
    a.length = static_cast<int>(std::lround((p.to - p.from) * fps));
    a.source = first + static_cast<int>(std::lround(p.from * fps));
    if (a.length < 1) throw Error(graph_name + ": " + what + " is shorter than one frame");
    if (a.start + a.length > total_frames)
      throw Error(speech + ": " + what + " ends after the audio (" + seconds(total_frames / fps) + ")");
    if (a.source + a.length > first + count)
      throw Error(graph_name + ": " + what + " lies outside " + (p.clip.empty() ? "the graph's " : "the clip's ") +
                  seconds(count / fps));
    for (int f = a.source; f + 1 < a.source + a.length; ++f)
      if (g.node(f).kinds & kBreakNode)
        throw Error(graph_name + ": " + what + " runs across a break of the reference (graph frame " +
                    std::to_string(f) + ": a clip's end or a capture jump)");
    out.push_back(a);
  }
  std::stable_sort(out.begin(), out.end(), [](const Anchor& a, const Anchor& b) { return a.start < b.start; });
  for (std::size_t i = 1; i < out.size(); ++i)
    if (out[i].start < out[i - 1].start + out[i - 1].length)
      throw Error(speech + ": the pins at " + seconds(out[i - 1].start / fps) + " and " + seconds(out[i].start / fps) +
                  " overlap");
  return out;
}

std::vector<Anchor> with_pins(const std::vector<Anchor>& rests, const std::vector<Anchor>& pins) {
  std::vector<Anchor> out = pins;
  for (const Anchor& r : rests) {
    bool free = true;
    for (const Anchor& p : pins) free = free && !overlap(r.start, r.start + r.length, p.start, p.start + p.length);
    if (free) out.push_back(r);
  }
  std::stable_sort(out.begin(), out.end(), [](const Anchor& a, const Anchor& b) { return a.start < b.start; });
  return out;
}

void resolve_word_pins(std::vector<PinRequest>& pins, const std::vector<double>& word_starts,
                       const std::string& transcript) {
  for (PinRequest& p : pins) {
    if (p.word < 0) continue;
    if (word_starts.empty()) throw Error("--pin-word needs a transcript with words (" + transcript + ": none)");
    if (static_cast<std::size_t>(p.word) >= word_starts.size())
      throw Error(transcript + ": --pin-word " + std::to_string(p.word) + " is past its last word (" +
                  std::to_string(word_starts.size() - 1) + ", counting from 0)");
    p.at = word_starts[static_cast<std::size_t>(p.word)];
  }
}

void splice_motion(Motion& base, const Motion& insert, int a, int b, double halflife, const std::vector<char>& mask) {
  if (b <= a) return;
  Motion cur = base;
  for (int f = a; f < b; ++f)
    for (int j = 0; j < base.joint_count(); ++j)
      if (mask.empty() || mask[static_cast<std::size_t>(j)]) {
        cur.rotations[cur.index(f, j)] = insert.rotation(f - a, j);
        cur.translations[cur.index(f, j)] = insert.translation(f - a, j);
      }
  const double y = spring_damping(halflife);
  if (a > 0) spring_end(cur, base, a, 1, b - a, y, mask);
  if (b < base.frame_count) spring_end(cur, base, b - 1, -1, b - a, y, mask);
  cur.euler_hints.clear();
  base = std::move(cur);
}

void apply_pins(Motion& out, const MotionGraph& g, const std::vector<Anchor>& pins, int settle) {
  // A spring from rest is under 1 % of its offset after 4.79 half-lives (engine/assemble/inertialize.h).
  const double halflife = std::max(0.5, settle / 4.79);
  for (const Anchor& p : pins) {
    // The reference's whole body, turned and moved on the floor so that its root starts where and
    // facing where the output's does: every joint relative to the root, in the root's heading, is
    // the reference's, and the feet move as they did in the capture.
    Motion ref = motion_slice(g.motion, p.source, p.source + p.length);
    const glm::dquat turn = heading_of(out.rotation(p.start, 0)) * glm::inverse(heading_of(ref.rotation(0, 0)));
    const glm::dvec3 from = ref.translation(0, 0), to = out.translation(p.start, 0);
    for (int f = 0; f < ref.frame_count; ++f) {
      const std::size_t k = ref.index(f, 0);
      ref.rotations[k] = glm::normalize(turn * ref.rotations[k]);
      glm::dvec3 t = turn * (ref.translations[k] - from);
      t.x += to.x;
      t.z += to.z;
      t.y = ref.translations[k].y;
      ref.translations[k] = t;
    }
    splice_motion(out, ref, p.start, p.start + p.length, halflife, {});
  }
}

std::vector<std::pair<int, int>> range_frames(const std::vector<TimeRange>& ranges, double fps, int total_frames,
                                              const std::string& name) {
  std::vector<std::pair<int, int>> out;
  for (const TimeRange& r : ranges) {
    const int a = static_cast<int>(std::lround(r.first * fps)), b = static_cast<int>(std::lround(r.second * fps));
    if (b <= a)
      throw Error(name + ": the range " + format_number(r.first) + ":" + format_number(r.second) + " holds no frame");
    if (b > total_frames)
      throw Error(name + ": the range " + format_number(r.first) + ":" + format_number(r.second) +
                  " ends after the output (" + seconds(total_frames / fps) + ")");
    out.emplace_back(a, b);
  }
  std::sort(out.begin(), out.end());
  std::vector<std::pair<int, int>> merged;
  for (const auto& r : out) {
    if (!merged.empty() && r.first <= merged.back().second)
      merged.back().second = std::max(merged.back().second, r.second);
    else
      merged.push_back(r);
  }
  return merged;
}

void check_keep(const Control& control, const MotionGraph& g, int total_frames) {
  const Motion& k = *control.keep;
  std::string why;
  if (!skeletons_match(k.skeleton, g.motion.skeleton, &why))
    throw Error(control.keep_name + ": not in the graph's skeleton (" + why + ")");
  if (std::abs(k.fps - g.motion.fps) > 1e-6 * g.motion.fps)
    throw Error(control.keep_name + ": " + format_number(k.fps) + " frames per second, the graph has " +
                format_number(g.motion.fps));
  if (k.frame_count != total_frames)
    throw Error(control.keep_name + ": " + std::to_string(k.frame_count) + " frames, the audio needs " +
                std::to_string(total_frames) + " (--keep takes an earlier output for the same audio)");
  if (control.ranges.empty()) throw Error(control.keep_name + ": --keep needs at least one --range FROM:TO");
}

void apply_keep(Motion& out, const Motion& keep, const std::vector<std::pair<int, int>>& frames, const MotionGraph& g,
                const BodyLayers& layers, double spine_follow, double halflife) {
  Motion fresh = out, kept = keep;
  motion_to_y_up(fresh, g.up);
  motion_to_y_up(kept, g.up);
  Motion joined = kept;
  for (const auto& [a, b] : frames) {
    Motion piece = motion_slice(fresh, a, b);
    if (layers.layered()) piece = join_layers(piece, motion_slice(kept, a, b), layers, spine_follow);
    splice_motion(joined, piece, a, b, halflife, {});
  }
  motion_from_y_up(joined, g.up);
  // Outside the ranges: keep's own values, not their round trip through Y-up.
  std::vector<char> inside(static_cast<std::size_t>(keep.frame_count), 0);
  for (const auto& [a, b] : frames) std::fill(inside.begin() + a, inside.begin() + b, 1);
  const bool hinted = !keep.euler_hints.empty();
  if (hinted) joined.euler_hints.assign(keep.euler_hints.size(), glm::dvec3(0.0));
  std::vector<glm::dvec3> previous(static_cast<std::size_t>(keep.joint_count()), glm::dvec3(0.0));
  for (int f = 0; f < keep.frame_count; ++f) {
    if (!inside[static_cast<std::size_t>(f)]) motion_copy_frame(keep, f, joined, f);
    if (!hinted) continue;
    // The BVH writer takes each kept frame's angles from its hints, as the file gave them; the
    // new frames get the angles nearest the frame before, as it would choose them.
    for (int j = 0; j < keep.joint_count(); ++j) {
      const std::size_t k = joined.index(f, j);
      previous[static_cast<std::size_t>(j)] =
          inside[static_cast<std::size_t>(f)]
              ? quat_to_euler_near(joined.rotations[k],
                                   keep.skeleton.joints[static_cast<std::size_t>(j)].rotation_order,
                                   previous[static_cast<std::size_t>(j)])
              : keep.euler_hints[k];
      joined.euler_hints[k] = previous[static_cast<std::size_t>(j)];
    }
  }
  out = std::move(joined);
}

void apply_keep_face(SmplxBody& face, const SmplxBody& keep, const std::vector<std::pair<int, int>>& frames,
                     double halflife) {
  const int dims = keep.expression_dims;
  if (!face.has_face() || !keep.has_face() || face.expression_dims != dims ||
      face.expressions.size() != keep.expressions.size())
    return;
  const int n = static_cast<int>(keep.expressions.size() / static_cast<std::size_t>(dims));
  std::vector<double> out = keep.expressions;
  const double y = spring_damping(halflife);
  auto at = [&](const std::vector<double>& v, int f, int d) { return v[static_cast<std::size_t>(f * dims + d)]; };
  for (const auto& [a, b] : frames)
    for (int d = 0; d < dims; ++d) {
      std::vector<double> fresh(static_cast<std::size_t>(b - a));
      for (int f = a; f < b; ++f) fresh[static_cast<std::size_t>(f - a)] = at(face.expressions, f, d);
      // The two ends' offsets, as splice_motion's springs (one axis of a glm::dvec3 carries them).
      for (int end = 0; end < 2; ++end) {
        const bool start = end == 0;
        if (start ? a == 0 : b == n) continue;
        const int first = start ? a : b - 1, step = start ? 1 : -1, next = first + step;
        const double now = fresh[static_cast<std::size_t>(first - a)];
        glm::dvec3 x(at(keep.expressions, first, d) - now, 0, 0), v(0.0);
        if (b - a > 1)
          v.x = (at(keep.expressions, next, d) - at(keep.expressions, first, d)) -
                (fresh[static_cast<std::size_t>(next - a)] - now);
        for (int i = 0, f = first; i < b - a; ++i, f += step) {
          fresh[static_cast<std::size_t>(f - a)] += x.x;
          spring_decay(x, v, y, 1.0);
        }
      }
      for (int f = a; f < b; ++f) out[static_cast<std::size_t>(f * dims + d)] = fresh[static_cast<std::size_t>(f - a)];
    }
  face.expressions = std::move(out);
}

void control_report(nlohmann::ordered_json& report, const std::vector<std::pair<int, int>>& planned, int total_frames,
                    bool keeping, const std::vector<Anchor>& pins) {
  if (!keeping && pins.empty()) return;
  std::vector<std::pair<int, int>> fresh = keeping ? planned : std::vector<std::pair<int, int>>{{0, total_frames}};
  nlohmann::ordered_json kept = nlohmann::ordered_json::array(), plan = nlohmann::ordered_json::array(),
                         pinned = nlohmann::ordered_json::array();
  int at = 0;
  for (const auto& [a, b] : fresh) {
    if (a > at) kept.push_back({at, a});
    plan.push_back({a, b});
    at = b;
  }
  if (at < total_frames && keeping) kept.push_back({at, total_frames});
  for (const Anchor& p : pins)
    pinned.push_back({{"start_frame", p.start}, {"frames", p.length}, {"graph_frame", p.source}});
  report["control"] = {{"kept", kept}, {"planned", plan}, {"pinned", pinned}};
  if (!report.contains("subsequences")) return;
  for (auto& s : report["subsequences"]) {
    const int a = s["start_frame"].get<int>(), b = a + s["target_length"].get<int>();
    bool touched = false;
    for (const auto& [x, y] : fresh) touched = touched || overlap(a, b, x, y);
    s["control"] = s.contains("fixed") && s["fixed"] == "pin" ? "pinned" : (touched ? "planned" : "kept");
  }
}

}  // namespace gmg
