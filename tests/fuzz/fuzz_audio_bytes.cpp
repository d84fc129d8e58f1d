// libFuzzer harness: what gmg makes of any bytes given as speech, and how it quotes them. The
// content sniffer (audio/audio_file.h) and, for a WAV that reads, the speech check
// (audio/speech_check.h) must return, never crash; escape_nonprintable must turn any bytes into one
// line of valid UTF-8 without control characters (what error messages print on a terminal).
#include <cstdlib>

#include "audio/audio_file.h"
#include "audio/speech_check.h"
#include "audio/speech_energy.h"
#include "audio/wav.h"
#include "engine/core/strings.h"
#include "tests/fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes = gmg::fuzz::bytes_of(data, size);
  (void)gmg::audio::sniff_content(bytes.substr(0, 64));
  const std::string shown = gmg::escape_nonprintable(bytes);
  for (std::size_t pos = 0; pos < shown.size();) {
    const std::optional<gmg::Utf8Char> c = gmg::decode_utf8(shown, pos);
    if (!c || c->code_point < 0x20 || c->code_point == 0x7F || (c->code_point >= 0x80 && c->code_point < 0xA0))
      std::abort();  // a byte a terminal would act on, or invalid UTF-8
    pos += c->length;
  }
  gmg::fuzz::expect_success_or_error("fuzz.wav", [&] {
    const gmg::audio::Audio a = gmg::audio::parse_wav(bytes, "fuzz.wav");
    (void)gmg::audio::speech_level_problem(a.duration(), gmg::audio::energy_track(a));
  });
  return 0;
}
