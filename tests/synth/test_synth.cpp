// Tests of engine/synth: the procedural synthetic speaker used by the demo, tests and benchmarks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include "audio/onset.h"
#include "audio/wav.h"
#include "engine/core/error.h"
#include "engine/motion/bvh.h"
#include "engine/motion/motion.h"
#include "engine/synth/synth.h"
#include "engine/synth/synth_internal.h"
#include "tests/test_support.h"
#include "text/keywords.h"
#include "text/transcript.h"

namespace {

using gmg::SynthClip;
using gmg::SynthSpec;

SynthSpec spec_of(double duration, std::uint64_t seed, double style = 0.0) {
  SynthSpec s;
  s.duration_s = duration;
  s.seed = seed;
  s.style = style;
  return s;
}

// ---------------------------------------------------------------------------------------------

TEST(Synth, SameSpecGivesIdenticalOutputAndSeedsDiffer) {
  const SynthClip a = gmg::synth_speaker(spec_of(8.0, 42));
  const SynthClip b = gmg::synth_speaker(spec_of(8.0, 42));
  const SynthClip c = gmg::synth_speaker(spec_of(8.0, 43));
  const std::string bvh_a = gmg::bvh_format(a.motion);
  EXPECT_EQ(bvh_a, gmg::bvh_format(b.motion));
  EXPECT_EQ(a.audio.samples, b.audio.samples);
  ASSERT_EQ(a.words.size(), b.words.size());
  for (std::size_t i = 0; i < a.words.size(); ++i) {
    EXPECT_EQ(a.words[i].text, b.words[i].text);
    EXPECT_EQ(a.words[i].start, b.words[i].start);
    EXPECT_EQ(a.words[i].end, b.words[i].end);
  }
  EXPECT_NE(bvh_a, gmg::bvh_format(c.motion));
  EXPECT_NE(a.audio.samples, c.audio.samples);
  // Style changes the speaker too.
  const SynthClip d = gmg::synth_speaker(spec_of(8.0, 42, 0.9));
  EXPECT_NE(bvh_a, gmg::bvh_format(d.motion));
}

TEST(Synth, SizesAndTranscriptShape) {
  struct Case {
    double duration, fps;
    int rate;
  };
  for (const Case& k :
       {Case{10.01, 30.0, 16000}, Case{7.77, 25.0, 22050}, Case{0.5, 60.0, 8000}, Case{13.333, 30.0, 44100}}) {
    SynthSpec s = spec_of(k.duration, 7);
    s.fps = k.fps;
    s.sample_rate = k.rate;
    const SynthClip clip = gmg::synth_speaker(s);
    SCOPED_TRACE(k.duration);
    EXPECT_EQ(clip.motion.frame_count, std::lround(k.duration * k.fps));
    EXPECT_EQ(clip.motion.rotations.size(),
              static_cast<std::size_t>(clip.motion.frame_count * clip.motion.joint_count()));
    EXPECT_EQ(clip.motion.translations.size(), clip.motion.rotations.size());
    EXPECT_DOUBLE_EQ(clip.motion.fps, k.fps);
    EXPECT_EQ(clip.audio.sample_rate, k.rate);
    EXPECT_EQ(static_cast<long>(clip.audio.samples.size()), std::lround(k.duration * k.rate));
    for (float x : clip.audio.samples) ASSERT_TRUE(x >= -1.0f && x < 1.0f);
    gmg::motion_check_finite(clip.motion, "synth");
    for (std::size_t i = 0; i < clip.words.size(); ++i) {
      const gmg::text::Word& w = clip.words[i];
      EXPECT_FALSE(w.text.empty());
      EXPECT_GE(w.start, 0.0);
      EXPECT_LT(w.start, w.end);
      EXPECT_LE(w.end, k.duration);
      if (i > 0) {
        EXPECT_LE(clip.words[i - 1].end, w.start);  // sorted, not overlapping
      }
    }
    for (std::size_t i = 1; i < clip.syllables.size(); ++i)
      EXPECT_LT(clip.syllables[i - 1].time, clip.syllables[i].time);
    for (std::size_t i = 1; i < clip.phrases.size(); ++i)
      EXPECT_GE(clip.phrases[i].start - clip.phrases[i - 1].end, 0.3 - 1e-9);
  }
  // A 30 s clip has a realistic speech plan: phrases, ~4-5 syllables/s inside them.
  const SynthClip clip = gmg::synth_speaker(spec_of(30.0, 3));
  ASSERT_GE(clip.phrases.size(), 5u);
  double speech = 0;
  for (const auto& p : clip.phrases) {
    EXPECT_GE(p.end - p.start, 0.5);
    EXPECT_LE(p.end - p.start, 4.0 + 1e-9);
    speech += p.end - p.start;
  }
  const double rate = clip.syllables.size() / speech;
  std::printf("30 s clip: %zu phrases, %zu words, %zu syllables, %.2f syllables/s of speech\n", clip.phrases.size(),
              clip.words.size(), clip.syllables.size(), rate);
  EXPECT_GT(rate, 3.5);
  EXPECT_LT(rate, 5.5);
}

TEST(Synth, Skeleton) {
  const gmg::Skeleton base = gmg::synth_skeleton();
  EXPECT_GE(base.joint_count(), 18);
  EXPECT_LE(base.joint_count(), 25);
  for (int hint : {0, 10, 25, 60, 65, 80, 100}) {
    const gmg::Skeleton sk = gmg::synth_skeleton(hint);
    SCOPED_TRACE(hint);
    EXPECT_EQ(sk.joint_count(), std::max(hint, base.joint_count()));
    std::set<std::string> names;
    for (int j = 0; j < sk.joint_count(); ++j) {
      const gmg::Joint& joint = sk.joints[static_cast<std::size_t>(j)];
      EXPECT_TRUE(names.insert(joint.name).second) << "duplicate joint " << joint.name;
      EXPECT_LT(joint.parent, j);
      if (j > 0) {
        EXPECT_GE(joint.parent, 0);
        EXPECT_EQ(joint.channels.size(), 3u);
      }
      bool leaf = true;
      for (const gmg::Joint& other : sk.joints)
        if (other.parent == j) leaf = false;
      EXPECT_EQ(joint.has_end_site, leaf) << joint.name;
    }
    EXPECT_EQ(sk.joints[0].name, "Hips");
    ASSERT_EQ(sk.joints[0].channels.size(), 6u);
    EXPECT_EQ(sk.joints[0].channels[0], gmg::Channel::Xposition);
    EXPECT_EQ(sk.joints[0].channels[3], gmg::Channel::Zrotation);
    for (const char* n : {"Head", "LeftHand", "RightHand", "LeftForeArm", "RightArm", "LeftFoot"})
      EXPECT_GE(sk.find(n), 0) << n;
  }
  EXPECT_GE(gmg::synth_skeleton(60).joint_count(), 60);
  EXPECT_GE(gmg::synth_skeleton(60).find("RightHandIndex1"), 0);
  EXPECT_THROW(gmg::synth_skeleton(-1), gmg::Error);
  // A big skeleton moves its fingers and still generates cleanly.
  SynthSpec s = spec_of(3.0, 5);
  s.joint_count_hint = 60;
  const SynthClip clip = gmg::synth_speaker(s);
  EXPECT_EQ(clip.motion.joint_count(), 60);
  gmg::motion_check_finite(clip.motion, "synth");
}

TEST(Synth, InvalidSpecsThrow) {
  SynthSpec s;
  s.duration_s = 0;
  EXPECT_THROW(gmg::synth_speaker(s), gmg::Error);
  s = SynthSpec{};
  s.duration_s = std::nan("");
  EXPECT_THROW(gmg::synth_speaker(s), gmg::Error);
  s = SynthSpec{};
  s.fps = -30;
  EXPECT_THROW(gmg::synth_speaker(s), gmg::Error);
  s = SynthSpec{};
  s.sample_rate = 0;
  EXPECT_THROW(gmg::synth_speaker(s), gmg::Error);
  s = SynthSpec{};
  s.style = 1.5;
  EXPECT_THROW(gmg::synth_speaker(s), gmg::Error);
  s = SynthSpec{};
  s.joint_count_hint = -3;
  EXPECT_THROW(gmg::synth_speaker(s), gmg::Error);
}

TEST(Synth, WriteAndReadBack) {
  gmg::testing::TempDir tmp;
  SynthSpec s = spec_of(6.0, 11);
  s.joint_count_hint = 30;
  const SynthClip clip = gmg::synth_speaker(s);
  const std::string dir = (tmp.path() / "nested" / "out").string();
  gmg::synth_write(clip, dir, "speaker");

  const gmg::Motion m = gmg::bvh_read(dir + "/speaker.bvh");
  EXPECT_EQ(m.frame_count, clip.motion.frame_count);
  EXPECT_DOUBLE_EQ(m.fps, clip.motion.fps);
  std::string why;
  EXPECT_TRUE(gmg::skeletons_match(m.skeleton, clip.motion.skeleton, &why)) << why;
  double worst = 0;
  for (std::size_t i = 0; i < m.rotations.size(); ++i)
    worst = std::max(worst, gmg::rotation_angle_between(m.rotations[i], clip.motion.rotations[i]));
  EXPECT_LT(worst, 1e-3);  // BVH text keeps enough decimals

  const gmg::audio::Audio a = gmg::audio::read_wav(dir + "/speaker.wav");
  EXPECT_EQ(a.sample_rate, clip.audio.sample_rate);
  EXPECT_EQ(a.samples, clip.audio.samples);  // samples sit on the PCM16 grid: exact

  const std::vector<gmg::text::Word> words = gmg::text::read_transcript(dir + "/speaker.tsv");
  ASSERT_EQ(words.size(), clip.words.size());
  ASSERT_FALSE(words.empty());
  for (std::size_t i = 0; i < words.size(); ++i) {
    EXPECT_EQ(words[i].text, clip.words[i].text);
    EXPECT_NEAR(words[i].start, clip.words[i].start, 1e-9);
    EXPECT_NEAR(words[i].end, clip.words[i].end, 1e-9);
  }
  gmg::text::check_transcript_fits(words, a.duration(), dir + "/speaker.tsv");
}

TEST(Synth, KeywordsMatchTheLexicon) {
  const SynthClip clip = gmg::synth_speaker(spec_of(60.0, 9));
  const gmg::text::Lexicon lex = gmg::text::default_lexicon();
  const std::vector<gmg::text::KeywordEvent> events = gmg::text::detect_keywords(clip.words, lex);
  ASSERT_EQ(events.size(), clip.keyword_times.size());
  ASSERT_EQ(clip.keyword_gestures.size(), clip.keyword_times.size());
  for (std::size_t i = 0; i < events.size(); ++i) {
    EXPECT_DOUBLE_EQ(events[i].time, clip.keyword_times[i]);
    EXPECT_NE(clip.keyword_gestures[i], gmg::SynthGesture::None);
  }
  const double share = static_cast<double>(events.size()) / clip.words.size();
  std::printf("60 s clip: %zu words, %zu keywords (%.0f%%)\n", clip.words.size(), events.size(), 100 * share);
  EXPECT_GT(share, 0.08);
  EXPECT_LT(share, 0.25);
  // Every gesture kind occurs.
  for (gmg::SynthGesture g :
       {gmg::SynthGesture::Open, gmg::SynthGesture::Point, gmg::SynthGesture::Sweep, gmg::SynthGesture::Lift})
    EXPECT_NE(std::find(clip.keyword_gestures.begin(), clip.keyword_gestures.end(), g), clip.keyword_gestures.end());
}

// The grammar's words against the lexicon: a word it says with a gesture is a lexicon entry, a
// word it says without one is not, so a transcript's keywords are exactly the planned ones.
TEST(Synth, GrammarWordsAreKeywordsExactlyWhenTheyCarryAGesture) {
  const gmg::text::Lexicon lex = gmg::text::default_lexicon();
  const std::vector<gmg::synth_internal::GrammarWord> words = gmg::synth_internal::grammar_vocabulary();
  ASSERT_GT(words.size(), 100u);
  for (const auto& w : words) EXPECT_EQ(lex.contains(w.text), w.gesture != gmg::SynthGesture::None) << w.text;
}

// The transcript reads as sentences: each starts with a capital letter and ends with a full
// stop at the end of a phrase that ends a sentence; commas end the other phrases.
TEST(Synth, TranscriptIsSentences) {
  const SynthClip clip = gmg::synth_speaker(spec_of(60.0, 4));
  ASSERT_GE(clip.phrases.size(), 10u);
  std::size_t w = 0, sentences = 0;
  bool sentence_start = true;
  for (std::size_t k = 0; k < clip.phrases.size(); ++k) {
    const gmg::SynthPhrase& ph = clip.phrases[k];
    ASSERT_LT(w, clip.words.size());
    EXPECT_DOUBLE_EQ(clip.words[w].start, ph.start);
    if (sentence_start) {
      EXPECT_TRUE(std::isupper(static_cast<unsigned char>(clip.words[w].text[0]))) << clip.words[w].text;
    }
    while (w < clip.words.size() && clip.words[w].end <= ph.end) ++w;
    const std::string& last = clip.words[w - 1].text;
    if (k + 1 == clip.phrases.size()) break;  // the clip may end inside a sentence
    EXPECT_EQ(last.back(), ph.ends_sentence ? '.' : ',') << last;
    sentence_start = ph.ends_sentence;
    sentences += ph.ends_sentence ? 1 : 0;
    const double pause = clip.phrases[k + 1].start - ph.end;
    if (ph.ends_sentence) {
      EXPECT_GE(pause, 0.8 - 1e-9);
      EXPECT_LE(pause, 2.4 + 1e-9);
    } else {
      EXPECT_GE(pause, 0.3 - 1e-9);
      EXPECT_LE(pause, 0.45 + 1e-9);
    }
  }
  EXPECT_GE(sentences, 8u);
}

// The detector (librosa's onset_detect with backtracking) marks an onset at the local minimum
// of the onset envelope before its peak. With a centred 2048-sample (93 ms) window the envelope
// starts to rise about half a window before a burst, so backtracked onsets usually lead the burst
// by 0-60 ms (sometimes up to ~150 ms); the envelope peaks themselves sit within 50 ms of it.
TEST(Synth, OnsetsFollowStressedSyllables) {
  int total_stressed = 0, total_within50 = 0, total_within_lead = 0, total_peak = 0;
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const double style = seed == 3 ? 1.0 : 0.0;
    const SynthClip clip = gmg::synth_speaker(spec_of(20.0, seed, style));
    const gmg::audio::OnsetAnalysis an = gmg::audio::detect_onsets(clip.audio, gmg::audio::OnsetParams{});
    const std::vector<double> onsets = an.onset_times();
    std::vector<double> peaks;
    for (int f : an.peak_frames) peaks.push_back(f * 512.0 / 22050.0);
    // Offset (onset - syllable) of the onset nearest to t.
    auto nearest = [](const std::vector<double>& times, double t) {
      double best = 1e9;
      for (double o : times)
        if (std::abs(o - t) < std::abs(best)) best = o - t;
      return best;
    };
    int stressed = 0, within50 = 0, within_lead = 0, peak = 0;
    std::vector<double> offsets;
    for (const gmg::SynthSyllable& syl : clip.syllables) {
      if (!syl.stressed) continue;
      ++stressed;
      const double off = nearest(onsets, syl.time);
      if (std::abs(off) <= 0.05) ++within50;
      if (off >= -0.1 && off <= 0.05) ++within_lead;
      if (std::abs(nearest(peaks, syl.time)) <= 0.05) ++peak;
      offsets.push_back(off);
    }
    // Onsets that belong to no syllable (false alarms).
    int stray = 0;
    for (double o : onsets) {
      bool near = false;
      for (const gmg::SynthSyllable& syl : clip.syllables) near = near || (o >= syl.time - 0.2 && o <= syl.time + 0.06);
      if (!near) ++stray;
    }
    std::sort(offsets.begin(), offsets.end());
    const double median = offsets.empty() ? 0 : offsets[offsets.size() / 2];
    std::printf(
        "seed %d style %.0f: %zu syllables (%d stressed), %zu onsets; stressed syllables with an "
        "onset within 50 ms: %d, 100 ms before to 50 ms after: %d, an envelope peak within "
        "50 ms: %d; median onset offset %+.0f ms; %d stray onsets\n",
        static_cast<int>(seed), style, clip.syllables.size(), stressed, onsets.size(), within50, within_lead, peak,
        1000 * median, stray);
    EXPECT_GE(static_cast<int>(onsets.size()), stressed / 2);
    EXPECT_LE(onsets.size(), clip.syllables.size() + 2);
    EXPECT_GE(within50, 0.6 * stressed);
    EXPECT_GE(within_lead, 0.8 * stressed);
    EXPECT_GE(peak, 0.9 * stressed);
    EXPECT_LE(stray, 2);
    EXPECT_LT(median, 0.01);
    EXPECT_GT(median, -0.06);
    total_stressed += stressed;
    total_within50 += within50;
    total_within_lead += within_lead;
    total_peak += peak;
  }
  EXPECT_GT(total_stressed, 60);
  EXPECT_GE(total_within50, 0.7 * total_stressed);
  EXPECT_GE(total_within_lead, 0.85 * total_stressed);
  EXPECT_GE(total_peak, 0.95 * total_stressed);
}

TEST(Synth, LongClipForBenchmarks) {
  SynthSpec s;
  s.duration_s = 12800 / 30.0;
  s.seed = 2023;
  s.joint_count_hint = 60;
  const auto t0 = std::chrono::steady_clock::now();
  const SynthClip clip = gmg::synth_speaker(s);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("12,800-frame clip (%.1f s, 60 joints): generated in %.2f s, %zu words, %zu keywords\n", s.duration_s,
              secs, clip.words.size(), clip.keyword_times.size());
  EXPECT_EQ(clip.motion.frame_count, 12800);
  EXPECT_EQ(clip.audio.samples.size(), static_cast<std::size_t>(std::lround(s.duration_s * 16000)));
  EXPECT_LT(secs, 60.0);
}

}  // namespace
