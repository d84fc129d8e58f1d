// `gmg evaluate`: the objective metrics of engine/metrics.h over files, as one JSON object.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "engine/metrics/metrics.h"
#include "engine/motion/motion.h"

namespace gmg {

struct EvaluateInputs {
  std::string generated;   // BVH (required)
  std::string truth;       // BVH, same skeleton and frame count; "" = skip the metrics needing it
  std::string audio;       // WAV of the speech; "" = skip BC
  std::string report;      // reenactment report JSON; "" = skip failure/fallback counts
};

// Positions are compared in centimetres: a skeleton whose rest pose is under 5 units tall is
// taken to be in metres (BEAT2) and scaled by 100, others are taken as centimetres (GENEA, ZEGGS).
double length_unit_to_cm(const Skeleton& skeleton);

// Joint indices of the wrists: names containing "wrist", else names ending in "hand".
std::vector<int> wrist_joints(const Skeleton& skeleton);

// Metrics of motions in memory (positions computed here). truth may be null; audio_beats may be
// null. Throws gmg::Error on skeleton or length mismatch, naming both files.
nlohmann::ordered_json evaluate_motions(const Motion& generated, const std::string& generated_name, const Motion* truth,
                                        const std::string& truth_name, const std::vector<double>* audio_beats_s,
                                        const MetricParams& params);

nlohmann::ordered_json evaluate_files(const EvaluateInputs& in, const MetricParams& params);

}  // namespace gmg
