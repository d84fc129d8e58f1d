// The up axis of a motion file. BVH says nothing about it: the datasets gmg was measured on
// (BEAT2, ZEGGS, GENEA) are Y-up, Blender's BVH exporter writes Z-up. Everything that asks where
// the floor is, which way is horizontal or how the speaker faces (capture facts, the root anchor,
// foot contacts, the body's layers, metrics, the renderer's camera) works in Y-up; a reference in
// another up axis is turned into Y-up when it is read (the canonical frame) and every output is
// turned back, so a rotated reference gives the same motion, rotated.
//
// Only the root joint's rotation and translation change: the rest of the skeleton hangs from the
// root, so turning the root turns the whole body.
#pragma once

#include <cstdint>
#include <string>

#include "engine/core/enum_names.h"
#include "engine/motion/motion.h"

namespace gmg {

enum class UpAxis : std::uint8_t { Y, Z };
inline constexpr EnumName<UpAxis> kUpAxisNames[] = {{UpAxis::Y, "y"}, {UpAxis::Z, "z"}};

// What `--up` asks for: detect it, or a given axis.
enum class UpChoice : std::uint8_t { Auto, Y, Z };
inline constexpr EnumName<UpChoice> kUpChoiceNames[] = {
    {UpChoice::Auto, "auto"}, {UpChoice::Y, "y"}, {UpChoice::Z, "z"}};

// The axis along which the body is tallest: of Y and Z, the one with the larger median extent of
// the joints' world positions over up to 64 frames spread over the motion (a standing speaker is
// 3-6 times taller than deep; arms out sideways lie along X, which is never up). Y for a motion
// without frames.
UpAxis detect_up_axis(const Motion& m);

// `choice` resolved against m: the detected axis for Auto.
UpAxis resolve_up_axis(const Motion& m, UpChoice choice);

// Turns m from `from` into Y-up (Z-up: (x, y, z) -> (x, z, -y), a quarter turn about X), in place:
// the root's rotation and translation of every frame. The root's Euler hints are dropped (they
// no longer describe its rotation). Nothing for Y.
void motion_to_y_up(Motion& m, UpAxis from);

// The inverse: turns a Y-up motion into `to`, in place.
void motion_from_y_up(Motion& m, UpAxis to);

// A motion file read (engine/motion/motion_file.h motion_read) and turned into Y-up from its
// detected up axis: for what measures or draws a motion on its own (evaluate, render).
Motion motion_read_y_up(const std::string& path, const std::string& skeleton = "");

// A point or direction between the frames.
glm::dvec3 to_y_up(const glm::dvec3& v, UpAxis from);
glm::dvec3 from_y_up(const glm::dvec3& v, UpAxis to);

}  // namespace gmg
