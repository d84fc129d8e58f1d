// Tests of audio/wav: byte-precise errors naming the file.
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

TEST(Wav, Errors) {
  TempDir dir;
  std::string d;
  le16(d, 1000);
  le16(d, 2000);
  expect_wav_error(dir, "empty.wav", "", {"byte 0", "empty"});
  expect_wav_error(dir, "short.wav", "RIFF", {"byte 4"});
  expect_wav_error(dir, "text.wav", "hello, this is not audio at all", {"byte 0", "RIFF"});
  {
    std::string avi = wav(Fmt{}, d);
    avi.replace(8, 4, "AVI ");
    expect_wav_error(dir, "avi.wav", avi, {"byte 8", "WAVE"});
  }
  expect_wav_error(dir, "nodata.wav", riff(fmt_chunk(Fmt{}) + chunk("LIST", "abcd")), {"byte", "no 'data' chunk"});
  expect_wav_error(dir, "nofmt.wav", riff(chunk("data", d)), {"byte", "no 'fmt ' chunk"});
  {
    // The data chunk declares 1000 bytes; 4 are present. The data chunk
    // header is at byte 12 + 24 (RIFF header + fmt chunk).
    std::string lying = riff(fmt_chunk(Fmt{}) + "data");
    le32(lying, 1000);
    lying += d;
    expect_wav_error(dir, "lying.wav", lying, {"byte 36", "declares 1000 bytes", "only 4"});
    // A streaming writer's 0xFFFFFFFF must not hang or overflow.
    std::string stream = riff(fmt_chunk(Fmt{}) + "data");
    le32(stream, 0xFFFFFFFFu);
    stream += d;
    expect_wav_error(dir, "ffff.wav", stream, {"byte 36", "declares 4294967295 bytes"});
    // Same for an unknown chunk before the data.
    std::string junk = riff(fmt_chunk(Fmt{}) + "junk");
    le32(junk, 0xFFFFFFFFu);
    expect_wav_error(dir, "junk.wav", junk, {"byte 36", "'junk'"});
  }
  expect_wav_error(dir, "zero.wav", wav(Fmt{}, ""), {"byte 36", "no samples"});
  {
    Fmt f;
    f.channels = 2;  // one 16-bit sample is half a frame
    expect_wav_error(dir, "halfframe.wav", wav(f, std::string(2, '\0')), {"no samples"});
  }
  {
    Fmt f;
    f.tag = 3;
    f.bits = 32;
    std::string fd;
    f32(fd, 0.5f);
    f32(fd, std::numeric_limits<float>::quiet_NaN());
    // sample 1 starts at byte 44 + 4
    expect_wav_error(dir, "nan.wav", wav(f, fd), {"byte 48", "NaN"});
    fd.clear();
    f32(fd, std::numeric_limits<float>::infinity());
    expect_wav_error(dir, "inf.wav", wav(f, fd), {"byte 44", "infinite"});
    f.bits = 64;
    fd.clear();
    f64(fd, std::numeric_limits<double>::quiet_NaN());
    expect_wav_error(dir, "nan64.wav", wav(f, fd), {"byte 44", "NaN"});
  }
  {
    Fmt f;
    f.bits = 12;
    expect_wav_error(dir, "bits12.wav", wav(f, d), {"byte 34", "bit depth 12"});
    f.tag = 3;
    f.bits = 16;
    expect_wav_error(dir, "float16.wav", wav(f, d), {"byte 34", "bit depth 16"});
    f.tag = 2;  // MS ADPCM
    expect_wav_error(dir, "adpcm.wav", wav(f, d), {"byte 20", "format tag 0x0002"});
  }
  {
    Fmt f;
    f.channels = 0;
    expect_wav_error(dir, "nochan.wav", wav(f, d), {"byte 22", "zero channels"});
    f.channels = 1;
    f.rate = 0;
    expect_wav_error(dir, "norate.wav", wav(f, d), {"byte 24", "zero sample rate"});
  }
  {
    std::string short_fmt = "RIFF";
    le32(short_fmt, 100);
    short_fmt += "WAVEfmt ";
    le32(short_fmt, 16);
    short_fmt += "abcd";  // fmt body cut short
    expect_wav_error(dir, "shortfmt.wav", short_fmt, {"byte 12", "'fmt ' chunk declares 16 bytes"});
  }
}

TEST(Wav, UnreadableFileUsesTheReaderWording) {
  TempDir dir;
  const std::string missing = dir.file("does_not_exist.wav");
  EXPECT_EQ(error_of([&] { gmg::audio::read_wav(missing); }), missing + ": cannot open (No such file or directory)");
  const std::string folder = dir.file("folder.wav");
  std::filesystem::create_directory(folder);
  EXPECT_EQ(error_of([&] { gmg::audio::read_wav(folder); }), folder + ": is a folder, not a file");
}

TEST(Wav, ParseWavNamesTheLabel) {
  Fmt f;
  const Audio a = gmg::audio::parse_wav(wav(f, std::string(4, '\0')), "in memory");
  EXPECT_EQ(a.samples.size(), 2u);
  EXPECT_EQ(error_of([] { gmg::audio::parse_wav("RIFX", "label.wav"); }),
            "label.wav: byte 4: file ends after 4 bytes, inside the RIFF header");
}

}  // namespace
