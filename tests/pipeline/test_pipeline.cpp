// The reenactment pipeline end to end: determinism, reports, bad inputs, speech in memory (the
// shared recordings: test_pipeline_real_data.cpp).
#include <algorithm>
#include <cstring>
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "audio/audio_file.h"
#include "audio/wav.h"
#include "engine/cli/cli.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/motion/bvh.h"
#include "engine/pipeline/pipeline.h"
#include "engine/synth/synth.h"
#include "graph/graph_io.h"
#include "tests/cli/cli_run.h"
#include "tests/core/helpers.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

using namespace gmg::testing;

// ---- the whole pipeline through the command line ----

int run_cli(std::vector<std::string> args) { return run_gmg(std::move(args)).code; }

class SynthPipeline : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new gmg::testing::TempDir();
    SynthSpec ref;
    ref.duration_s = 40;
    ref.seed = 11;
    synth_write(synth_speaker(ref), dir_->path().string(), "ref");
    SynthSpec test;
    test.duration_s = 15;
    test.seed = 16;  // its speech says "never", which the reference does not: keyword fallbacks
    synth_write(synth_speaker(test), dir_->path().string(), "test");
    ASSERT_EQ(run_cli({"build", "--motion", file("ref.bvh"), "--audio", file("ref.wav"), "--transcript",
                       file("ref.tsv"), "-o", file("ref.gmg")}),
              0);
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static std::string file(const std::string& name) { return dir_->file(name); }
  // The test speech's events, analysed for graph `g` as `gmg reenact` does.
  static SpeechEvents test_events(const MotionGraph& g, const Config& cfg) {
    return speech_analyse({file("test.wav"), file("test.tsv")}, g.motion.fps, -1, cfg.graph, lexicon_for(cfg.graph));
  }
  // Where a graph file's key poses start (graph/graph_io.cpp): after the part the checksum covers
  // (its length the header's last field, at byte 20), their u64 count and zero padding to a page.
  static std::size_t key_poses_offset(const std::string& bytes) {
    std::uint64_t summed = 0;
    std::memcpy(&summed, bytes.data() + 20, 8);
    return (28 + summed + 8 + 4095) / 4096 * 4096;
  }
  static gmg::testing::TempDir* dir_;
};
gmg::testing::TempDir* SynthPipeline::dir_ = nullptr;

TEST_F(SynthPipeline, SameSeedGivesByteIdenticalOutput) {
  auto run = [&](const std::string& tag, const std::string& seed) {
    EXPECT_EQ(run_cli({"reenact", "--graph", file("ref.gmg"), "--audio", file("test.wav"), "--transcript",
                       file("test.tsv"), "-o", file(tag + ".bvh"), "--report", file(tag + ".json"), "--seed", seed}),
              0);
    return read_file_bytes(file(tag + ".bvh")) + read_file_bytes(file(tag + ".json"));
  };
  const std::string a = run("a", "5");
  const std::string b = run("b", "5");
  EXPECT_EQ(a, b);
  const Motion m = bvh_read(file("a.bvh"));
  EXPECT_EQ(m.frame_count, 15 * 30);
}

// The seed reaches every random choice: with random start nodes (init=random) two seeds give two
// different motions, and the same seed the same one. Fails if the pipeline ignores config.seed.
TEST_F(SynthPipeline, DifferentSeedsGiveDifferentMotions) {
  const MotionGraph g = graph_load(file("ref.gmg"));
  Config cfg;
  cfg.search.init = InitMode::Random;
  const SpeechEvents ev = test_events(g, cfg);
  auto motion_bytes = [&](std::uint64_t seed) {
    cfg.seed = seed;
    return bvh_format(reenact_events(g, ev, cfg).motion);
  };
  EXPECT_NE(motion_bytes(1), motion_bytes(2));
  EXPECT_EQ(motion_bytes(3), motion_bytes(3));
}

// With the default (natural) planner too: near-equal candidates are drawn with the seed.
TEST_F(SynthPipeline, DefaultPlannerVariesWithTheSeed) {
  const MotionGraph g = graph_load(file("ref.gmg"));
  Config cfg;
  const SpeechEvents ev = test_events(g, cfg);
  cfg.seed = 1;
  const std::string a = bvh_format(reenact_events(g, ev, cfg).motion);
  cfg.seed = 2;
  EXPECT_NE(a, bvh_format(reenact_events(g, ev, cfg).motion));
}

