#include "engine/pipeline/reenact.h"

#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>

#include "engine/core/error.h"
#include "engine/core/limits.h"
#include "engine/core/strings.h"
#include "engine/face/face_track.h"
#include "engine/metrics/evaluate.h"
#include "engine/pipeline/lower_body.h"
#include "engine/pipeline/report.h"
#include "search/segmentation.h"

namespace gmg {
namespace {

// How soon a pinned stretch plays the reference after its start and up to before its end.
constexpr double kPinSettleS = 0.2;

}  // namespace

void check_output_size(int frames, const Skeleton& skeleton, const std::string& name) {
  const std::uint64_t bytes = static_cast<std::uint64_t>(frames) *
                              static_cast<std::uint64_t>(std::max(1, skeleton.channel_count())) *
                              limits::kBvhBytesPerValue;
  if (frames > limits::kMaxOutputFrames || bytes > limits::kMaxOutputBytes)
    throw Error(name + ": the output would have " + std::to_string(frames) + " frames of " +
                std::to_string(skeleton.channel_count()) + " channels (about " + std::to_string(bytes >> 20) +
                " MB of BVH); gmg writes at most " + std::to_string(limits::kMaxOutputFrames) + " frames and " +
                std::to_string(limits::kMaxOutputBytes >> 30) + " GB");
}

void reenactment_use_betas(Reenactment& r, std::vector<double> betas, const std::string& from) {
  r.body.betas = std::move(betas);
  r.report["body"] = body_report(r.motion.skeleton, r.body, from);
}

Reenactment reenact_events(const MotionGraph& g, const SpeechEvents& events, const Config& config,
                           const ControlFrames& control) {
  const std::vector<Anchor>& pins = control.pins;
  config_validate(config);
  std::mt19937_64 rng(config.seed);
  const std::vector<Subsequence> subs = segment_speech(events.total_frames, events.onset_frames, events.keyword_frames);
  Reenactment r;
  // Pins displace the rests they overlap; the lower body rests where the upper body does.
  const std::vector<Anchor> anchors =
      with_pins(output_rests(g, events.features.values, events.total_frames, config), pins);
  std::vector<Anchor> rests;
  for (const Anchor& a : anchors)
    if (a.kind == Fixed::Rest) rests.push_back(a);
  r.plan = plan_reenactment(g, subs, config.search, rng, events.features.values, anchors);
  const LowerBody lower = plan_lower_body(g, rests, events.total_frames, config, rng);
  const BlendParams blend = assembly_params(config);
  const std::unique_ptr<BeatAlignment> beats =
      config.search.planner == PlannerMode::Natural ? beat_alignment(g, events.onset_frames, blend) : nullptr;
  r.motion = lower.layers.layered() ? assemble_layered(g, r.plan, lower, blend, beats.get())
                                    : assemble_motion(g, r.plan, blend, beats.get());
  // A pin plays the reference's stretch, joined within 0.2 s of its ends.
  if (!pins.empty()) apply_pins(r.motion, g, pins, static_cast<int>(std::lround(kPinSettleS * g.motion.fps)));
  motion_from_y_up(r.motion, g.up);  // the output in the reference's own up axis
  r.body = assemble_body(g, r.plan, assembly_params(config));
  // After the body's planning, and drawing no random numbers: the body is the same with either face.
  const FaceTrack face = face_track(g, events.face_features.values, &events.phones, events.total_frames, config.face);
  apply_face_track(g, face, r.motion, r.body);
  // A kept range keeps the previous output whole, its face and jaw included.
  if (control.keep)
    apply_keep(r.motion, *control.keep, control.ranges, g, lower.layers, blend.spine_follow,
               blend.halflife_s * g.motion.fps);
  if (control.keep_body) apply_keep_face(r.body, *control.keep_body, control.ranges, blend.halflife_s * g.motion.fps);
  g.check_unchanged();  // a graph file cut short or rewritten meanwhile gave zeros or other values

  r.report =
      reenactment_report(r.plan, events, config, g.motion.fps, length_unit_to_cm(g.motion.skeleton), g.has_speech());
  if (nlohmann::ordered_json body = body_report(g.motion.skeleton, r.body); !body.is_null())
    r.report["body"] = std::move(body);
  if (nlohmann::ordered_json legs = lower_body_report(g.motion.skeleton, lower); !legs.is_null())
    r.report["lower_body"] = std::move(legs);
  if (r.report.contains("body") || !face.sources.empty()) r.report["face_track"] = face_track_report(face);
  control_report(r.report, control.ranges, events.total_frames, control.keep != nullptr, pins);
  r.warnings = events.warnings;
  return r;
}

std::string check_lock_joints_of_graph(const MotionGraph& g, const Config& config, const std::string& graph_name) {
  const std::vector<std::string>& joints = config.cleanup.lock_joints;
  if (joints.empty()) return "";
  std::vector<std::string> names;
  for (const Joint& j : g.motion.skeleton.joints) names.push_back(j.name);
  const auto missing = std::find_if(joints.begin(), joints.end(), [&](const std::string& j) {
    return std::find(names.begin(), names.end(), j) == names.end();
  });
  if (missing != joints.end())
    throw Error(graph_name + ": lock_joints names '" + *missing + "', which is not a joint of its skeleton" +
                did_you_mean(*missing, names));
  return graph_name + ": lock_joints has no effect on a built graph (its motion was cleaned, or not, by 'gmg build')";
}

namespace {

// The report of a whole reenactment: the tool and its inputs first, then reenact_events' report.
void prepend_inputs(Reenactment& r, nlohmann::ordered_json inputs) {
  nlohmann::ordered_json full;
  full["tool"] = "gmg reenact";
  full["inputs"] = std::move(inputs);
  for (auto it = r.report.begin(); it != r.report.end(); ++it) full[it.key()] = it.value();
  r.report = std::move(full);
}

// The control's pins and kept frames checked against the output of `events`, then the reenactment.
Reenactment reenact_controlled(const MotionGraph& g, const SpeechEvents& events, const Config& config,
                               const Control& control, std::vector<double> word_starts, const std::string& speech,
                               const std::string& transcript, const std::string& graph_name) {
  std::vector<PinRequest> pins = control.pins;
  std::sort(word_starts.begin(), word_starts.end());
  resolve_word_pins(pins, word_starts, transcript.empty() ? speech : transcript);
  ControlFrames frames;
  frames.pins = pin_anchors(g, pins, events.total_frames, speech, graph_name);
  if (control.keep) {
    check_keep(control, g, events.total_frames);
    frames.keep = control.keep;
    frames.keep_body = control.keep_body;
    frames.ranges = range_frames(control.ranges, g.motion.fps, events.total_frames, control.keep_name);
    // A pin among the kept frames would be overwritten by them.
    for (const Anchor& p : frames.pins) {
      const bool inside = std::any_of(frames.ranges.begin(), frames.ranges.end(), [&](const std::pair<int, int>& r) {
        return p.start >= r.first && p.start + p.length <= r.second;
      });
      if (!inside)
        throw Error(control.keep_name + ": the pin at " + format_number(p.start / g.motion.fps) +
                    " s is not inside a --range (the frames outside them are kept as they are)");
    }
  } else if (!control.ranges.empty()) {
    throw Error(speech + ": --range needs --keep, the earlier output whose other frames it keeps");
  }
  return naming_memory_errors(speech, "reenacting", [&] { return reenact_events(g, events, config, frames); });
}

bool pins_by_word(const Control& control) {
  return std::any_of(control.pins.begin(), control.pins.end(), [](const PinRequest& p) { return p.word >= 0; });
}

}  // namespace

Reenactment reenact(const MotionGraph& g, const SpeechFiles& speech, const Config& config,
                    const std::string& graph_name, const Control& control) {
  check_lock_joints_of_graph(g, config, graph_name);
  const text::Lexicon lexicon = lexicon_for(config.graph);
  const SpeechEvents events = speech_analyse(speech, g.motion.fps, -1, config.graph, lexicon);
  check_output_size(events.total_frames, g.motion.skeleton, speech.audio);
  std::vector<double> word_starts;
  if (pins_by_word(control) && !speech.transcript.empty())
    for (const text::Word& w : text::read_transcript(speech.transcript, speech.transcript_format, speech.tier))
      word_starts.push_back(w.start);
  Reenactment r =
      reenact_controlled(g, events, config, control, word_starts, speech.audio, speech.transcript, graph_name);
  nlohmann::ordered_json inputs = {
      {"graph", graph_name},
      {"audio", speech.audio},
      {"transcript",
       speech.transcript.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(speech.transcript)}};
  if (control.keep) inputs["keep"] = control.keep_name;
  prepend_inputs(r, std::move(inputs));
  return r;
}

Reenactment reenact_audio(const MotionGraph& g, const audio::Audio& sound, const std::vector<text::Word>* words,
                          const Config& config, const std::string& name, const std::string& graph_name,
                          bool allow_silence, const Control& control) {
  check_lock_joints_of_graph(g, config, graph_name);
  check_audio_samples(sound, name);
  std::vector<text::Word> sorted;
  if (words) {
    sorted = *words;
    check_words(sorted, name);
  }
  const text::Lexicon lexicon = lexicon_for(config.graph);
  const SpeechEvents events =
      speech_events(sound, words ? &sorted : nullptr, name, g.motion.fps, -1, config.graph, lexicon, allow_silence);
  check_output_size(events.total_frames, g.motion.skeleton, name);
  std::vector<double> word_starts;
  for (const text::Word& w : sorted) word_starts.push_back(w.start);
  Reenactment r = reenact_controlled(g, events, config, control, word_starts, name, "", graph_name);
  nlohmann::ordered_json inputs = {{"graph", graph_name}, {"audio", name}, {"transcript", nullptr}};
  if (control.keep) inputs["keep"] = control.keep_name;
  prepend_inputs(r, std::move(inputs));
  return r;
}

}  // namespace gmg
