// libFuzzer harness: the GENEA TSV transcript reader (text/tsv.cpp).
#include "tests/fuzz/fuzz_common.h"
#include "text/transcript.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gmg::fuzz::expect_success_or_error("fuzz.tsv",
                                     [&] { (void)gmg::text::parse_tsv(gmg::fuzz::bytes_of(data, size), "fuzz.tsv"); });
  return 0;
}
