// The limits every reader and writer enforces on what an input may claim, in one place.
//
// Hostile or damaged files must not make gmg allocate gigabytes, loop for minutes or overflow
// an int: each reader checks these caps and rejects a file beyond them with a gmg::Error naming
// the file, the value and the cap. Each value is far above any real recording; the comment says
// why it is safe (BEAT2 has 55 joints, GENEA 2023 83, ZEGGS 75; motion is 30 to 120 fps; speech
// 16 to 48 kHz; references of hours are legitimate: 19 h at 30 fps is 2 M frames).
#pragma once

#include <cstdint>

namespace gmg::limits {

// ---- Motion (BVH reader, graph files) ----------------------------------------------------------

// Joints of a skeleton. Body rigs have 20 to 100 joints, with fingers and a face rig a few
// hundred; 1024 leaves room for both.
inline constexpr int kMaxJoints = 1024;

// Nesting depth of the BVH hierarchy (the root is depth 1). The deepest real chain, root to
// fingertip, is under 30 joints; the reader is iterative, the cap keeps recursive consumers
// (the writer) on a small stack.
inline constexpr int kMaxHierarchyDepth = 256;

// Frames a motion may have (and a BVH's "Frames:" may declare): 925 h at 30 fps, far above the
// 2 M frames of a 19 h reference, and below 2^31 so frame indices fit an int. Frames are
// allocated as they are read, never from the header, so the cap only bounds the count.
inline constexpr int kMaxFrames = 100'000'000;

// Frame rate: capture systems record 24 to 240 fps. Below 1 fps nothing moves; above 1000 fps
// a second of speech would become thousands of frames.
inline constexpr double kMinFps = 1.0;
inline constexpr double kMaxFps = 1000.0;

// A BVH's motion in memory (80 bytes per joint and frame: rotation, translation, Euler angles)
// may take at most kMotionBytesPerFileByte bytes per byte of the file, or kMotionFloorBytes for a
// small file. Real files need 1.5 to 13 (each joint with channels costs at least "0 " per
// channel in the text); only joints without channels, stored for every frame but absent from
// the frame lines, can claim more, and those make a small file ask for gigabytes.
inline constexpr std::uint64_t kMotionBytesPerFileByte = 48;
inline constexpr std::uint64_t kMotionFloorBytes = 16ull << 20;

// ---- Audio (WAV reader) -------------------------------------------------------------------------

// Sample rate: telephone speech is 8 kHz, studio recorders go to 192 kHz. The resampler's filter
// grows with the rate (20 taps per unit of the reduced rate ratio), so the cap also bounds it
// (at most 3.8 M taps, 31 MB).
inline constexpr int kMinSampleRate = 4000;
inline constexpr int kMaxSampleRate = 192000;

// Length of one audio file: a day. Hours of reference speech are legitimate; a day keeps every
// frame count derived from it (at kMaxFps) below kMaxFrames.
inline constexpr double kMaxAudioSeconds = 24.0 * 3600.0;

// Largest .npz member or .npy array read: far above any motion capture (an hour of SMPL-X at 30
// fps in float64 is 140 MB), far below what would exhaust memory on a crafted archive.
inline constexpr std::uint64_t kMaxNpyBytes = std::uint64_t{1} << 31;

// ---- Generated output ---------------------------------------------------------------------------

// A reenactment (or synthetic clip) may have at most this many frames: 92 h at 30 fps.
inline constexpr int kMaxOutputFrames = 10'000'000;

// And its BVH text at most this many bytes (estimated before any work as frames x channels x
// kBvhBytesPerValue): 8 GiB is 8 h of a GENEA skeleton (498 channels) at 30 fps.
inline constexpr std::uint64_t kMaxOutputBytes = 8ull << 30;
inline constexpr std::uint64_t kBvhBytesPerValue = 11;  // "-123.456789 ": what bvh_format writes at most, typically

}  // namespace gmg::limits
