// Hostile input, cases 20 to 22 (tests/cli/hostile_input.h): speech that cannot be speech, a
// reference whose audio and motion disagree in length, and damaged compressed audio.
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli/hostile_input.h"

namespace gmg::hostile {
namespace {

// ---- Speech that cannot be speech ----------------------------------------------------------

// `seconds` at 8 kHz of silence (amplitude 0) or of a steady 220 Hz tone.
void write_wav_of(const std::string& path, double seconds, double amplitude) {
  audio::Audio a;
  a.sample_rate = 8000;
  a.samples.resize(static_cast<std::size_t>(seconds * a.sample_rate));
  for (std::size_t i = 0; i < a.samples.size(); ++i)
    a.samples[i] = static_cast<float>(amplitude * std::sin(2.0 * M_PI * 220.0 * static_cast<double>(i) / 8000.0));
  audio::write_wav_pcm16(path, a);
}

// 20: silence, 10 ms of audio and a steady tone are refused for reenact, build and evaluate,
// naming the file and the threshold; --allow-silence takes them as they are.
TEST_F(HostileInput, Case20SilentOrShortAudioIsRefusedUnlessAllowed) {
  copy({"ref.gmg", "ref.bvh"});
  write_wav_of(at("silence.wav"), 12.0, 0.0);
  write_wav_of(at("click.wav"), 0.01, 0.5);
  write_wav_of(at("tone.wav"), 12.0, 0.3);
  const auto before = snapshot(work_.path());
  const std::string allow = "--allow-silence uses it anyway";
  expect_refused(gmg({"reenact", "--graph", "ref.gmg", "--audio", "silence.wav", "-o", "out.bvh"}), "silence.wav",
                 "is silent: every sample is zero, and speech needs -60 dB or more; " + allow);
  expect_refused(gmg({"reenact", "--graph", "ref.gmg", "--audio", "click.wav", "-o", "out.bvh"}), "click.wav",
                 "holds 0.01 s of audio, too short to be speech (gmg needs at least 0.5 s; " + allow);
  expect_refused(gmg({"reenact", "--graph", "ref.gmg", "--audio", "tone.wav", "-o", "out.bvh"}), "tone.wav",
                 "has no onset in 12.0 s of audio: a steady sound or noise, not speech");
  expect_refused(gmg({"build", "--motion", "ref.bvh", "--audio", "click.wav", "-o", "g.gmg"}), "click.wav",
                 "too short to be speech");
  expect_refused(gmg({"build", "--motion", "ref.bvh", "--audio", "silence.wav", "-o", "g.gmg"}), "silence.wav",
                 "is silent");
  expect_refused(gmg({"reenact", "--reference-motion", "ref.bvh", "--reference-audio", "silence.wav", "--audio",
                      "tone.wav", "-o", "out.bvh"}),
                 "silence.wav", "is silent");
  expect_refused(gmg({"evaluate", "--generated", "ref.bvh", "--audio", "click.wav"}), "click.wav",
                 "too short to be speech");
  expect_unchanged(before);
  const ChildRun allowed =
      gmg({"reenact", "--graph", "ref.gmg", "--audio", "silence.wav", "-o", "out.bvh", "--allow-silence"});
  EXPECT_EQ(allowed.code, 0) << allowed.err;
  EXPECT_EQ(bvh_read(at("out.bvh")).frame_count, 12 * 30);
}

// 21: a reference whose audio and motion lengths differ by more than a second builds, with a
// warning naming both files; so does an evaluation of a motion against speech of another length.
TEST_F(HostileInput, Case21DurationMismatchIsAWarningNamingBoth) {
  copy({"ref.bvh", "ref.wav", "new.wav"});
  const ChildRun r = gmg({"build", "--motion", "ref.bvh", "--audio", "new.wav", "-o", "g.gmg"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(r.err, "gmg: warning: new.wav: lasts 2.0 s but its motion ref.bvh lasts 4.0 s (2.0 s apart)"))
      << r.err;
  const ChildRun same = gmg({"build", "--motion", "ref.bvh", "--audio", "ref.wav", "-o", "h.gmg"});
  EXPECT_EQ(same.code, 0) << same.err;
  EXPECT_FALSE(contains(same.err, "warning")) << same.err;
  const ChildRun e = gmg({"evaluate", "--generated", "ref.bvh", "--audio", "new.wav", "--json"});
  EXPECT_EQ(e.code, 0) << e.err;
  EXPECT_TRUE(contains(e.err, "gmg: warning: new.wav: lasts 2.0 s but the motion ref.bvh lasts 4.0 s")) << e.err;
}

// 22: an MP3 or FLAC cut short or with damaged bytes decodes with one warning naming the file
// (what the decoder reported, how much of the declared length came out); the decoder's own lines
// never reach the terminal.
TEST_F(HostileInput, Case22DamagedMp3AndFlacWarnNamingTheFile) {
  if (!have_ffmpeg()) GTEST_SKIP() << "the ffmpeg tool is absent: no MP3 or FLAC to damage";
  copy({"ref.gmg"});
  SynthSpec spec;
  spec.duration_s = 6.0;
  spec.seed = 9;
  synth_write(synth_speaker(spec), work_.path().string(), "speech");
  for (const char* ext : {"mp3", "flac"}) {
    const std::string cmd = "cd '" + work_.path().string() +
                            "' && ffmpeg -hide_banner -loglevel error -y -i speech.wav speech." + ext + " 2> /dev/null";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    const std::string whole = read_file_bytes(at(std::string("speech.") + ext));
    write_text(at(std::string("cut.") + ext), whole.substr(0, whole.size() / 2));
    std::string damaged = whole;
    for (std::size_t k = whole.size() / 4; k < whole.size() * 3 / 4; k += 7)
      damaged[k] = static_cast<char>(damaged[k] * 31 + 7);
    write_text(at(std::string("bad.") + ext), damaged);
    for (const std::string stem : {"cut", "bad"}) {
      const std::string name = stem + "." + ext;
      const ChildRun r = gmg({"reenact", "--graph", "ref.gmg", "--audio", name, "-o", stem + ext + ".bvh"});
      expect_own_lines_only(r);
      EXPECT_TRUE(contains(r.err, name + ": damaged: ")) << name << ": " << r.err;
      if (r.code == 0) {
        EXPECT_TRUE(contains(r.err, "gmg: warning: " + name + ": damaged: ")) << r.err;
        EXPECT_TRUE(contains(r.err, "the audio may be incomplete or have gaps")) << r.err;
      } else {  // so damaged that what it decoded cannot be speech: the damage leads
        expect_refused(r, name + ": damaged: ", "and what it decoded ");
      }
    }
    const ChildRun whole_run = gmg({"reenact", "--graph", "ref.gmg", "--audio", std::string("speech.") + ext, "-o",
                                    std::string("whole") + ext + ".bvh"});
    EXPECT_EQ(whole_run.code, 0) << whole_run.err;
    EXPECT_EQ(whole_run.err, "") << "an undamaged file has nothing to warn about";
  }
}

}  // namespace
}  // namespace gmg::hostile
