// Tests of audio/wav: WAV decoding of every supported variant (errors: test_wav_errors.cpp,
// writing: test_wav_write.cpp).
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

TEST(Wav, Pcm16Values) {
  TempDir dir;
  std::string d;
  for (int v : {0, 16384, -32768, 32767, -1}) le16(d, static_cast<std::uint16_t>(static_cast<std::int16_t>(v)));
  Audio a = read_bytes(dir, "a.wav", wav(Fmt{}, d));
  EXPECT_EQ(a.sample_rate, 16000);
  ASSERT_EQ(a.samples.size(), 5u);
  EXPECT_FLOAT_EQ(a.samples[0], 0.0f);
  EXPECT_FLOAT_EQ(a.samples[1], 0.5f);
  EXPECT_FLOAT_EQ(a.samples[2], -1.0f);
  EXPECT_FLOAT_EQ(a.samples[3], 32767.0f / 32768.0f);
  EXPECT_FLOAT_EQ(a.samples[4], -1.0f / 32768.0f);
  EXPECT_DOUBLE_EQ(a.duration(), 5.0 / 16000.0);
}

TEST(Wav, Pcm24Values) {
  TempDir dir;
  Fmt f;
  f.bits = 24;
  std::string d;
  for (std::uint32_t v : {0x400000u, 0x800000u, 0xFFFFFFu, 0x7FFFFFu, 0xC00000u}) le24(d, v);
  Audio a = read_bytes(dir, "a.wav", wav(f, d));
  ASSERT_EQ(a.samples.size(), 5u);
  EXPECT_FLOAT_EQ(a.samples[0], 0.5f);
  EXPECT_FLOAT_EQ(a.samples[1], -1.0f);
  EXPECT_FLOAT_EQ(a.samples[2], -1.0f / 8388608.0f);
  EXPECT_FLOAT_EQ(a.samples[3], 8388607.0f / 8388608.0f);
  EXPECT_FLOAT_EQ(a.samples[4], -0.5f);
}

TEST(Wav, Pcm32Values) {
  TempDir dir;
  Fmt f;
  f.bits = 32;
  std::string d;
  for (std::uint32_t v : {0x40000000u, 0x80000000u, 0xE0000000u}) le32(d, v);
  Audio a = read_bytes(dir, "a.wav", wav(f, d));
  ASSERT_EQ(a.samples.size(), 3u);
  EXPECT_FLOAT_EQ(a.samples[0], 0.5f);
  EXPECT_FLOAT_EQ(a.samples[1], -1.0f);
  EXPECT_FLOAT_EQ(a.samples[2], -0.25f);
}

TEST(Wav, Float32Values) {
  TempDir dir;
  Fmt f;
  f.tag = 3;
  f.bits = 32;
  std::string d;
  for (float v : {0.25f, -0.75f, 1.5f, 0.0f}) f32(d, v);
  Audio a = read_bytes(dir, "a.wav", wav(f, d));
  ASSERT_EQ(a.samples.size(), 4u);
  EXPECT_FLOAT_EQ(a.samples[0], 0.25f);
  EXPECT_FLOAT_EQ(a.samples[1], -0.75f);
  EXPECT_FLOAT_EQ(a.samples[2], 1.5f);  // float data is kept as stored, like librosa
  EXPECT_FLOAT_EQ(a.samples[3], 0.0f);
}

TEST(Wav, Float64Values) {
  TempDir dir;
  Fmt f;
  f.tag = 3;
  f.bits = 64;
  std::string d;
  for (double v : {0.125, -0.5, 0.3}) f64(d, v);
  Audio a = read_bytes(dir, "a.wav", wav(f, d));
  ASSERT_EQ(a.samples.size(), 3u);
  EXPECT_FLOAT_EQ(a.samples[0], 0.125f);
  EXPECT_FLOAT_EQ(a.samples[1], -0.5f);
  EXPECT_FLOAT_EQ(a.samples[2], 0.3f);
}

