// What the assembly needs to know about a whole reference capture, beyond the frames it plays:
// how far its root ever steps in one frame, where it stands, and when and how its feet are on the
// ground. Each is a property of every frame of the reference, so it is computed once per
// reference: `gmg build` stores it in the graph (graph/graph_io.cpp) and a reenactment reads the
// reference only at the frames it plays (engine/assemble/transitions.h, foot_lock.h).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/motion/body_parts.h"
#include "engine/motion/capture_runs.h"
#include "engine/motion/motion.h"
#include "engine/motion/samples.h"

namespace gmg {

// A foot is in contact when its world speed is below kContactSpeed leg lengths per second (13 cm/s
// for a 0.9 m leg: a planted foot's capture noise stays far below, a step is ten times faster) and
// it is within kContactHeight leg lengths of the lowest point it reaches in its capture run ("low").
// Contacts and gaps shorter than kContactMinRun frames are smoothed away.
constexpr double kContactSpeed = 0.15;
constexpr double kContactHeight = 0.10;
constexpr int kContactMinRun = 3;

// Bits of CaptureFacts::foot_flags for leg l (0 or 1, find_legs order).
inline std::uint8_t foot_contact_bit(int leg) { return static_cast<std::uint8_t>(1u << (2 * leg)); }
inline std::uint8_t foot_low_bit(int leg) { return static_cast<std::uint8_t>(2u << (2 * leg)); }

struct CaptureFacts {
  bool known = false;  // false: not computed (a graph made by hand); the assembly computes them itself
  // The largest horizontal root step inside capture runs (file units per frame).
  double largest_root_step = 0.0;
  // The root's extent over every frame (each coordinate's minimum and maximum).
  glm::dvec3 root_lo{0.0}, root_hi{0.0};
  // Per leg of find_legs (none or two): the knee's hinge axis in the thigh's frame, learnt from the
  // frames where the capture bends the knee by 17 degrees or more; 0 when it never does.
  std::vector<glm::dvec3> knee_hinges;
  // Per frame (empty without legs): foot_contact_bit and foot_low_bit of each leg.
  Samples<std::uint8_t> foot_flags;
};

// Computes them over every frame of `m`, whose capture runs are `runs` (same frame count).
CaptureFacts capture_facts(const Motion& m, const CaptureRuns& runs);

// Contact and "low" flags of one foot from its world positions `p` (one per frame, Y-up) in the
// capture runs `runs`: low within kContactHeight leg lengths of its lowest point in the run,
// contact when also slower than kContactSpeed leg lengths a second; short runs smoothed away.
void foot_contacts(const std::vector<glm::dvec3>& p, const CaptureRuns& runs, double leg_length, double fps,
                   std::vector<char>& out_contact, std::vector<char>& out_low);

// Joints from the root down to j.
std::vector<int> chain_to(const Skeleton& s, int j);

// World rotation and position of every joint of `chain` (chain_to's) at frame f.
void chain_world(const Motion& m, int f, const std::vector<int>& chain, std::vector<glm::dquat>& rot,
                 std::vector<glm::dvec3>& pos);

}  // namespace gmg
