// libFuzzer harness: the Google speech JSON transcript reader (text/google_json.cpp).
#include "tests/fuzz/fuzz_common.h"
#include "text/transcript.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gmg::fuzz::expect_success_or_error(
      "fuzz.json", [&] { (void)gmg::text::parse_google_json(gmg::fuzz::bytes_of(data, size), "fuzz.json"); });
  return 0;
}