TEST_F(SynthPipeline, ReportCountsEverySubsequence) {
  ASSERT_EQ(run_cli({"reenact", "--graph", file("ref.gmg"), "--audio", file("test.wav"), "--transcript",
                     file("test.tsv"), "-o", file("r.bvh"), "--report", file("r.json")}),
            0);
  const nlohmann::json r = nlohmann::json::parse(read_file_bytes(file("r.json")));
  // The same job in process: the report must describe this plan, segment by segment.
  const Reenactment direct = reenact(graph_load(file("ref.gmg")), {file("test.wav"), file("test.tsv")}, Config{}, "g");
  const std::vector<PlannedSegment>& segs = direct.plan.segments;
  ASSERT_EQ(r["subsequences"].size(), segs.size());
  int with_fallback = 0;
  for (std::size_t i = 0; i < segs.size(); ++i) {
    const auto& s = r["subsequences"][i];
    EXPECT_EQ(s["fallback"], fallback_name(segs[i].fallback)) << i;
    EXPECT_EQ(s["accepted"].get<bool>(), segs[i].accepted) << i;
    EXPECT_EQ(s["continued"].get<bool>(), segs[i].continued) << i;
    EXPECT_EQ(s["target_length"].get<int>(), segs[i].sub.length) << i;
    with_fallback += segs[i].fallback != Fallback::None;
  }
  EXPECT_GT(with_fallback, 0) << "the synthetic test speech has keywords the reference lacks";
  EXPECT_EQ(r["totals"]["fallbacks"]["keyword_to_rhythm"].get<int>(),
            direct.plan.fallback_count(Fallback::KeywordToRhythm));
  EXPECT_EQ(r["totals"]["subsequences"].get<std::size_t>(), segs.size());
  EXPECT_EQ(r["inputs"]["transcript"], file("test.tsv"));
}

TEST_F(SynthPipeline, BadInputsFailWithoutOutput) {
  gmg::testing::write_text(file("empty.wav"), "");
  EXPECT_NE(run_cli({"reenact", "--graph", file("ref.gmg"), "--audio", file("empty.wav"), "-o", file("x.bvh")}), 0);
  EXPECT_NE(run_cli({"reenact", "--graph", file("missing.gmg"), "--audio", file("test.wav"), "-o", file("x.bvh")}), 0);
  // A transcript past the audio's end.
  gmg::testing::write_text(file("late.tsv"), "1.0\t1.5\thello\n30.0\t31.0\tbig\n");
  EXPECT_NE(run_cli({"reenact", "--graph", file("ref.gmg"), "--audio", file("test.wav"), "--transcript",
                     file("late.tsv"), "-o", file("x.bvh")}),
            0);
  EXPECT_NE(run_cli({"reenact", "--graph", file("ref.gmg"), "--audio", file("test.wav"), "-o", file("x.bvh"), "--set",
                     "l_npaths=0"}),
            0);
  EXPECT_FALSE(std::filesystem::exists(file("x.bvh")));
}

// The checks about the inputs themselves live in the library, so every caller (the command line,
// batch, the Python module) refuses and warns alike.
TEST_F(SynthPipeline, SilentOrShortSpeechIsRefusedUnlessAllowed) {
  const MotionGraph g = graph_load(file("ref.gmg"));
  audio::Audio quiet;
  quiet.sample_rate = 16000;
  quiet.samples.assign(std::size_t{16000} * 12, 0.0f);
  audio::write_wav_pcm16(file("silence.wav"), quiet);
  quiet.samples.resize(160);  // 10 ms
  audio::write_wav_pcm16(file("click.wav"), quiet);
  const Config cfg;
  EXPECT_EQ(error_of([&] {
              reenact(g, {file("silence.wav"), ""}, cfg, "ref.gmg");
            }),
            file("silence.wav") +
                ": is silent: every sample is zero, and speech needs -60 dB or more; --allow-silence uses it anyway");
  EXPECT_EQ(error_of([&] {
              reenact(g, {file("click.wav"), ""}, cfg, "ref.gmg");
            }),
            file("click.wav") +
                ": holds 0.01 s of audio, too short to be speech (gmg needs at least 0.5 s; --allow-silence uses it "
                "anyway)");
  // A reference speech is checked the same way, before its motion is read.
  EXPECT_EQ(error_of([&] {
              graph_build_from_files({{file("ref.bvh"), {file("click.wav"), ""}}}, cfg);
            }),
            error_of([&] {
              reenact(g, {file("click.wav"), ""}, cfg, "ref.gmg");
            }));
  SpeechFiles allowed{file("silence.wav"), ""};
  allowed.allow_silence = true;
  const Reenactment r = reenact(g, allowed, cfg, "ref.gmg");
  EXPECT_EQ(r.motion.frame_count, 12 * 30);
}

