// The face speech section of graph files (format 12): round trip, older formats without it, and
// the checks of its values.
#include <functional>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "graph/graph_io.h"
#include "tests/graph/fixtures.h"
#include "tests/test_support.h"

namespace gmg {
namespace {

using namespace gmg::testing;

MotionGraph graph_with_face_speech() {
  MotionGraph g = two_clip_graph();
  FaceSpeech& f = g.face_speech;
  f.feature_dims = 2;
  for (int i = 0; i < g.frame_count(); ++i) {
    f.features.vec().insert(f.features.vec().end(), {0.25f * static_cast<float>(i % 7), -1.5f});
    f.jaw.vec().push_back(0.01f * static_cast<float>(i % 30));
  }
  f.symbols = {"M", "AA"};
  f.phones = {{3.0, 7.5, 0}, {7.5, 12.0, 1}, {101.0, 104.25, 0}};
  return g;
}

TEST(GraphFaceSection, RoundTripsInFormat12AndIsAbsentBefore) {
  const MotionGraph g = graph_with_face_speech();
  TempDir dir;
  graph_save(dir.file("g.gmg"), g);
  EXPECT_EQ(read_file_bytes(dir.file("g.gmg"))[8], 12);
  const MotionGraph h = graph_load(dir.file("g.gmg"));
  ASSERT_TRUE(h.face_speech.known());
  EXPECT_EQ(h.face_speech.feature_dims, 2);
  EXPECT_EQ(h.face_speech.features, g.face_speech.features);
  EXPECT_EQ(h.face_speech.jaw, g.face_speech.jaw);
  EXPECT_EQ(h.face_speech.symbols, g.face_speech.symbols);
  ASSERT_EQ(h.face_speech.phones.size(), 3u);
  EXPECT_EQ(h.face_speech.phones[2].start, 101.0);
  EXPECT_EQ(h.face_speech.phones[2].end, 104.25);
  EXPECT_EQ(h.face_speech.phones[1].symbol, 1u);

  graph_save(dir.file("old.gmg"), g, 11);
  const MotionGraph old = graph_load(dir.file("old.gmg"));
  EXPECT_FALSE(old.face_speech.known());
  EXPECT_TRUE(old.face_speech.phones.empty());
  EXPECT_EQ(old.frame_count(), g.frame_count());
}

TEST(GraphFaceSection, LoadChecksItsValues) {
  TempDir dir;
  const std::string path = dir.file("hand.gmg");
  auto expect_refused = [&](const std::string& fragment, const std::function<void(MotionGraph&)>& damage) {
    MotionGraph g = graph_with_face_speech();
    damage(g);
    graph_save(path, g);
    try {
      graph_load(path);
      ADD_FAILURE() << "accepted: " << fragment;
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("hand.gmg: byte "), std::string::npos) << what;
      EXPECT_NE(what.find(fragment), std::string::npos) << what;
    }
  };
  expect_refused("the face features disagree with frames x features",
                 [](MotionGraph& g) { g.face_speech.features.vec().pop_back(); });
  expect_refused("a face feature is not finite",
                 [](MotionGraph& g) { g.face_speech.features[5] = std::numeric_limits<float>::infinity(); });
  expect_refused("the jaw's opening disagrees with the frame count",
                 [](MotionGraph& g) { g.face_speech.jaw.vec().pop_back(); });
  expect_refused("a jaw angle is not between 0 and pi", [](MotionGraph& g) { g.face_speech.jaw[4] = -0.5f; });
  expect_refused("phone 2 is not inside the frames after the phone before it",
                 [](MotionGraph& g) { g.face_speech.phones[1].start = 6.0; });
  expect_refused("phone 3 is not inside the frames after the phone before it",
                 [](MotionGraph& g) { g.face_speech.phones[2].end = 1000.0; });
  expect_refused("phone 1 has no symbol", [](MotionGraph& g) { g.face_speech.phones[0].symbol = 2; });
  expect_refused("a phone symbol is empty or too long", [](MotionGraph& g) { g.face_speech.symbols[1] = ""; });
}

}  // namespace
}  // namespace gmg
