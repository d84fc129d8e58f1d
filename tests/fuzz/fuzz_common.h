// Shared by the libFuzzer harnesses of tests/fuzz: each feeds the bytes to one reader and accepts
// exactly one outcome besides success, a gmg::Error (whose message must name the input). Any
// other exception escapes and libFuzzer reports it as a crash, as it does for a sanitizer
// finding, a timeout (-timeout) or too much memory (-rss_limit_mb / -malloc_limit_mb).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "engine/core/error.h"
#include "engine/motion/motion.h"
#include "engine/motion/rotation.h"

namespace gmg::fuzz {

inline std::string bytes_of(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

// Runs f; a gmg::Error is an accepted outcome but must name `name` (the input's label).
template <typename F>
void expect_success_or_error(const std::string& name, F&& f) {
  try {
    f();
  } catch (const gmg::Error& e) {
    const std::string what = e.what();
    if (what.find(name) == std::string::npos && what.rfind("invalid config: ", 0) != 0 &&
        what.rfind("config key ", 0) != 0 && what.rfind("unknown config key ", 0) != 0)
      std::abort();  // an error that does not say which input it is about
  }
}

// Two joints (a root with position channels and a head): the skeleton of the hand-made graph
// seed and the template the .npz harness reads archives with.
inline gmg::Skeleton two_joint_skeleton() {
  gmg::Skeleton sk;
  gmg::Joint root;
  root.name = "hips";
  root.channels = {gmg::Channel::Xposition, gmg::Channel::Yposition, gmg::Channel::Zposition,
                   gmg::Channel::Zrotation, gmg::Channel::Xrotation, gmg::Channel::Yrotation};
  root.rotation_order = gmg::rotation_order_from_channels(root.channels);
  gmg::Joint head;
  head.name = "head";
  head.parent = 0;
  head.offset = glm::dvec3(0, 10, 0);
  head.channels = {gmg::Channel::Zrotation, gmg::Channel::Xrotation, gmg::Channel::Yrotation};
  head.rotation_order = gmg::rotation_order_from_channels(head.channels);
  head.has_end_site = true;
  head.end_site = glm::dvec3(0, 5, 0);
  sk.joints = {root, head};
  return sk;
}

}  // namespace gmg::fuzz