// One clip on two workers reads its motion alongside its speech; on one, after it. The graph is the
// same, and so is the error when both files are bad: the speech's, as when read one after the other.
TEST_F(SynthPipeline, MotionReadAlongsideTheSpeechGivesTheSameGraphAndErrors) {
  const Config cfg;
  const ReferenceFiles clip{file("ref.bvh"), {file("ref.wav"), file("ref.tsv")}};
  const MotionGraph one = graph_build_from_files({clip}, cfg, {}, 1);
  const MotionGraph two = graph_build_from_files({clip}, cfg, {}, 2);
  ASSERT_EQ(two.frame_count(), one.frame_count());
  graph_save(file("read_after.gmg"), one);
  graph_save(file("read_alongside.gmg"), two);
  EXPECT_EQ(read_file_bytes(file("read_alongside.gmg")), read_file_bytes(file("read_after.gmg")));

  gmg::testing::write_text(file("bad_frames.bvh"), read_file_bytes(file("ref.bvh")) + "not a frame line\n");
  audio::Audio click;
  click.sample_rate = 16000;
  click.samples.assign(160, 0.1f);  // 10 ms: too short to be speech
  audio::write_wav_pcm16(file("click10.wav"), click);
  for (const int jobs : {1, 2}) {
    SCOPED_TRACE(jobs);
    const std::string both = error_of([&] {
      graph_build_from_files({{file("bad_frames.bvh"), {file("click10.wav"), ""}}}, cfg, {}, jobs);
    });
    EXPECT_NE(both.find("click10.wav: holds 0.01 s of audio"), std::string::npos) << both;
    const std::string motion = error_of([&] {
      graph_build_from_files({{file("bad_frames.bvh"), {file("ref.wav"), ""}}}, cfg, {}, jobs);
    });
    EXPECT_NE(motion.find("bad_frames.bvh"), std::string::npos) << motion;
  }
}

TEST_F(SynthPipeline, ReferenceAudioAndMotionOfDifferentLengthsWarnNamingBoth) {
  // ref.bvh lasts 40 s; test.wav 15 s: a mismatch of 25 s.
  ReferenceFiles clip{file("ref.bvh"), {file("test.wav"), ""}};
  std::vector<std::string> warnings;
  graph_build_from_files({clip}, Config{}, {}, 1, &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], file("test.wav") + ": lasts 15.0 s but its motion " + file("ref.bvh") +
                             " lasts 40.0 s (25.0 s apart): both are read from their starts, so check they are one "
                             "recording");
  warnings.clear();
  graph_build_from_files({{file("ref.bvh"), {file("ref.wav"), ""}}}, Config{}, {}, 1, &warnings);
  EXPECT_TRUE(warnings.empty()) << warnings.front();  // the same recording: nothing to say
}

TEST_F(SynthPipeline, LockJointsMissingFromABuiltGraphNameTheJoint) {
  const MotionGraph g = graph_load(file("ref.gmg"));
  Config cfg;
  cfg.cleanup.lock_joints = {"RightHnd"};
  EXPECT_EQ(error_of([&] { check_lock_joints_of_graph(g, cfg, "ref.gmg"); }),
            "ref.gmg: lock_joints names 'RightHnd', which is not a joint of its skeleton (did you mean 'RightHand'?)");
  EXPECT_EQ(error_of([&] {
              reenact(g, {file("test.wav"), ""}, cfg, "ref.gmg");
            }),
            error_of([&] { check_lock_joints_of_graph(g, cfg, "ref.gmg"); }));
  cfg.cleanup.lock_joints = {"RightHand"};
  EXPECT_EQ(check_lock_joints_of_graph(g, cfg, "ref.gmg"),
            "ref.gmg: lock_joints has no effect on a built graph (its motion was cleaned, or not, by 'gmg build')");
  cfg.cleanup.lock_joints.clear();
  EXPECT_EQ(check_lock_joints_of_graph(g, cfg, "ref.gmg"), "");
}

