// BVH reading and writing for any skeleton.
//
// Reads (bvh_read.cpp): any joint names and hierarchy, End Sites, 0-6 channels per joint in any
// order (channel names ASCII case-insensitive, position channels on any joint), CRLF or LF, tabs or
// spaces, a UTF-8 byte-order mark. Rejects malformed files with a gmg::Error "path: line N:
// problem" (an unreadable file: the reader's "path: cannot open (reason)", engine/core/files.h)
// and never returns a partial motion. Writes: bvh_write.cpp.
//
// Semantics: rotation channels compose intrinsically in listed order (see engine/motion/rotation.h);
// a joint's position channels replace its OFFSET as its local translation (the convention of
// MotionBuilder and the GENEA data, whose per-joint position channels repeat the offsets).
// fps = 1 / Frame Time, snapped to the nearest integer when within 0.1% of it, because files
// write "0.03333" for 30 fps and the frame grid must be exact.
#pragma once

#include <string>

#include "engine/motion/motion.h"

namespace gmg {

Motion bvh_read(const std::string& path);

// Parses BVH text; `name` is used in error messages in place of a path.
Motion bvh_parse(const std::string& text, const std::string& name);

// Writes m as BVH text (same skeleton and channel lists). Euler angles are chosen per joint to
// stay continuous from frame to frame, so curves do not flip at +/-180 degrees.
std::string bvh_format(const Motion& m);

// Writes atomically (temporary file, then rename). Throws gmg::Error on failure.
void bvh_write(const std::string& path, const Motion& m);

}  // namespace gmg
