// libFuzzer harness: graph files (graph/graph_io.cpp). The file's checksum would stop almost every
// mutation at the header, so the first byte chooses: even, the rest is a whole file; odd, the
// rest is how many bytes the checksum covers (u64) and a payload that gets a valid header (this
// gmg's format version) and checksum, so the field checks behind the checksum are what is fuzzed.
#include <algorithm>
#include <cstdint>
#include <cstring>

#include "engine/core/checksum.h"
#include "graph/graph_io.h"
#include "tests/fuzz/fuzz_common.h"

namespace {

template <typename T>
void append(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.append(b, sizeof(T));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  std::string bytes = gmg::fuzz::bytes_of(data + 1, size - 1);
  if (data[0] % 2 == 1) {
    std::string file("GMGRAPH\0", 8);
    append<std::uint32_t>(file, gmg::kGraphFormatVersion);
    // The checksum covers the payload up to its motion values: the input's next 8 bytes say how
    // far (at most all of it), the rest is the payload.
    std::uint64_t summed = 0;
    std::memcpy(&summed, bytes.data(), std::min<std::size_t>(8, bytes.size()));
    bytes.erase(0, std::min<std::size_t>(8, bytes.size()));
    summed = std::min<std::uint64_t>(summed, bytes.size());
    append<std::uint64_t>(file, bytes.size());
    append<std::uint64_t>(file, summed);
    file += bytes;
    append<std::uint64_t>(file, gmg::checksum_of(bytes.data(), static_cast<std::size_t>(summed)));
    bytes = std::move(file);
  }
  gmg::fuzz::expect_success_or_error("fuzz.gmg", [&] { (void)gmg::graph_parse(bytes, "fuzz.gmg"); });
  return 0;
}
