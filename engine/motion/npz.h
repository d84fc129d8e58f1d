// SMPL-X motion in NumPy .npz archives, as BEAT2 ships it and BEAT2/EMAGE tools read it.
//
// An archive holds `poses` (N x 3J float: per frame, J joint rotations as axis-angle = exponential
// map, radians, in the body model's joint order; SMPL-X has J = 55), `trans` (N x 3: the pelvis
// translation, metres) and `mocap_frame_rate` (a scalar; AMASS's spelling `mocap_framerate` is
// read too). Rotations map a vector from the joint's frame to its parent's, as the engine's do
// (engine/motion/rotation.h), and the axes are the file's (BEAT2: Y up).
//
// The archive has no bone lengths: a skeleton template gives them (any BVH of the same joints;
// only its hierarchy is used). Joint k of `poses` is the template joint with the k-th SMPL-X name
// when J = 55 and the template has all 55 SMPL-X names (in any order, e.g. the depth-first order
// of a BVH); otherwise the template's k-th joint in its file order, which must then be the
// archive's joint order. Template joints without a pose stay in their rest pose.
//
// The root: SMPL-X's `trans` leaves out the pelvis's rest position (the body model adds it), so
// the root's translation is trans + the template's ROOT OFFSET, the rest position BVH puts
// there. A template whose ROOT OFFSET is the pelvis's rest location gives the world positions
// of the body model; one with a zero ROOT OFFSET gives them shifted by that constant (BEAT2
// speaker 2: (0.002777, -0.383289, 0.010682) m), and the same root-relative positions. Writing
// subtracts the skeleton's ROOT OFFSET again, so BVH -> npz -> BVH with the same skeleton is
// exact.
#pragma once

#include <string>
#include <vector>

#include "engine/motion/motion.h"

namespace gmg {

// The 55 SMPL-X joint names in SMPL-X order (the order of `poses`).
const std::vector<std::string>& smplx_joint_names();

// Parses the bytes of an .npz archive with `skeleton` as the template (see above). `name` labels
// errors. Throws gmg::Error naming the archive and the array: not a zip archive, a missing
// array (the message lists the archive's arrays), a malformed .npy, a shape that does not fit
// the template, a value that is not finite, a frame rate that is not positive, zero frames.
Motion npz_parse(const std::string& bytes, const std::string& name, const Skeleton& skeleton);

// Reads an .npz file (npz_parse).
Motion npz_read(const std::string& path, const Skeleton& skeleton);

// The archive bytes of m: `poses` (N x 3J float64; the SMPL-X order when the skeleton has exactly
// the 55 SMPL-X joint names, else the skeleton's order), `trans` (N x 3 float64: the root's
// translation minus its OFFSET) and `mocap_frame_rate` (int32 when whole, as BEAT2 writes it,
// else float64). A SMPL-X skeleton also gets BEAT2's other arrays, so tools that load them
// run: `betas` (300 zeros: the skeleton's bone lengths are not a body shape, so the mean shape),
// `expressions` (N x 100 zeros: no face motion), `gender` "neutral", `model` "smplx2020".
// Only the root's translation is stored: other joints' position channels are dropped.
std::string npz_format(const Motion& m, const std::string& name);

// Writes npz_format(m) atomically.
void npz_write(const std::string& path, const Motion& m);

}  // namespace gmg
