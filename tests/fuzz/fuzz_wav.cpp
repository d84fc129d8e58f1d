// libFuzzer harness: the WAV reader (audio/wav.cpp), then the resampler the onset detector uses.
#include "audio/resample.h"
#include "audio/wav.h"
#include "tests/fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gmg::fuzz::expect_success_or_error("fuzz.wav", [&] {
    const gmg::audio::Audio a = gmg::audio::parse_wav(gmg::fuzz::bytes_of(data, size), "fuzz.wav");
    // Only short clips at rates sharing a factor of 50 with 22050 Hz (a filter of at most 76801
    // taps): the resampler's cost at coprime rates is what the rate limits bound, not the point here.
    if (a.samples.size() < 4096 && a.sample_rate % 50 == 0)
      (void)gmg::audio::resample_poly(a.samples, a.sample_rate, 22050);
  });
  return 0;
}