TEST(Wav, Unsigned8BitValues) {
  TempDir dir;
  Fmt f;
  f.bits = 8;
  std::string d;
  for (int v : {128, 0, 192, 255, 64}) d.push_back(static_cast<char>(v));
  // 5 bytes of data: odd-sized chunk followed by a pad byte.
  Audio a = read_bytes(dir, "a.wav", wav(f, d));
  ASSERT_EQ(a.samples.size(), 5u);
  EXPECT_FLOAT_EQ(a.samples[0], 0.0f);
  EXPECT_FLOAT_EQ(a.samples[1], -1.0f);
  EXPECT_FLOAT_EQ(a.samples[2], 0.5f);
  EXPECT_FLOAT_EQ(a.samples[3], 127.0f / 128.0f);
  EXPECT_FLOAT_EQ(a.samples[4], -0.5f);
}

TEST(Wav, ExtensiblePcmAndFloat) {
  TempDir dir;
  Fmt f;
  f.tag = 0xFFFE;
  f.bits = 24;
  f.subformat = 1;
  std::string d;
  le24(d, 0x200000);
  le24(d, 0xE00000);
  Audio a = read_bytes(dir, "pcm.wav", wav(f, d));
  ASSERT_EQ(a.samples.size(), 2u);
  EXPECT_FLOAT_EQ(a.samples[0], 0.25f);
  EXPECT_FLOAT_EQ(a.samples[1], -0.25f);

  f.bits = 32;
  f.subformat = 3;
  d.clear();
  f32(d, -0.625f);
  Audio b = read_bytes(dir, "float.wav", wav(f, d));
  ASSERT_EQ(b.samples.size(), 1u);
  EXPECT_FLOAT_EQ(b.samples[0], -0.625f);

  // A subformat GUID that is neither PCM nor float.
  f.subformat = 2;
  expect_wav_error(dir, "adpcm_ext.wav", wav(f, d), {"byte", "subformat"});
}

TEST(Wav, ChannelsAreMixedDownByMean) {
  TempDir dir;
  Fmt f;
  f.channels = 2;
  std::string d;
  // frames (L, R): (0.5, -0.25), (1/4, 1/4), (-1, 0)
  for (int v : {16384, -8192, 8192, 8192, -32768, 0}) le16(d, static_cast<std::uint16_t>(static_cast<std::int16_t>(v)));
  Audio a = read_bytes(dir, "stereo.wav", wav(f, d));
  ASSERT_EQ(a.samples.size(), 3u);
  EXPECT_FLOAT_EQ(a.samples[0], 0.125f);
  EXPECT_FLOAT_EQ(a.samples[1], 0.25f);
  EXPECT_FLOAT_EQ(a.samples[2], -0.5f);

  f.channels = 3;
  f.tag = 3;
  f.bits = 32;
  d.clear();
  for (float v : {0.3f, 0.6f, 0.9f}) f32(d, v);
  Audio b = read_bytes(dir, "three.wav", wav(f, d));
  ASSERT_EQ(b.samples.size(), 1u);
  EXPECT_NEAR(b.samples[0], 0.6f, 1e-6);
}

