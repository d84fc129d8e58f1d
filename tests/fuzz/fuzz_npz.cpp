// libFuzzer harness: the SMPL-X .npz motion reader (engine/motion/npz.cpp: zip, .npy headers,
// shapes, and the body: betas, expressions, text arrays), with a two-joint skeleton template.
#include "engine/motion/npz.h"
#include "tests/fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const gmg::Skeleton skeleton = gmg::fuzz::two_joint_skeleton();
  gmg::fuzz::expect_success_or_error("fuzz.npz", [&] {
    gmg::SmplxBody body;
    (void)gmg::npz_parse(gmg::fuzz::bytes_of(data, size), "fuzz.npz", skeleton, &body);
  });
  return 0;
}
