// libFuzzer harness: JSON transcripts as the engine reads them (text/whisper_json.cpp: Whisper,
// WhisperX, else Google speech JSON).
#include "tests/fuzz/fuzz_common.h"
#include "text/transcript.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gmg::fuzz::expect_success_or_error(
      "fuzz.json", [&] { (void)gmg::text::parse_json_transcript(gmg::fuzz::bytes_of(data, size), "fuzz.json"); });
  return 0;
}
