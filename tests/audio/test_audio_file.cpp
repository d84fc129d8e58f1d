// Tests of audio/audio_file: WAV through read_wav, other formats through aubio. The FLAC, MP3 and
// OGG files are made at test time with the ffmpeg tool (skipped when it is absent), so no binary
// audio lives in the repository.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "audio/audio_file.h"
#include "audio/onset.h"
#include "audio/wav.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "tests/core/helpers.h"
#include "tests/test_support.h"

namespace {

using gmg::audio::Audio;
using gmg::testing::error_of;
using gmg::testing::TempDir;

bool have_ffmpeg() { return std::system("ffmpeg -version > /dev/null 2>&1") == 0; }

// Converts `in` to `out` with ffmpeg (the format from out's extension, plus `options`).
void ffmpeg(const std::string& in, const std::string& out, const std::string& options = "") {
  const std::string cmd = "ffmpeg -hide_banner -loglevel error -y -i '" + in + "' " + options + " '" + out + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
}

// Two seconds of a 440 Hz tone with a click every half second, PCM16: what a FLAC keeps exactly.
Audio tone(int rate) {
  Audio a;
  a.sample_rate = rate;
  a.samples.resize(static_cast<std::size_t>(2 * rate));
  for (std::size_t i = 0; i < a.samples.size(); ++i) {
    double v = 0.3 * std::sin(2 * M_PI * 440.0 * static_cast<double>(i) / rate);
    if (i % static_cast<std::size_t>(rate / 2) < 40) v += 0.5;
    a.samples[i] = static_cast<float>(std::round(v * 32768.0) / 32768.0);
  }
  return a;
}

double rms(const std::vector<float>& x) {
  double s = 0;
  for (float v : x) s += static_cast<double>(v) * v;
  return std::sqrt(s / static_cast<double>(x.size()));
}

TEST(AudioFile, WavGoesThroughTheExactReader) {
  TempDir dir;
  const std::string wav = dir.file("t.WAV");
  gmg::audio::write_wav_pcm16(wav, tone(16000));
  EXPECT_TRUE(gmg::audio::is_wav_path(wav));
  EXPECT_EQ(gmg::audio::read_audio(wav).samples, gmg::audio::read_wav(wav).samples);
  // A WAV read_wav rejects is not handed to another decoder: its error stands.
  gmg::testing::write_text(dir.file("bad.wav"), std::string("RIFF\x04\x00\x00\x00WAVX", 12));
  EXPECT_EQ(error_of([&] { gmg::audio::read_audio(dir.file("bad.wav")); }),
            error_of([&] { gmg::audio::read_wav(dir.file("bad.wav")); }));
}

TEST(AudioFile, UnreadableAndUndecodableFilesNameTheFile) {
  TempDir dir;
  EXPECT_EQ(error_of([&] { gmg::audio::read_audio(dir.file("gone.flac")); }),
            dir.file("gone.flac") + ": cannot open (No such file or directory)");
  EXPECT_EQ(error_of([&] { gmg::audio::read_audio(dir.path().string()); }),
            dir.path().string() + ": is a folder, not a file");
  // Binary that is no known format: the decoder's reason, on one line.
  gmg::testing::write_text(dir.file("noise.flac"), std::string("\x01\x02\x03\x04\x05\x06\x07\x08\x09\x0e", 10));
  const std::string msg = error_of([&] { gmg::audio::read_audio(dir.file("noise.flac")); });
  EXPECT_EQ(msg.rfind(dir.file("noise.flac") + ": cannot decode as audio", 0), 0u) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  EXPECT_EQ(msg.find("RIFF"), std::string::npos) << "a WAV reader's complaint about a file that is no WAV: " << msg;
  std::string bytes(4096, '\0');  // binary without any format's signature
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>(((i * 2654435761u >> 13) & 0x7F) | 0x01);
  gmg::testing::write_text(dir.file("noise.bin"), bytes);
  const std::string bin = error_of([&] { gmg::audio::read_audio(dir.file("noise.bin")); });
  EXPECT_EQ(bin.rfind(dir.file("noise.bin") + ": cannot decode as audio", 0), 0u) << bin;
  EXPECT_EQ(bin.find("RIFF"), std::string::npos) << bin;
}

// What a file holds decides how it is read, and a file that is not audio says what it is instead
// of how a WAV or the decoder fails on it.
TEST(AudioFile, FilesThatAreNotAudioSayWhatTheyAre) {
  TempDir dir;
  const auto refused = [&](const std::string& name, const std::string& bytes) {
    gmg::testing::write_text(dir.file(name), bytes);
    return error_of([&] { gmg::audio::read_audio(dir.file(name)); });
  };
  const std::string hint = " (give the speech as WAV, FLAC, MP3, OGG, M4A, ...)";
  EXPECT_EQ(refused("words.wav", "0\t1\thello\n"), dir.file("words.wav") + ": is not audio: it is a text file" + hint);
  EXPECT_EQ(refused("words.flac", "0\t1\thello\n"),
            dir.file("words.flac") + ": is not audio: it is a text file" + hint);
  EXPECT_EQ(refused("take.wav", "HIERARCHY\nROOT hips\n"),
            dir.file("take.wav") + ": is not audio: it is a BVH motion file" + hint);
  EXPECT_EQ(refused("ref.mp3", std::string("GMGRAPH\0\x03\0\0\0", 12)),
            dir.file("ref.mp3") + ": is not audio: it is a gmg graph file" + hint);
  EXPECT_EQ(refused("t.wav", "{\"segments\": []}"), dir.file("t.wav") + ": is not audio: it is JSON text" + hint);
  EXPECT_EQ(refused("empty.mp3", ""), dir.file("empty.mp3") + ": is empty (0 bytes), not audio");
  // Bytes that say nothing, named .wav: the WAV reader's own byte-precise error.
  const std::string raw = refused("raw.wav", std::string("\x01\x00\x02\x00\x03\x00\x04\x00\x05\x00\x06\x00", 12));
  EXPECT_EQ(raw.rfind(dir.file("raw.wav") + ": byte 0: ", 0), 0u) << raw;
}

TEST(AudioFile, SniffingNamesTheFormats) {
  using gmg::audio::sniff_content;
  EXPECT_EQ(sniff_content(std::string("RIFF\x24\0\0\0WAVEfmt ", 16)).name, "a WAV file");
  EXPECT_TRUE(sniff_content(std::string("fLaC\0\0\0\x22", 8)).audio);
  EXPECT_EQ(sniff_content("ID3\x04").name, "an MP3 file");
  EXPECT_EQ(sniff_content("\xFF\xFB\x90\x64").name, "an MP3 file");
  EXPECT_EQ(sniff_content("\xFF\xF1\x50\x80").name, "an AAC (ADTS) file");
  EXPECT_EQ(sniff_content(std::string("\0\0\0\x20"
                                      "ftypM4A ",
                                      12))
                .name,
            "an MP4/M4A file");
  EXPECT_EQ(sniff_content(std::string("OggS\0\x02", 6)).name, "an Ogg file");
  EXPECT_EQ(sniff_content("\xEF\xBB\xBFHIERARCHY\r\n").name, "a BVH motion file");
  EXPECT_EQ(sniff_content("PK\x03\x04").name, "a ZIP archive (an .npz?)");
  EXPECT_EQ(sniff_content("File type = \"ooTextFile\"").name, "a Praat TextGrid");
  EXPECT_EQ(sniff_content("\x01\x02\x03\x04").name, "");
  EXPECT_FALSE(sniff_content("hello").audio);
}

// An M4A cut in half has lost its index (written last): the decoder's reason leads, not the
// complaint of the WAV reader aubio tries after it ("could not find RIFF header").
TEST(AudioFile, ACutM4aSaysWhyItCannotBeDecoded) {
  if (!have_ffmpeg()) GTEST_SKIP() << "the ffmpeg tool is absent";
  TempDir dir;
  gmg::audio::write_wav_pcm16(dir.file("t.wav"), tone(16000));
  ffmpeg(dir.file("t.wav"), dir.file("t.m4a"), "-c:a aac");
  const std::string whole = gmg::read_file_bytes(dir.file("t.m4a"));
  gmg::testing::write_text(dir.file("cut.m4a"), whole.substr(0, whole.size() / 2));
  const std::string msg = error_of([&] { gmg::audio::read_audio(dir.file("cut.m4a")); });
  EXPECT_EQ(msg, dir.file("cut.m4a") +
                     ": cannot decode an MP4/M4A file (the decoder: moov atom not found); the file may be cut short or "
                     "damaged");
  EXPECT_EQ(msg.find("RIFF"), std::string::npos) << msg;
}

TEST(AudioFile, AnMp3NamedWavIsDecodedWithAWarning) {
  if (!have_ffmpeg()) GTEST_SKIP() << "the ffmpeg tool is absent";
  TempDir dir;
  gmg::audio::write_wav_pcm16(dir.file("t.wav"), tone(44100));
  ffmpeg(dir.file("t.wav"), dir.file("t.mp3"), "-b:a 128k");
  std::filesystem::rename(dir.file("t.mp3"), dir.file("really_mp3.wav"));
  std::vector<std::string> warnings;
  const Audio a = gmg::audio::read_audio(dir.file("really_mp3.wav"), &warnings);
  EXPECT_NEAR(a.duration(), 2.0, 0.1);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], dir.file("really_mp3.wav") + ": is an MP3 file, not a WAV; decoded as such");
}

