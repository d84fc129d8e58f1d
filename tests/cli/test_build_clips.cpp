// `gmg build --clips`: many clips of one skeleton into one graph, from folders (flat or
// GENEA-style subfolders) and CSV manifests, joined in stem order.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/cli/cli.h"
#include "engine/synth/synth.h"
#include "graph/graph_io.h"
#include "graph/stats.h"
#include "tests/cli/cli_run.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

namespace fs = std::filesystem;

// Exit code of `gmg args...`; *err gets what it printed on stderr.
int run(std::vector<std::string> args, std::string* err = nullptr) {
  const testing::CliRun r = testing::run_gmg(std::move(args));
  if (err) *err = r.err;
  return r.code;
}

// A short synthetic clip (BVH + WAV + TSV) named `stem` in `dir`; returns its frame count.
int write_clip(const std::string& dir, const std::string& stem, std::uint64_t seed) {
  SynthSpec spec;
  spec.duration_s = 6.0;
  spec.seed = seed;
  const SynthClip clip = synth_speaker(spec);
  synth_write(clip, dir, stem);
  return clip.motion.frame_count;
}

TEST(BuildClips, FoldersAndManifestsJoinInStemOrder) {
  testing::TempDir tmp;
  const fs::path flat = tmp.path() / "flat", genea = tmp.path() / "genea";
  fs::create_directories(flat);
  const int b = write_clip(flat.string(), "b", 2);
  const int a = write_clip(flat.string(), "a", 1);
  // GENEA layout: bvh/, wav/, tsv/ subfolders.
  for (const char* sub : {"bvh", "wav", "tsv"}) fs::create_directories(genea / sub);
  const int c = write_clip(tmp.path().string(), "c", 3);
  fs::rename(tmp.path() / "c.bvh", genea / "bvh" / "c.bvh");
  fs::rename(tmp.path() / "c.wav", genea / "wav" / "c.wav");
  fs::rename(tmp.path() / "c.tsv", genea / "tsv" / "c.tsv");
  // A manifest naming one more clip (relative to the manifest's folder), without transcript.
  const int d = write_clip(tmp.path().string(), "d", 4);
  testing::write_text(tmp.file("more.csv"), "stem,bvh,wav,transcript\nd,d.bvh,d.wav,none\n");

  std::string err;
  ASSERT_EQ(run({"build", "--clips", genea.string(), "--clips", flat.string(), "--clips", tmp.file("more.csv"), "-o",
                 tmp.file("g.gmg"), "--progress", "lines"},
                &err),
            0)
      << err;
  EXPECT_NE(err.find("build: read 4/4 clips"), std::string::npos) << err;
  EXPECT_NE(err.find("build: transitions of 100% of"), std::string::npos) << err;
  const MotionGraph g = graph_load(tmp.file("g.gmg"));
  ASSERT_EQ(g.clips.size(), 4u);
  const std::vector<std::pair<std::string, int>> expected = {
      {(flat / "a.bvh").string(), a}, {(flat / "b.bvh").string(), b}, {(genea / "bvh" / "c.bvh").string(), c}, {"", d}};
  int first = 0;
  for (std::size_t i = 0; i < 4; ++i) {
    if (!expected[i].first.empty()) {
      EXPECT_EQ(g.clips[i].name, expected[i].first);
    }
    EXPECT_EQ(g.clips[i].first_frame, first);
    EXPECT_EQ(g.clips[i].frame_count, expected[i].second);
    first += expected[i].second;
  }
  EXPECT_NE(g.clips[3].name.find("d.bvh"), std::string::npos);
  EXPECT_EQ(g.frame_count(), a + b + c + d);
  EXPECT_EQ(graph_stats(g).break_nodes, 4) << "each clip ends in a break node";
}

TEST(BuildClips, MixingFormsOrFindingNothingIsAnError) {
  testing::TempDir tmp;
  std::string err;
  EXPECT_EQ(run({"build", "--clips", tmp.path().string(), "-o", tmp.file("g.gmg")}, &err), 1);
  EXPECT_NE(err.find("no reference clip"), std::string::npos) << err;
  EXPECT_EQ(
      run({"build", "--clips", tmp.path().string(), "--motion", "x.bvh", "--audio", "x.wav", "-o", tmp.file("g.gmg")},
          &err),
      2);  // usage errors exit 2
  EXPECT_NE(err.find("not both"), std::string::npos) << err;
  EXPECT_EQ(run({"build", "-o", tmp.file("g.gmg")}, &err), 2);
  EXPECT_NE(err.find("no reference given"), std::string::npos) << err;
}

}  // namespace
}  // namespace gmg
