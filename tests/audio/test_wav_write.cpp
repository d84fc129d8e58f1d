// Tests of audio/wav: writing 16-bit PCM, and reading at a target rate.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "audio/resample.h"
#include "audio/wav.h"
#include "engine/core/error.h"
#include "tests/audio/wav_bytes.h"
#include "tests/core/helpers.h"
#include "tests/test_support.h"

namespace {

using gmg::audio::Audio;
using gmg::testing::error_of;
using gmg::testing::TempDir;
using namespace gmg::testing::wav;

TEST(Wav, WritePcm16RoundTrip) {
  TempDir dir;
  Audio a;
  a.sample_rate = 22050;
  for (int i = 0; i < 1001; ++i)
    a.samples.push_back(static_cast<float>(std::lround(10000 * std::sin(i * 0.01))) / 32768.0f);
  a.samples.push_back(2.0f);   // clipped
  a.samples.push_back(-2.0f);  // clipped
  const std::string path = dir.file("out.wav");
  gmg::audio::write_wav_pcm16(path, a);
  std::size_t files = 0;  // no temporary file left beside it, whatever its name
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1u);
  EXPECT_EQ(std::filesystem::file_size(path), 44u + 2u * a.samples.size());
  Audio b = gmg::audio::read_wav(path);
  EXPECT_EQ(b.sample_rate, 22050);
  ASSERT_EQ(b.samples.size(), a.samples.size());
  for (std::size_t i = 0; i < 1001; ++i) ASSERT_EQ(b.samples[i], a.samples[i]) << i;
  EXPECT_FLOAT_EQ(b.samples[1001], 32767.0f / 32768.0f);
  EXPECT_FLOAT_EQ(b.samples[1002], -1.0f);
}

TEST(Wav, WritePcm16HeaderByHand) {
  // Two samples at 8000 Hz: RIFF size 36 + 4 data bytes, byte rate 16000, block align 2;
  // 0.5 -> 16384 (0x4000), -1.0 -> -32768 (0x8000), little-endian.
  TempDir dir;
  Audio a;
  a.sample_rate = 8000;
  a.samples = {0.5f, -1.0f};
  gmg::audio::write_wav_pcm16(dir.file("two.wav"), a);
  const std::string expected = std::string("RIFF") + std::string("\x28\0\0\0", 4) + "WAVEfmt " +
                               std::string("\x10\0\0\0\x01\0\x01\0\x40\x1f\0\0\x80\x3e\0\0\x02\0\x10\0", 20) + "data" +
                               std::string("\x04\0\0\0\0\x40\0\x80", 8);
  std::ifstream in(dir.file("two.wav"), std::ios::binary);
  const std::string written((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(written, expected);
}

TEST(Wav, WriteErrorsNameTheFileAndLeaveNothing) {
  TempDir dir;
  Audio a;
  a.sample_rate = 16000;
  a.samples = {0.1f, 0.2f};
  Audio no_rate;
  const std::string bad = dir.file("bad.wav");
  EXPECT_EQ(error_of([&] { gmg::audio::write_wav_pcm16(bad, no_rate); }),
            bad + ": cannot write WAV: sample rate 0 is not positive");
  const std::string nowhere = dir.file("no/such/dir/x.wav");
  const std::string msg = error_of([&] { gmg::audio::write_wav_pcm16(nowhere, a); });
  EXPECT_EQ(msg.rfind(nowhere + ": ", 0), 0u) << msg;
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(Wav, ReadWithTargetRateResamples) {
  TempDir dir;
  Audio a;
  a.sample_rate = 16000;
  a.samples.assign(16000, 0.25f);
  const std::string path = dir.file("a.wav");
  gmg::audio::write_wav_pcm16(path, a);
  Audio b = gmg::audio::read_wav(path, 22050);
  EXPECT_EQ(b.sample_rate, 22050);
  EXPECT_EQ(b.samples.size(), 22050u);
  EXPECT_NEAR(b.samples[11025], 0.25f, 1e-3);
  Audio c = gmg::audio::read_wav(path, 16000);
  EXPECT_EQ(c.samples, gmg::audio::read_wav(path).samples);
  EXPECT_EQ(error_of([&] { gmg::audio::read_wav(path, 0); }), path + ": target sample rate 0 is not positive");
}

}  // namespace