TEST(AudioFile, FlacStereoAndMonoGiveTheWavsSamplesExactly) {
  if (!have_ffmpeg()) GTEST_SKIP() << "the ffmpeg tool is absent";
  TempDir dir;
  const std::string wav = dir.file("t.wav");
  gmg::audio::write_wav_pcm16(wav, tone(22050));
  const Audio expected = gmg::audio::read_wav(wav);
  ffmpeg(wav, dir.file("t.flac"));
  // Both channels the signal (pan, not -ac 2, which mixes mono in at -3 dB): their mean is the signal.
  ffmpeg(wav, dir.file("t2.flac"), "-af 'pan=stereo|c0=c0|c1=c0'");
  for (const std::string name : {"t.flac", "t2.flac"}) {
    const Audio a = gmg::audio::read_audio(dir.file(name));
    EXPECT_EQ(a.sample_rate, 22050) << name;
    EXPECT_EQ(a.samples, expected.samples) << name;
  }
}

TEST(AudioFile, LossyFormatsDecodeToTheSameSoundNearly) {
  if (!have_ffmpeg()) GTEST_SKIP() << "the ffmpeg tool is absent";
  TempDir dir;
  const std::string wav = dir.file("t.wav");
  gmg::audio::write_wav_pcm16(wav, tone(44100));
  const Audio expected = gmg::audio::read_wav(wav);
  // MP3 (and OGG Vorbis when this ffmpeg has the encoder): the length within two MP3 frames of
  // padding, the loudness within 10%.
  ffmpeg(wav, dir.file("t.mp3"), "-b:a 192k");
  std::vector<std::string> files = {"t.mp3"};
  if (std::system(("ffmpeg -hide_banner -loglevel error -y -i '" + wav + "' -c:a libvorbis '" + dir.file("t.ogg") +
                   "' 2> /dev/null")
                      .c_str()) == 0)
    files.push_back("t.ogg");
  for (const std::string& name : files) {
    const Audio a = gmg::audio::read_audio(dir.file(name));
    EXPECT_EQ(a.sample_rate, 44100) << name;
    EXPECT_NEAR(a.duration(), expected.duration(), 2 * 1152.0 / 44100) << name;
    EXPECT_NEAR(rms(a.samples), rms(expected.samples), 0.1 * rms(expected.samples)) << name;
  }
}

