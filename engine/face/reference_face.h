// The reference as the face track reads it in one reenactment (engine/face/face_track.h): its
// frames' face features standardised, the jaw's opening and the expressions, its phones and the
// silences between them with their neighbours, and a compact face per frame for the cost of joins.
// Made from a graph's face speech and body (graph/face_speech.h, MotionGraph::body).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "graph/motion_graph.h"
#include "text/phones.h"

namespace gmg {

// A stretch of the reference spoken as one phone, or a silence between phones ("" symbol).
struct FacePhone {
  double start = 0.0, end = 0.0;  // graph frames
  std::string symbol;             // "" for a silence
  std::string left, right;        // the neighbours' symbols ("" silence, or a clip's end)
  int clip = 0;
};

struct ReferenceFace {
  double fps = 30.0;
  int frames = 0;
  int dims = 0;                         // face features per frame
  std::vector<float> z;                 // frames x dims: the features over their reference spread
  std::vector<float> jaw;               // the jaw's angle per frame; empty without a jaw joint
  double jaw_sd = 0.0;                  // its spread (> 0 when there is a jaw)
  const double* expressions = nullptr;  // frames x expression_dims, or null
  int expression_dims = 0;
  std::vector<int> clip_of;               // each frame's clip
  std::vector<int> clip_first, clip_end;  // each clip's frames [first, end)
  std::vector<FacePhone> phones;          // phones and silences, in time order; empty without phones
  std::vector<char> has_phones;           // each clip's: 1 when its transcript had phones
  // The face per frame for joins: the jaw over its spread, then up to kJoinExpressions expression
  // coefficients over their spreads (BEAT2's FLAME coefficients come in order of their variance).
  static constexpr int kJoinExpressions = 10;
  int face_dims = 0;
  std::vector<float> face;  // frames x face_dims
  // The reference's features' mean and spread (what z is relative to) for standardising new speech.
  std::vector<double> mean, sd;

  bool has_jaw() const { return !jaw.empty(); }
  bool has_expressions() const { return expressions != nullptr; }
  // The difference of two frames' faces: |jaw difference| + root mean square of the expressions'.
  double face_distance(int a, int b) const;
};

// Throws gmg::Error when the graph's face speech is not known (check FaceSpeech::known first).
ReferenceFace reference_face(const MotionGraph& g);

}  // namespace gmg