// Every format and channel count decodes as the formula, bit for bit (the mean of the channels
// summed from 0.0 in double, times 1 / channels, rounded to float; a float sample of -0 comes out
// +0), over more frames than the reader decodes at a time; read from a file and from bytes alike.
TEST(Wav, EveryFormatDecodesAsTheFormulaBitForBit) {
  TempDir dir;
  struct Case {
    std::uint16_t tag, bits;
  };
  std::uint64_t state = 7;
  const auto next = [&state] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return state >> 11;
  };
  for (const Case c : {Case{1, 8}, Case{1, 16}, Case{1, 24}, Case{1, 32}, Case{3, 32}, Case{3, 64}})
    for (const std::uint16_t channels : {1, 2, 3}) {
      Fmt f;
      f.tag = c.tag;
      f.bits = c.bits;
      f.channels = channels;
      const std::size_t frames = 9001;
      std::string d;
      std::vector<double> values;  // each stored sample as the reader reads it
      for (std::size_t i = 0; i < frames * channels; ++i) {
        const std::uint64_t r = next();
        const bool special = i % 97 == 5;  // the extremes, and -0 for floats
        if (c.tag == 1 && c.bits == 8) {
          const int u = special ? (i % 2 ? 0 : 255) : static_cast<int>(r % 256);
          d.push_back(static_cast<char>(u));
          values.push_back((u - 128) / 128.0);
        } else if (c.tag == 1 && c.bits == 16) {
          const std::int16_t v = special ? (i % 2 ? -32768 : 32767) : static_cast<std::int16_t>(r);
          le16(d, static_cast<std::uint16_t>(v));
          values.push_back(v / 32768.0);
        } else if (c.tag == 1 && c.bits == 24) {
          const std::int32_t v =
              special ? (i % 2 ? -8388608 : 8388607) : static_cast<std::int32_t>(r % 16777216) - 8388608;
          le24(d, static_cast<std::uint32_t>(v) & 0xFFFFFFu);
          values.push_back(v / 8388608.0);
        } else if (c.tag == 1) {
          const std::int32_t v = special ? (i % 2 ? std::numeric_limits<std::int32_t>::min() : 2147483647)
                                         : static_cast<std::int32_t>(static_cast<std::uint32_t>(r));
          le32(d, static_cast<std::uint32_t>(v));
          values.push_back(v / 2147483648.0);
        } else if (c.bits == 32) {
          const float v = special ? -0.0f : static_cast<float>(static_cast<double>(r % 2000001) / 1e6 - 1.0);
          f32(d, v);
          values.push_back(v);
        } else {
          const double v = special ? -0.0 : static_cast<double>(r % 2000001) / 1e6 - 1.0 + 1e-12;
          f64(d, v);
          values.push_back(v);
        }
      }
      std::vector<float> want(frames);
      for (std::size_t i = 0; i < frames; ++i) {
        double sum = 0.0;
        for (std::size_t ch = 0; ch < channels; ++ch) sum += values[i * channels + ch];
        want[i] = static_cast<float>(sum * (1.0 / channels));
      }
      const std::string bytes = wav(f, d);
      const Audio from_file = read_bytes(dir, "formula.wav", bytes);
      const Audio from_bytes = gmg::audio::parse_wav(bytes, "formula.wav");
      for (const Audio* a : {&from_file, &from_bytes}) {
        ASSERT_EQ(a->samples.size(), frames);
        // NOLINTNEXTLINE(bugprone-suspicious-memory-comparison): bit for bit is the claim
        EXPECT_EQ(std::memcmp(a->samples.data(), want.data(), frames * sizeof(float)), 0)
            << "tag " << c.tag << ", " << c.bits << " bits, " << channels << " channels";
      }
    }
}

// A NaN far into the file, past the first stretch decoded at a time, is found and named.
TEST(Wav, NotFiniteSampleFarIntoTheFile) {
  TempDir dir;
  Fmt f;
  f.tag = 3;
  f.bits = 32;
  f.channels = 2;
  std::string d;
  for (int i = 0; i < 2 * 10000; ++i) f32(d, i == 2 * 9000 + 1 ? std::numeric_limits<float>::infinity() : 0.25f);
  expect_wav_error(dir, "late.wav", wav(f, d),
                   {"byte " + std::to_string(44 + 4 * (2 * 9000 + 1)), "sample 9000 (channel 1) is infinite"});
}

TEST(Wav, SampleRates) {
  TempDir dir;
  for (std::uint32_t rate : {44100u, 48000u, 16000u, 8000u, 22050u}) {
    Fmt f;
    f.rate = rate;
    std::string d;
    for (int i = 0; i < 100; ++i) le16(d, static_cast<std::uint16_t>(i * 10));
    Audio a = read_bytes(dir, "r" + std::to_string(rate) + ".wav", wav(f, d));
    EXPECT_EQ(a.sample_rate, static_cast<int>(rate));
    ASSERT_EQ(a.samples.size(), 100u);
    EXPECT_FLOAT_EQ(a.samples[99], 990.0f / 32768.0f);
    EXPECT_DOUBLE_EQ(a.duration(), 100.0 / rate);
  }
}