// A graph loaded with MotionCheck::OnUse (as `gmg reenact` and `gmg batch` load one) has the
// frames its assembly reads checked, and reads no other: a copy of the file whose every other
// block of motion holds NaN gives the same reenactment byte for byte (any read of them would put
// NaN in the output), while a full load of that copy, `gmg inspect`, says it is damaged, and
// damage in a block the reenactment plays stops `gmg reenact` with the frames named.
TEST_F(SynthPipeline, AReenactmentChecksAndReadsOnlyTheMotionItPlays) {
  Config cfg;
  const MotionGraph g = graph_load(file("ref.gmg"), MotionCheck::OnUse);
  ASSERT_NE(g.unchecked_motion, nullptr);
  const SpeechEvents ev = test_events(g, cfg);
  const std::string intact = bvh_format(reenact_events(g, ev, cfg).motion);
  EXPECT_EQ(intact, bvh_format(reenact_events(graph_load(file("ref.gmg")), ev, cfg).motion));
  const std::vector<std::uint8_t> checked = g.unchecked_motion->checked;
  const int per = g.unchecked_motion->block_frames;
  const auto played = std::count(checked.begin(), checked.end(), std::uint8_t{1});
  ASSERT_GT(played, 0);
  ASSERT_LT(played, static_cast<long>(checked.size())) << "the reenactment played every block: no test";

  // The motion's place in the file (graph/graph_io.cpp): after the key poses, each array's u64
  // count, zero padding to a page boundary, its values: the rotations', then the translations'.
  std::string bytes = read_file_bytes(file("ref.gmg"));
  const std::size_t joints = g.motion.skeleton.joints.size(), frames = static_cast<std::size_t>(g.frame_count());
  const std::size_t keys_at = key_poses_offset(bytes);
  const std::size_t rotations_at = (keys_at + g.key_poses.size() * 8 + 8 + 4095) / 4096 * 4096;
  const std::size_t translations_at = (rotations_at + frames * joints * 32 + 8 + 4095) / 4096 * 4096;
  ASSERT_EQ(bytes.size(), translations_at + frames * joints * 24 + 8);
  auto poison = [&](std::string& file_bytes, std::size_t block) {
    const std::size_t first = block * static_cast<std::size_t>(per);
    const std::size_t n = std::min(static_cast<std::size_t>(per), frames - first);
    file_bytes.replace(rotations_at + first * joints * 32, n * joints * 32, n * joints * 32, '\xff');
    file_bytes.replace(translations_at + first * joints * 24, n * joints * 24, n * joints * 24, '\xff');
  };
  std::string unplayed = bytes;
  for (std::size_t b = 0; b < checked.size(); ++b)
    if (!checked[b]) poison(unplayed, b);
  write_text(file("unplayed.gmg"), unplayed);
  EXPECT_EQ(bvh_format(reenact_events(graph_load(file("unplayed.gmg"), MotionCheck::OnUse), ev, cfg).motion), intact);
  EXPECT_EQ(error_of([&] { graph_load(file("unplayed.gmg")); }),
            file("unplayed.gmg") + ": graph file is damaged (checksum mismatch)");
  EXPECT_NE(run_cli({"inspect", file("unplayed.gmg")}), 0);
  ASSERT_EQ(run_cli({"reenact", "--graph", file("unplayed.gmg"), "--audio", file("test.wav"), "--transcript",
                     file("test.tsv"), "-o", file("unplayed.bvh")}),
            0);
  ASSERT_EQ(run_cli({"reenact", "--graph", file("ref.gmg"), "--audio", file("test.wav"), "--transcript",
                     file("test.tsv"), "-o", file("intact.bvh")}),
            0);
  EXPECT_EQ(read_file_bytes(file("unplayed.bvh")), read_file_bytes(file("intact.bvh")));

  // Damage in the first block played: the reenactment stops, names the file and the frames, and
  // writes nothing.
  const std::size_t first_played =
      static_cast<std::size_t>(std::find(checked.begin(), checked.end(), std::uint8_t{1}) - checked.begin());
  std::string played_damaged = bytes;
  poison(played_damaged, first_played);
  write_text(file("played.gmg"), played_damaged);
  const std::string frames_named =
      std::to_string(first_played * static_cast<std::size_t>(per)) + " to " +
      std::to_string(std::min(frames, (first_played + 1) * static_cast<std::size_t>(per)) - 1);
  EXPECT_EQ(error_of([&] { reenact_events(graph_load(file("played.gmg"), MotionCheck::OnUse), ev, cfg); }),
            file("played.gmg") + ": graph file is damaged (checksum mismatch in frames " + frames_named + ")");
  const CliRun r = run_gmg({"reenact", "--graph", file("played.gmg"), "--audio", file("test.wav"), "--transcript",
                            file("test.tsv"), "-o", file("played.bvh")});
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("checksum mismatch in frames " + frames_named), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(file("played.bvh")));
}

