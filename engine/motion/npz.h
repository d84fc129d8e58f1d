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
// the root's translation is trans + that rest position (npz_root_rest): the template's ROOT
// OFFSET, the rest position BVH puts there, when it is not zero. A SMPL-X skeleton whose ROOT
// OFFSET is zero is BEAT2's BVH convention, whose root channels hold trans + the pelvis's rest
// position of its body (BEAT2 speaker 2: (0.002777, -0.383289, 0.010682) m), so that constant
// is used. Either way an .npz read on a BVH's skeleton gives that BVH's joint positions, and
// writing subtracts the same vector, so `trans` is BEAT2's whether a motion came from the BVH or
// the .npz, and BVH -> npz -> BVH with the same skeleton keeps every value (to float32 for poses,
// see NpzFloats).
//
// The body: an archive's `betas` (shape), `expressions` (the face, frames x D; BEAT2: D = 100
// FLAME expression coefficients), `gender` and `model` are read into SmplxBody and written back,
// so a motion made from a BEAT2 file keeps its speaker.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/enum_names.h"
#include "engine/motion/motion.h"

namespace gmg {

// The 55 SMPL-X joint names in SMPL-X order (the order of `poses`).
const std::vector<std::string>& smplx_joint_names();

// True when the skeleton has every SMPL-X joint name (in any order, perhaps with other joints).
bool has_smplx_names(const Skeleton& skeleton);

// What an SMPL-X archive holds besides the skeleton's motion: the body's shape and its face.
struct SmplxBody {
  std::vector<double> betas;        // shape coefficients (BEAT2: 300); empty = not known (written as zeros)
  std::vector<double> expressions;  // the face: frames x expression_dims, frame-major; empty = no face
  int expression_dims = 0;          // 0 = no face (written as zeros)
  std::string gender;               // "" = not known (written "neutral")
  std::string model;                // "" = not known (written "smplx2020")

  bool has_face() const { return expression_dims > 0; }
};

// BEAT2's expression coefficients per frame and betas, the sizes written when a body has none.
inline constexpr int kBeat2Expressions = 100;
inline constexpr int kBeat2Betas = 300;

// The dtypes written: Beat2 as BEAT2 ships them (poses and betas float32; trans and expressions
// float64; mocap_frame_rate int32), or every float array float64 (a BVH -> npz -> BVH round trip
// then gives the BVH's bytes back).
enum class NpzFloats : std::uint8_t { Beat2, Float64 };
inline constexpr EnumName<NpzFloats> kNpzFloatsNames[] = {{NpzFloats::Beat2, "beat2"}, {NpzFloats::Float64, "float64"}};

// BEAT2 speaker 2's pelvis rest position (metres, Y up), which BEAT2's BVH adds to `trans`.
glm::dvec3 beat2_pelvis_rest();

// The vector between the root's translation and `trans` (see above): the ROOT OFFSET when it is
// not zero; beat2_pelvis_rest() for a skeleton with the 55 SMPL-X joint names and a zero ROOT
// OFFSET; zero otherwise.
glm::dvec3 npz_root_rest(const Skeleton& skeleton);

// Parses the bytes of an .npz archive with `skeleton` as the template (see above). `name` labels
// errors. Throws gmg::Error naming the archive and the array: not a zip archive, a missing
// array (the message lists the archive's arrays), a malformed .npy, a shape that does not fit
// the template, a value that is not finite, a frame rate that is not positive, zero frames.
// With out_body, the body's arrays are read too (each optional; `expressions` must have the
// poses' frame count, every value finite; all-zero expressions or betas, as written for a motion
// without a face or shape, are none). `template_name` (the template's file, when it has one)
// names the template in the errors about it.
Motion npz_parse(const std::string& bytes, const std::string& name, const Skeleton& skeleton,
                 SmplxBody* out_body = nullptr, const std::string& template_name = "");

// Reads an .npz file (npz_parse).
Motion npz_read(const std::string& path, const Skeleton& skeleton, SmplxBody* out_body = nullptr,
                const std::string& template_name = "");

// The archive bytes of m: `poses` (N x 3J; the SMPL-X order when the skeleton has exactly the 55
// SMPL-X joint names, else the skeleton's order), `trans` (N x 3: the root's translation minus
// npz_root_rest) and `mocap_frame_rate` (int32 when whole, as BEAT2 writes it, else float64). A
// SMPL-X skeleton, or a body that has them, also gets BEAT2's other arrays, in BEAT2's order
// (betas, poses, expressions, trans, model, gender, mocap_frame_rate): `betas` (the body's, else
// 300 zeros: the skeleton's bone lengths are not a body shape, so the mean shape), `expressions`
// (the body's face, else N x 100 zeros), `gender` and `model` (the body's, else "neutral" and
// "smplx2020"). Only the root's translation is stored: other joints' position channels are
// dropped. gmg::Error naming `name` when the body's face does not have m's frame count.
std::string npz_format(const Motion& m, const std::string& name, const SmplxBody& body = {},
                       NpzFloats floats = NpzFloats::Beat2);

// Writes npz_format(m) atomically.
void npz_write(const std::string& path, const Motion& m, const SmplxBody& body = {},
               NpzFloats floats = NpzFloats::Beat2);

// The shape coefficients in a file: the `betas` array of an .npz archive (a BEAT2 file), or an
// .npy array (numpy.save), 1-D or 1 x N, finite. gmg::Error naming the file otherwise.
std::vector<double> read_betas_file(const std::string& path);

}  // namespace gmg