TEST(Wav, UnknownAndOddChunksAreSkipped) {
  TempDir dir;
  std::string d;
  le16(d, 16384);
  le16(d, 8192);
  // An odd-sized LIST chunk (with its pad byte) before fmt, a 'fact' chunk
  // between, and data before fmt (legal RIFF order).
  const std::string bytes = riff(chunk("LIST", "abc") + chunk("data", d) + chunk("fact", std::string(4, '\x02')) +
                                 fmt_chunk(Fmt{}) + chunk("junk", "12345"));
  Audio a = read_bytes(dir, "chunks.wav", bytes);
  ASSERT_EQ(a.samples.size(), 2u);
  EXPECT_FLOAT_EQ(a.samples[0], 0.5f);
  EXPECT_FLOAT_EQ(a.samples[1], 0.25f);
}

TEST(WavRealData, Float32File) {
  GMG_REQUIRE_SHARED_DATA();
  Audio a = gmg::audio::read_wav(gmg::testing::shared_data_dir() + "/beat2_scott/2_scott_0_1_1.wav");
  EXPECT_EQ(a.sample_rate, 16000);
  EXPECT_EQ(a.samples.size(), 1025558u);  // 4102232 data bytes / 4
  EXPECT_NEAR(a.duration(), 64.1, 0.01);
  float peak = 0.0f;
  for (float v : a.samples) peak = std::max(peak, std::fabs(v));
  EXPECT_GT(peak, 0.05f);
  EXPECT_LE(peak, 1.0f);
}

TEST(WavRealData, Pcm16File) {
  GMG_REQUIRE_SHARED_DATA();
  Audio a = gmg::audio::read_wav(gmg::testing::shared_data_dir() + "/beat2_scott/2_scott_0_2_2.wav");
  EXPECT_EQ(a.sample_rate, 16000);
  EXPECT_EQ(a.samples.size(), 992000u);  // 1984000 data bytes / 2
  EXPECT_NEAR(a.duration(), 62.0, 0.01);
  // Every sample is a multiple of 1 / 32768.
  for (std::size_t i = 0; i < a.samples.size(); i += 997) {
    const double q = a.samples[i] * 32768.0;
    ASSERT_EQ(q, std::round(q)) << i;
  }
}

TEST(Wav, SampleRateFromFourTo192Kilohertz) {
  TempDir dir;
  const std::string d(8, '\x01');
  for (std::uint32_t rate : {4000u, 192000u}) {
    Fmt f;
    f.rate = rate;
    EXPECT_EQ(read_bytes(dir, "ok.wav", wav(f, d)).sample_rate, static_cast<int>(rate));
  }
  for (std::uint32_t rate : {1u, 3999u, 192001u, 10000019u, 2147483647u, 4294967295u}) {
    Fmt f;
    f.rate = rate;
    expect_wav_error(dir, "rate.wav", wav(f, d),
                     {"byte 24", "sample rate " + std::to_string(rate) + " Hz is outside the 4000 to 192000 Hz"});
  }
}

TEST(Wav, ResamplerRefusesAFilterBeyondTheLimit) {
  // 1000003 Hz shares no factor with 22050: 20 * 1000003 + 1 taps.
  EXPECT_EQ(error_of([] { gmg::audio::resample_poly(std::vector<float>(4, 0.f), 1000003, 22050); }),
            "resample_poly: resampling from 1000003 Hz to 22050 Hz needs a filter of 20000061 taps (at most 3840001)");
  // The highest rate the reader accepts, coprime or not, stays within it.
  EXPECT_EQ(gmg::audio::resample_poly(std::vector<float>(100, 0.f), 191999, 22050).size(), 12u);
}

}  // namespace