// The same for the key poses (format 9): a reenactment checks the junction poses of the key nodes
// its ranking reads (search/junction.h; which ones, JunctionCost's tests), and a NaN pose of a key
// it ranks, which no load of a reenactment reads, stops `gmg reenact` with the file, the key node
// and its frame named, and writes nothing.
TEST_F(SynthPipeline, AReenactmentChecksTheKeyPosesItRanks) {
  Config cfg;
  const MotionGraph g = graph_load(file("ref.gmg"), MotionCheck::OnUse);
  ASSERT_NE(g.unchecked_key_poses, nullptr);
  const SpeechEvents ev = test_events(g, cfg);
  const std::string intact = bvh_format(reenact_events(g, ev, cfg).motion);
  const std::vector<std::uint8_t> checked = g.unchecked_key_poses->checked;
  const std::size_t ranked =
      static_cast<std::size_t>(std::find(checked.begin(), checked.end(), std::uint8_t{1}) - checked.begin());
  ASSERT_LT(ranked, checked.size());

  std::string bytes = read_file_bytes(file("ref.gmg"));
  const std::size_t keys_at = key_poses_offset(bytes);
  const std::size_t dims = g.key_poses.size() / checked.size();
  ASSERT_EQ(bytes.compare(keys_at, g.key_poses.size() * 8,
                          std::string(reinterpret_cast<const char*>(g.key_poses.data()), g.key_poses.size() * 8)),
            0);
  bytes.replace(keys_at + ranked * dims * 8, dims * 8, dims * 8, '\xff');
  write_text(file("ranked.gmg"), bytes);
  EXPECT_NE(graph_load(file("ranked.gmg"), MotionCheck::OnUse).unchecked_key_poses, nullptr);
  EXPECT_EQ(error_of([&] { graph_load(file("ranked.gmg")); }),
            file("ranked.gmg") + ": graph file is damaged (checksum mismatch)");
  const std::string named = "checksum mismatch in the junction pose of key node " + std::to_string(ranked) +
                            " (frame " + std::to_string(g.keys[ranked]) + ")";
  EXPECT_EQ(error_of([&] { reenact_events(graph_load(file("ranked.gmg"), MotionCheck::OnUse), ev, cfg); }),
            file("ranked.gmg") + ": graph file is damaged (" + named + ")");
  const CliRun r = run_gmg({"reenact", "--graph", file("ranked.gmg"), "--audio", file("test.wav"), "--transcript",
                            file("test.tsv"), "-o", file("ranked.bvh")});
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find(named), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(file("ranked.bvh")));
  // The poses checked as they are read are the ones a full load checks and reads.
  EXPECT_EQ(intact, bvh_format(reenact_events(graph_load(file("ref.gmg")), ev, cfg).motion));
}

// ---- speech in memory ----

// The arrays path (the Python module's) is the files path: a graph built from the clip in memory
// and a reenactment of speech in memory give the motion the files give.
TEST_F(SynthPipeline, ClipsAndSpeechInMemoryGiveWhatTheirFilesGive) {
  const Config cfg;
  const MotionGraph from_files = graph_build_from_files({{file("ref.bvh"), {file("ref.wav"), file("ref.tsv")}}}, cfg);
  ReferenceClip clip;
  clip.name = file("ref.bvh");
  clip.motion = bvh_read(file("ref.bvh"));
  clip.sound = audio::read_audio(file("ref.wav"));
  clip.words = text::read_transcript(file("ref.tsv"));
  clip.has_words = true;
  const MotionGraph from_memory = graph_build_from_clips({clip}, cfg);
  ASSERT_EQ(from_memory.frame_count(), from_files.frame_count());
  EXPECT_EQ(from_memory.speech, from_files.speech);
  EXPECT_EQ(from_memory.graph.edge_count(), from_files.graph.edge_count());
  const Reenactment a = reenact(from_files, {file("test.wav"), file("test.tsv")}, cfg, "g");
  const std::vector<text::Word> words = text::read_transcript(file("test.tsv"));
  const Reenactment b = reenact_audio(from_memory, audio::read_audio(file("test.wav")), &words, cfg, "new", "g");
  EXPECT_EQ(bvh_format(b.motion), bvh_format(a.motion));
  // Bad arrays are refused with the readers' kind of message.
  audio::Audio silent;
  silent.sample_rate = 100;
  silent.samples.assign(10, 0.0f);
  EXPECT_THROW(reenact_audio(from_memory, silent, nullptr, cfg, "new", "g"), Error);
  std::vector<text::Word> backwards = {{2.0, 1.0, "no"}};
  EXPECT_THROW(reenact_audio(from_memory, audio::read_audio(file("test.wav")), &backwards, cfg, "new", "g"), Error);
}

}  // namespace
}  // namespace gmg