TEST(AudioFile, AFlacCopyOfASharedRecordingFindsTheSameOnsets) {
  GMG_REQUIRE_SHARED_DATA();
  if (!have_ffmpeg()) GTEST_SKIP() << "the ffmpeg tool is absent";
  // 2_scott_0_2_2.wav is PCM16, which FLAC holds losslessly (the float WAV of 0_1_1 it would not).
  const std::string wav = gmg::testing::shared_data_dir() + "/beat2_scott/2_scott_0_2_2.wav";
  TempDir dir;
  const std::string flac = dir.file("2_scott_0_2_2.flac");
  ffmpeg(wav, flac);
  const Audio from_wav = gmg::audio::read_wav(wav), from_flac = gmg::audio::read_audio(flac);
  ASSERT_EQ(from_flac.sample_rate, from_wav.sample_rate);
  EXPECT_EQ(from_flac.samples, from_wav.samples);
  const gmg::audio::OnsetParams params;
  const auto a = gmg::audio::detect_onsets(from_wav, params), b = gmg::audio::detect_onsets(from_flac, params);
  EXPECT_EQ(b.onset_frames, a.onset_frames);
  EXPECT_EQ(b.peak_frames, a.peak_frames);
  EXPECT_EQ(b.onset_frames.size(), 128u);  // the count librosa finds (data README)
}

}  // namespace
