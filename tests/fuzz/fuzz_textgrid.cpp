// libFuzzer harness: the Praat TextGrid transcript reader (text/textgrid.cpp).
#include "tests/fuzz/fuzz_common.h"
#include "text/transcript.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gmg::fuzz::expect_success_or_error(
      "fuzz.TextGrid", [&] { (void)gmg::text::parse_textgrid(gmg::fuzz::bytes_of(data, size), "fuzz.TextGrid"); });
  return 0;
}
