#include "engine/assemble/channels.h"

#include <cmath>

#include "engine/assemble/blend.h"
#include "engine/assemble/inertialize.h"
#include "engine/assemble/resample.h"
#include "engine/assemble/timeline.h"
#include "engine/core/error.h"

namespace gmg {
namespace {

// The channels in groups of three, so the spring of inertialize.h (on 3-vectors) decays them.
using Values = std::vector<glm::dvec3>;

// Reads the channels at fractional source times: the logic of transitions.cpp's SourceReader for
// translations, so a channel is read exactly where and how a translation is.
class ChannelReader {
 public:
  ChannelReader(const std::vector<double>& values, int dims, const CaptureRuns& runs)
      : values_(values), dims_(dims), groups_((dims + 2) / 3), runs_(runs) {}

  int groups() const { return groups_; }

  bool readable(double t, int from) const { return runs_.readable(t, from); }

  void sample(double t, Values& out) const {
    const int f = static_cast<int>(std::floor(t));
    const double a = t - f;
    const int g = runs_.next_frame(f, a);
    out.resize(static_cast<std::size_t>(groups_));
    for (int k = 0; k < groups_; ++k) out[static_cast<std::size_t>(k)] = (1.0 - a) * at(f, k) + a * at(g, k);
  }

  void velocity(double t, double rate, const Values& at_t, Values& out) const {
    out.assign(static_cast<std::size_t>(groups_), glm::dvec3(0.0));
    double partner = 0.0, sign = 1.0;
    if (!runs_.velocity_partner(t, rate, partner, sign)) return;
    Values other;
    sample(partner, other);
    for (std::size_t k = 0; k < out.size(); ++k) out[k] = sign * (at_t[k] - other[k]);
  }

 private:
  glm::dvec3 at(int frame, int group) const {
    glm::dvec3 v(0.0);
    const std::size_t row = static_cast<std::size_t>(frame) * static_cast<std::size_t>(dims_);
    for (int c = 0; c < 3 && 3 * group + c < dims_; ++c) v[c] = values_[row + static_cast<std::size_t>(3 * group + c)];
    return v;
  }

  const std::vector<double>& values_;
  int dims_, groups_;
  const CaptureRuns& runs_;
};

void check_values(const std::vector<double>& values, int dims, std::size_t frames) {
  if (dims < 1 || values.size() != frames * static_cast<std::size_t>(dims))
    throw Error("assemble: the channels do not cover the source frames");
}

void append_group_values(const Values& v, int dims, std::vector<double>& out) {
  for (int c = 0; c < dims; ++c) out.push_back(v[static_cast<std::size_t>(c / 3)][c % 3]);
}

}  // namespace

std::vector<double> assemble_channels_inertialized(const std::vector<double>& values, int dims,
                                                   const std::vector<char>& continues,
                                                   const std::vector<PathPiece>& pieces, double halflife_frames) {
  return assemble_channels_inertialized(values, dims, CaptureRuns(continues), pieces, halflife_frames);
}

std::vector<double> assemble_channels_inertialized(const std::vector<double>& values, int dims, const CaptureRuns& runs,
                                                   const std::vector<PathPiece>& pieces, double halflife_frames) {
  check_values(values, dims, static_cast<std::size_t>(runs.frame_count()));
  if (!(halflife_frames > 0.0)) throw Error("assemble: transition_halflife must be > 0");
  const std::vector<SourceClock> clock = source_timeline(pieces, runs);
  const ChannelReader reader(values, dims, runs);
  const double y = spring_damping(halflife_frames);
  const auto groups = static_cast<std::size_t>(reader.groups());
  Values off(groups, glm::dvec3(0.0)), off_vel(off);
  Values dst, dst_vel, previous, previous_vel, old_pose, old_vel;
  std::vector<double> out;
  out.reserve(clock.size() * static_cast<std::size_t>(dims));
  for (std::size_t i = 0; i < clock.size(); ++i) {
    const SourceClock& c = clock[i];
    reader.sample(c.time, dst);
    if (i > 0) {
      for (std::size_t k = 0; k < groups; ++k) spring_decay(off[k], off_vel[k], y, 1.0);
      if (c.run != clock[i - 1].run) {
        // Where the old source would have gone next (transitions.cpp old_source_next).
        const SourceClock& p = clock[i - 1];
        if (p.rate > 0.0 && reader.readable(p.time + p.rate, static_cast<int>(std::floor(p.time)))) {
          reader.sample(p.time + p.rate, old_pose);
          reader.velocity(p.time + p.rate, p.rate, old_pose, old_vel);
        } else {
          old_pose = previous;
          for (std::size_t k = 0; k < groups; ++k) old_pose[k] += previous_vel[k];
          old_vel = previous_vel;
        }
        reader.velocity(c.time, c.rate, dst, dst_vel);
        // Summed in transitions.cpp's order, so a channel rounds as a translation does.
        for (std::size_t k = 0; k < groups; ++k) {
          off[k] = off[k] + old_pose[k] - dst[k];
          off_vel[k] = off_vel[k] + old_vel[k] - dst_vel[k];
        }
      }
    }
    Values shown(groups);
    for (std::size_t k = 0; k < groups; ++k) shown[k] = dst[k] + off[k];
    append_group_values(shown, dims, out);
    previous = dst;
    reader.velocity(c.time, c.rate, dst, previous_vel);
  }
  return out;
}

std::vector<double> assemble_channels_blended(const std::vector<double>& values, int dims,
                                              const std::vector<PathPiece>& pieces, const BlendParams& params) {
  if (dims < 1 || values.size() % static_cast<std::size_t>(dims) != 0)
    throw Error("assemble: the channels do not cover the source frames");
  const auto frames = values.size() / static_cast<std::size_t>(dims);
  const int groups = (dims + 2) / 3;
  // The channels of a piece's path frames as the translations of a skeleton of point joints, so
  // they are resampled and blended by the motion's own code.
  Skeleton points;
  for (int k = 0; k < groups; ++k) {
    Joint j;
    j.name = "c" + std::to_string(k);
    j.parent = k == 0 ? -1 : 0;
    j.channels = {Channel::Xposition, Channel::Yposition, Channel::Zposition};
    points.joints.push_back(j);
  }
  std::vector<Motion> resampled;
  resampled.reserve(pieces.size());
  for (const PathPiece& piece : pieces) {
    Motion m = motion_rest(points, 30.0, static_cast<int>(piece.path.size()));
    for (std::size_t i = 0; i < piece.path.size(); ++i) {
      const auto f = static_cast<std::size_t>(piece.path[i]);
      if (f >= frames) throw Error("assemble: a path frame is outside the channels");
      for (int c = 0; c < dims; ++c)
        m.translations[m.index(static_cast<int>(i), c / 3)][c % 3] =
            values[f * static_cast<std::size_t>(dims) + static_cast<std::size_t>(c)];
    }
    std::vector<int> path(piece.path.size());
    for (std::size_t i = 0; i < path.size(); ++i) path[i] = static_cast<int>(i);
    resampled.push_back(resample_path(m, path, piece.length));
  }
  const Motion joined = blend_concatenate(resampled, params);
  std::vector<double> out;
  out.reserve(static_cast<std::size_t>(joined.frame_count) * static_cast<std::size_t>(dims));
  for (int f = 0; f < joined.frame_count; ++f)
    for (int c = 0; c < dims; ++c) out.push_back(joined.translation(f, c / 3)[c % 3]);
  return out;
}

}  // namespace gmg
