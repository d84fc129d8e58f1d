#include "engine/motion/capture_facts.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/core/error.h"

namespace gmg {

std::vector<int> chain_to(const Skeleton& s, int j) {
  std::vector<int> chain;
  for (int k = j; k >= 0; k = s.joints[static_cast<std::size_t>(k)].parent) chain.push_back(k);
  std::reverse(chain.begin(), chain.end());
  return chain;
}

void chain_world(const Motion& m, int f, const std::vector<int>& chain, std::vector<glm::dquat>& rot,
                 std::vector<glm::dvec3>& pos) {
  rot.resize(chain.size());
  pos.resize(chain.size());
  for (std::size_t k = 0; k < chain.size(); ++k) {
    const glm::dquat& q = m.rotation(f, chain[k]);
    const glm::dvec3& t = m.translation(f, chain[k]);
    if (k == 0) {
      rot[k] = q;
      pos[k] = t;
    } else {
      pos[k] = pos[k - 1] + rot[k - 1] * t;
      rot[k] = rot[k - 1] * q;
    }
  }
}

namespace {

// A pass over the motion gives back each stretch of this many frames behind it (a long reference
// spilled to disk or served from its file stays resident only where it is read).
constexpr int kReleaseStride = 1 << 16;

void release_behind(const Motion& m, int f) {
  if (f > 0 && f % kReleaseStride == 0) motion_release_frames(m, f - kReleaseStride, kReleaseStride);
}

// Fills gaps and removes runs of `value` shorter than kContactMinRun.
void drop_short_runs(std::vector<char>& flags, char value) {
  for (std::size_t i = 0; i < flags.size();) {
    std::size_t j = i;
    while (j < flags.size() && flags[j] == flags[i]) ++j;
    if (flags[i] == value && j - i < static_cast<std::size_t>(kContactMinRun))
      std::fill(flags.begin() + static_cast<std::ptrdiff_t>(i), flags.begin() + static_cast<std::ptrdiff_t>(j),
                static_cast<char>(!value));
    i = j;
  }
}

}  // namespace

void foot_contacts(const std::vector<glm::dvec3>& p, const CaptureRuns& runs, double leg_length, double fps,
                   std::vector<char>& out_contact, std::vector<char>& out_low) {
  const int frames = static_cast<int>(p.size());
  out_contact.assign(p.size(), 0);
  out_low.assign(p.size(), 0);
  for (int first = 0; first < frames;) {
    int last = first;  // the capture run [first, last]
    while (last + 1 < frames && runs.continues(last)) ++last;
    double lowest = std::numeric_limits<double>::infinity();
    for (int f = first; f <= last; ++f) lowest = std::min(lowest, p[static_cast<std::size_t>(f)].y);
    for (int f = first; f <= last; ++f) {
      const int g = f > first ? f - 1 : std::min(f + 1, last);
      const double speed = glm::length(p[static_cast<std::size_t>(f)] - p[static_cast<std::size_t>(g)]) * fps;
      out_low[static_cast<std::size_t>(f)] = p[static_cast<std::size_t>(f)].y <= lowest + kContactHeight * leg_length;
      out_contact[static_cast<std::size_t>(f)] =
          speed < kContactSpeed * leg_length && out_low[static_cast<std::size_t>(f)];
    }
    first = last + 1;
  }
  drop_short_runs(out_contact, 0);  // fill short gaps first: a planted foot's noise
  drop_short_runs(out_contact, 1);
}

namespace {

// The largest horizontal root step inside capture runs.
double largest_root_step(const Motion& m, const CaptureRuns& runs) {
  double largest = 0.0;
  for (int f = 1; f < m.frame_count; ++f) {
    release_behind(m, f);
    if (!runs.continues(f - 1)) continue;
    const glm::dvec3 d = m.translation(f, 0) - m.translation(f - 1, 0);
    largest = std::max(largest, std::hypot(d.x, d.z));
  }
  return largest;
}

// One leg's flags (contact, low) into `flags`, and its hinge.
glm::dvec3 leg_facts(const Motion& m, const CaptureRuns& runs, const Leg& leg, int l,
                     std::vector<std::uint8_t>& flags) {
  const std::vector<int> chain = chain_to(m.skeleton, leg.ankle);
  const std::size_t n = chain.size();
  std::vector<glm::dquat> wr;
  std::vector<glm::dvec3> wp;
  std::vector<glm::dvec3> p(static_cast<std::size_t>(m.frame_count));
  glm::dvec3 hinge(0.0);
  for (int f = 0; f < m.frame_count; ++f) {
    release_behind(m, f);
    chain_world(m, f, chain, wr, wp);
    p[static_cast<std::size_t>(f)] = wp.back();
    // The knee plane's normal in the thigh's frame, where the knee is clearly bent (17 degrees or
    // more): a hinge, nearly the same axis in every such frame.
    const glm::dvec3 normal = glm::cross(wp[n - 3] - wp[n - 2], wp[n - 1] - wp[n - 2]);
    const double length = glm::length(wp[n - 3] - wp[n - 2]) * glm::length(wp[n - 1] - wp[n - 2]);
    if (length > 0.0 && glm::length(normal) / length >= 0.3)
      hinge += glm::conjugate(wr[n - 3]) * (normal / glm::length(normal));
  }
  std::vector<char> contact, low;
  foot_contacts(p, runs, leg.length, m.fps, contact, low);
  for (std::size_t f = 0; f < flags.size(); ++f)
    flags[f] =
        static_cast<std::uint8_t>(flags[f] | (contact[f] ? foot_contact_bit(l) : 0) | (low[f] ? foot_low_bit(l) : 0));
  return glm::length(hinge) > 0.0 ? glm::normalize(hinge) : glm::dvec3(0.0);
}

}  // namespace

CaptureFacts capture_facts(const Motion& m, const CaptureRuns& runs) {
  if (runs.frame_count() != m.frame_count) throw Error("capture facts: the capture runs do not cover the motion");
  CaptureFacts out;
  out.known = true;
  out.largest_root_step = largest_root_step(m, runs);
  motion_release_pages(m);
  out.root_lo = glm::dvec3(std::numeric_limits<double>::infinity());
  out.root_hi = glm::dvec3(-std::numeric_limits<double>::infinity());
  for (int f = 0; f < m.frame_count; ++f) {
    release_behind(m, f);
    out.root_lo = glm::min(out.root_lo, m.translation(f, 0));
    out.root_hi = glm::max(out.root_hi, m.translation(f, 0));
  }
  const std::vector<Leg> legs = find_legs(m.skeleton);
  if (legs.empty()) return out;
  std::vector<std::uint8_t> flags(static_cast<std::size_t>(m.frame_count), 0);
  for (std::size_t l = 0; l < legs.size(); ++l)
    out.knee_hinges.push_back(leg_facts(m, runs, legs[l], static_cast<int>(l), flags));
  motion_release_pages(m);
  out.foot_flags = std::move(flags);
  return out;
}

}  // namespace gmg
