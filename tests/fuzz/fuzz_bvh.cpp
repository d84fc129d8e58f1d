// libFuzzer harness: the BVH reader (engine/motion/bvh_read.cpp).
#include "engine/motion/bvh.h"
#include "tests/fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gmg::fuzz::expect_success_or_error("fuzz.bvh",
                                     [&] { (void)gmg::bvh_parse(gmg::fuzz::bytes_of(data, size), "fuzz.bvh"); });
  return 0;
}
