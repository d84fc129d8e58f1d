// Jerk spikes of a capture: frames where a joint of the upper body moves far more abruptly than it
// ever does otherwise. ZEGGS `067_Speech_2_x_1_0` has such a stretch (frames 1067-1231: the right
// forearm and hand shake at 4-5 Hz, 10 cm a frame back and forth, with jerk 20-190 x the hand's
// median). Whether it is a shaken hand or marker noise cannot be told from the capture, so it is
// kept as the speaker's motion; what the planner must not do is replay it more often than the
// speaker did it (search/planner.cpp): an output built from the stretches that suit its speech would
// otherwise show it wherever they happen to include it.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/motion/capture_runs.h"
#include "engine/motion/motion.h"

namespace gmg {

// A joint spikes at a frame when its root-relative position's jerk (third difference inside a
// capture run) exceeds kSpikeFactor times its median over the capture. Spiking frames are widened
// by kSpikeMargin frames either side (the jerk of a jolt spreads over its neighbours).
constexpr double kSpikeFactor = 20.0;
constexpr int kSpikeMargin = 2;

// Per frame of m: 1 where one of `joints` spikes (engine/motion/body_parts.h upper_body_joints).
std::vector<std::uint8_t> jerk_spikes(const Motion& m, const CaptureRuns& runs, const std::vector<int>& joints);

}  // namespace gmg
