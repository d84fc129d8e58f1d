// gmg.Graph, gmg.Reenactment and the engine's jobs: build, load, reenact, evaluate, convert.
// Each calls the library function the command line calls for the same job, so the same inputs,
// parameters and seed give the same bytes.
#include <pybind11/stl.h>

#include <algorithm>

#include "audio/audio_file.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/json.h"
#include "engine/evaluate/evaluate_files.h"
#include "engine/metrics/face_metrics.h"
#include "engine/motion/motion_file.h"
#include "engine/python/python_types.h"
#include "graph/graph_io.h"
#include "graph/stats.h"

namespace gmg::python {
namespace {

// One reference clip as the arguments give it: files (read by graph_build_from_files), or in
// memory when any part is an array or a gmg.Motion.
struct ClipArgs {
  py::object motion, audio, transcript, skeleton, sample_rate, words, tier;
  bool allow_silence = false;
};

// A transcript file and words= both give the words: which would win is not for gmg to guess.
void check_one_transcript(const py::object& transcript, const py::object& words, const std::string& what) {
  if (!transcript.is_none() && !words.is_none())
    throw Error(what + ": give either a transcript file or words=, not both");
}

bool clip_on_files(const ClipArgs& c) { return is_path(c.motion) && is_path(c.audio) && c.words.is_none(); }

std::string opt_path(const py::object& o) { return o.is_none() ? std::string() : path_of(o); }
std::string opt_text(const py::object& o, const std::string& what) {
  return o.is_none() ? std::string() : text_of(o, what);
}

ReferenceFiles files_of(const ClipArgs& c, text::TranscriptFormat format) {
  return {path_of(c.motion),
          {path_of(c.audio), opt_path(c.transcript), format, opt_text(c.tier, "tier"), c.allow_silence},
          opt_path(c.skeleton)};
}

// The clip in memory: arrays taken as they are, files read as graph_build_from_files reads them.
ReferenceClip clip_in_memory(const ClipArgs& c, text::TranscriptFormat format) {
  ReferenceClip out;
  out.allow_silence = c.allow_silence;
  if (py::isinstance<PyMotion>(c.motion)) {
    const PyMotion& m = c.motion.cast<const PyMotion&>();
    out.name = m.name.empty() ? std::string("motion") : m.name;
    out.motion = m.motion;
    out.body = m.body;
  } else {
    out.name = path_of(c.motion);
    const std::string skeleton = opt_path(c.skeleton);
    const py::gil_scoped_release release;
    out.motion = motion_read(out.name, skeleton, &out.body);
  }
  if (is_path(c.audio)) {
    const std::string path = path_of(c.audio);
    const py::gil_scoped_release release;
    out.sound = audio::read_audio(path);
  } else {
    out.sound = audio_of(c.audio, c.sample_rate, out.name + ": audio");
  }
  if (!c.words.is_none()) {
    out.words = words_of(c.words);
    out.has_words = true;
  } else if (!c.transcript.is_none()) {
    const std::string path = path_of(c.transcript), tier = opt_text(c.tier, "tier");
    const py::gil_scoped_release release;
    out.words = text::read_transcript(path, format, tier);
    out.has_words = true;
  }
  return out;
}

ClipArgs clip_from_dict(const py::handle& item, bool allow_silence) {
  if (!py::isinstance<py::dict>(item))
    throw Error("clips: expected a dict per clip (motion=, audio=, ...), got " +
                py::str(py::type::handle_of(item).attr("__name__")).cast<std::string>());
  const auto d = py::reinterpret_borrow<py::dict>(item);
  ClipArgs c;
  c.allow_silence = allow_silence;
  for (const auto& [key, value] : d) {
    const std::string k = py::str(key).cast<std::string>();
    py::object v = py::reinterpret_borrow<py::object>(value);
    if (k == "motion")
      c.motion = v;
    else if (k == "audio")
      c.audio = v;
    else if (k == "transcript")
      c.transcript = v;
    else if (k == "skeleton")
      c.skeleton = v;
    else if (k == "sample_rate")
      c.sample_rate = v;
    else if (k == "words")
      c.words = v;
    else if (k == "tier")
      c.tier = v;
    else
      throw Error("clips: unknown key '" + k + "' (motion, audio, transcript, skeleton, sample_rate, words, tier)");
  }
  for (py::object* o : {&c.motion, &c.audio, &c.transcript, &c.skeleton, &c.sample_rate, &c.words, &c.tier})
    if (!*o) *o = py::none();
  if (c.motion.is_none() || c.audio.is_none()) throw Error("clips: every clip needs motion and audio");
  check_one_transcript(c.transcript, c.words, "clips");
  return c;
}

// One parameter per keyword argument of gmg.build (the Python signature).
// NOLINTNEXTLINE(readability-function-size)
PyGraph build(const py::object& motion, const py::object& audio, const py::object& transcript, const py::object& clips,
              const py::object& skeleton, const py::object& sample_rate, const py::object& words,
              const py::object& tier, const std::string& transcript_format, const py::object& config,
              const py::object& set, int jobs, bool allow_silence) {
  std::vector<ClipArgs> args;
  if (!clips.is_none()) {
    if (!motion.is_none() || !audio.is_none())
      throw Error("build: give either clips= or motion= with audio=, not both");
    for (const py::handle& c : clips) args.push_back(clip_from_dict(c, allow_silence));
  } else {
    if (motion.is_none() || audio.is_none()) throw Error("build: give motion= and audio= (or clips=)");
    check_one_transcript(transcript, words, "build");
    args.push_back({motion, audio, transcript, skeleton, sample_rate, words, tier, allow_silence});
  }
  if (args.empty()) throw Error("build: no reference clip given");
  const Config cfg = config_of(config, set, py::none());
  const text::TranscriptFormat format = text::parse_transcript_format(transcript_format);
  bool files = true;
  for (const ClipArgs& c : args) files = files && clip_on_files(c);
  PyGraph out;
  if (files) {
    std::vector<ReferenceFiles> refs;
    refs.reserve(args.size());
    for (const ClipArgs& c : args) refs.push_back(files_of(c, format));
    out.name = refs.front().motion;
    const py::gil_scoped_release release;
    out.graph = std::make_shared<const MotionGraph>(graph_build_from_files(refs, cfg, {}, jobs));
  } else {
    std::vector<ReferenceClip> refs;
    refs.reserve(args.size());
    for (const ClipArgs& c : args) refs.push_back(clip_in_memory(c, format));
    out.name = refs.front().name;
    const py::gil_scoped_release release;
    out.graph = std::make_shared<const MotionGraph>(graph_build_from_clips(std::move(refs), cfg));
  }
  return out;
}

PyGraph load(const py::object& path) {
  PyGraph out;
  out.name = path_of(path);
  const py::gil_scoped_release release;
  out.graph = std::make_shared<const MotionGraph>(graph_load(out.name));
  return out;
}

PyGraph graph_arg(const py::object& graph) {
  if (py::isinstance<PyGraph>(graph)) return graph.cast<PyGraph>();
  if (is_path(graph)) return load(graph);
  throw Error("graph: expected a gmg.Graph or the path of a graph file");
}

// gmg.reenact's keep=, ranges= and pins= as `gmg reenact --keep --range --pin`: keep a
// gmg.Reenactment, a gmg.Motion or a path (.bvh, or .npz in the graph's skeleton), read into `kept`;
// pins (at, from, to) or (at, clip, from, to) in seconds.
Control control_of(const py::object& keep, const py::object& ranges, const py::object& pins, const MotionGraph& g,
                   Motion& kept, SmplxBody& kept_face) {
  Control c;
  for (const py::handle& p : pins) {
    const py::tuple t = py::reinterpret_borrow<py::object>(p).cast<py::tuple>();
    if (t.size() != 3 && t.size() != 4) throw Error("pins: expected (at, from, to) or (at, clip, from, to) tuples");
    PinRequest pin;
    pin.at = t[0].cast<double>();
    if (t.size() == 4) pin.clip = t[1].cast<std::string>();
    pin.from = t[t.size() - 2].cast<double>();
    pin.to = t[t.size() - 1].cast<double>();
    if (pin.at < 0 || pin.from < 0 || !(pin.to > pin.from))
      throw Error("pins: times must be 0 or more, with from before to");
    c.pins.push_back(pin);
  }
  for (const py::handle& r : ranges) {
    const auto range = r.cast<std::pair<double, double>>();
    if (range.first < 0 || !(range.second > range.first))
      throw Error("ranges: expected (from, to) with 0 <= from < to");
    c.ranges.push_back(range);
  }
  if (keep.is_none() != c.ranges.empty()) throw Error("reenact: keep= and ranges= go together");
  if (keep.is_none()) return c;
  if (py::isinstance<PyReenactment>(keep)) {
    kept = keep.cast<const PyReenactment&>().motion.motion;
    kept_face = keep.cast<const PyReenactment&>().motion.body;
    c.keep_name = "keep";
  } else if (py::isinstance<PyMotion>(keep)) {
    kept = keep.cast<const PyMotion&>().motion;
    kept_face = keep.cast<const PyMotion&>().body;
    c.keep_name = "keep";
  } else {
    c.keep_name = path_of(keep);
    const py::gil_scoped_release release;
    kept = is_npz_path(c.keep_name) ? npz_read(c.keep_name, g.motion.skeleton, &kept_face) : motion_read(c.keep_name);
  }
  c.keep = &kept;
  c.keep_body = &kept_face;
  return c;
}

// One parameter per keyword argument of gmg.reenact.
// NOLINTNEXTLINE(readability-function-size)
PyReenactment reenact(const py::object& graph, const py::object& audio, const py::object& transcript,
                      const py::object& sample_rate, const py::object& words, const std::string& transcript_format,
                      const py::object& tier, const py::object& seed, const py::object& config, const py::object& set,
                      const py::object& betas, const py::object& name, bool allow_silence, const py::object& keep,
                      const py::object& ranges, const py::object& pins) {
  check_one_transcript(transcript, words, "reenact");
  const PyGraph g = graph_arg(graph);
  const Config cfg = config_of(config, set, seed);
  Motion kept;
  SmplxBody kept_face;
  const Control control = control_of(keep, ranges, pins, *g.graph, kept, kept_face);
  const text::TranscriptFormat format = text::parse_transcript_format(transcript_format);
  // Read first, as `gmg reenact --betas` does: a bad file stops before the long work.
  std::vector<double> shape;
  std::string shape_from;
  if (!betas.is_none()) {
    if (is_path(betas)) {
      shape_from = path_of(betas);
      shape = read_betas_file(shape_from);
    } else {
      check_real_numbers(betas, "betas");
      const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(betas);
      if (!a || a.ndim() != 1 || a.size() == 0) throw Error("betas: expected a 1-D array or the path of a file");
      shape.assign(a.data(), a.data() + a.size());
      shape_from = "array";
    }
  }
  Reenactment r;
  std::string label;
  if (is_path(audio) && words.is_none()) {
    const SpeechFiles speech{path_of(audio), opt_path(transcript), format, opt_text(tier, "tier"), allow_silence};
    label = speech.audio;
    const py::gil_scoped_release release;
    r = gmg::reenact(*g.graph, speech, cfg, g.name, control);
  } else {
    label = name.is_none() ? (is_path(audio) ? path_of(audio) : std::string("audio")) : text_of(name, "name");
    audio::Audio sound;
    if (is_path(audio)) {
      const std::string path = path_of(audio);
      const py::gil_scoped_release release;
      sound = audio::read_audio(path);
    } else {
      sound = audio_of(audio, sample_rate, label);
    }
    std::vector<text::Word> w;
    const bool has_words = !words.is_none() || !transcript.is_none();
    if (!words.is_none()) {
      w = words_of(words);
    } else if (!transcript.is_none()) {
      const std::string path = path_of(transcript), t = opt_text(tier, "tier");
      const py::gil_scoped_release release;
      w = text::read_transcript(path, format, t);
    }
    const py::gil_scoped_release release;
    r = reenact_audio(*g.graph, sound, has_words ? &w : nullptr, cfg, label, g.name, allow_silence, control);
  }
  if (!betas.is_none()) reenactment_use_betas(r, std::move(shape), shape_from);
  PyReenactment out;
  out.motion.motion = std::move(r.motion);
  out.motion.body = std::move(r.body);
  out.motion.name = label;
  out.report = std::move(r.report);
  return out;
}

// A motion argument of evaluate: a path (read with the skeleton), a gmg.Motion or a Reenactment.
Motion motion_arg(const py::object& o, const std::string& skeleton, std::string& name) {
  if (py::isinstance<PyReenactment>(o)) {
    const PyReenactment& r = o.cast<const PyReenactment&>();
    name = r.motion.name.empty() ? "reenactment" : r.motion.name;
    return r.motion.motion;
  }
  if (py::isinstance<PyMotion>(o)) {
    const PyMotion& m = o.cast<const PyMotion&>();
    name = m.name.empty() ? "motion" : m.name;
    return m.motion;
  }
  name = path_of(o);
  const py::gil_scoped_release release;
  return motion_read(name, skeleton);
}

// One parameter per keyword argument of gmg.evaluate.
// NOLINTNEXTLINE(readability-function-size)
py::object evaluate(const py::object& generated, const py::object& truth, const py::object& audio,
                    const py::object& sample_rate, const py::object& other_audio, const py::object& report,
                    const py::object& reference, const py::object& skeleton, bool trim, const std::string& hellinger,
                    double hist_width, const py::object& plot, bool allow_silence) {
  EvaluateOptions options;
  const auto bins = enum_from_name(kHistogramBinsNames, hellinger);
  if (!bins) throw Error("hellinger: '" + hellinger + "' is not overflow or genea");
  options.metrics.hist_bins = *bins;
  options.metrics.hist_bin_width = hist_width;
  const std::string templ = opt_path(skeleton);
  bool files = is_path(generated) && (truth.is_none() || is_path(truth)) && (audio.is_none() || is_path(audio)) &&
               (report.is_none() || is_path(report)) && (reference.is_none() || is_path(reference));
  for (const py::handle& o : other_audio) files = files && is_path(o);
  EvaluateResult result;
  if (files) {
    // All files: exactly `gmg evaluate`.
    EvaluateInputs in;
    in.generated = path_of(generated);
    in.truth = opt_path(truth);
    in.skeleton = templ;
    in.audio = opt_path(audio);
    for (const py::handle& o : other_audio) in.other_audio.push_back(path_of(o));
    in.report = opt_path(report);
    in.reference = opt_path(reference);
    in.trim = trim;
    in.allow_silence = allow_silence;
    in.plot = opt_path(plot);
    const py::gil_scoped_release release;
    result = evaluate_files(in, options);
  } else {
    EvaluateLoaded l;
    l.generated = motion_arg(generated, templ, l.generated_name);
    if (!truth.is_none()) l.truth = motion_arg(truth, templ, l.truth_name);
    auto sound_of = [&](const py::handle& o, const std::string& label, std::string& out_name) {
      if (is_path(o)) {
        out_name = path_of(o);
        const py::gil_scoped_release release;
        return read_evaluated_speech(out_name, allow_silence, l.warnings);  // as gmg evaluate reads it
      }
      out_name = label;
      audio::Audio sound = audio_of(o, sample_rate, label);
      check_speech_level(sound, label, allow_silence);
      return sound;
    };
    if (!audio.is_none()) l.audio = sound_of(audio, "audio", l.audio_name);
    int k = 0;
    for (const py::handle& o : other_audio) {
      std::string n;
      l.other_audio.push_back(sound_of(o, "other audio " + std::to_string(++k), n));
      l.other_audio_names.push_back(n);
    }
    py::object rep = report;
    if (rep.is_none() && py::isinstance<PyReenactment>(generated)) rep = generated;
    if (!rep.is_none()) {
      if (py::isinstance<PyReenactment>(rep)) {
        l.report = nlohmann::json::parse(json_dump(rep.cast<const PyReenactment&>().report, -1));
        l.report_name = "report of " + l.generated_name;
      } else if (is_path(rep)) {
        l.report_name = path_of(rep);
        l.report = read_json_file(l.report_name);
      } else {
        l.report = from_python(rep, "report");
        l.report_name = "report";
      }
    }
    if (!reference.is_none()) {
      if (py::isinstance<PyGraph>(reference)) {
        const PyGraph& g = reference.cast<const PyGraph&>();
        for (const ClipInfo& c : g.graph->clips)
          l.reference.push_back(motion_slice(g.graph->motion, c.first_frame, c.first_frame + c.frame_count));
        l.reference_name = g.name;
      } else if (py::isinstance<PyMotion>(reference)) {
        l.reference.push_back(motion_arg(reference, templ, l.reference_name));
      } else {
        l.reference_name = path_of(reference);
        l.reference = read_reference_clips(l.reference_name, templ);
      }
    }
    l.trim = trim;
    l.plot = opt_path(plot);
    const py::gil_scoped_release release;
    result = evaluate_loaded(std::move(l), options);
  }
  return to_python(result.json);
}

py::dict convert(const py::object& in, const py::object& out, const py::object& skeleton, const py::object& betas,
                 const std::string& npz_dtype) {
  ConvertOptions o;
  o.skeleton = opt_path(skeleton);
  o.betas = opt_path(betas);
  const auto floats = enum_from_name(kNpzFloatsNames, npz_dtype);
  if (!floats) throw Error("npz_dtype: '" + npz_dtype + "' is not beat2 or float64");
  o.floats = *floats;
  const std::string from = path_of(in), to = path_of(out);
  ConvertSummary s;
  {
    const py::gil_scoped_release release;
    s = motion_convert(from, to, o);
  }
  py::dict d;
  d["frames"] = s.frames;
  d["fps"] = s.fps;
  d["joints"] = s.joints;
  d["notes"] = s.notes;
  return d;
}

PyMotion graph_motion(const PyGraph& g) {
  PyMotion m;
  m.motion = g.graph->motion;
  m.body = g.graph->body;
  m.name = g.name;
  return m;
}

void bind_graph(py::module_& m) {
  py::class_<PyGraph>(m, "Graph", "A gesture motion graph of one speaker, built (gmg.build) or loaded (gmg.load).")
      .def_property_readonly("name", [](const PyGraph& g) { return g.name; })
      .def_property_readonly("frame_count", [](const PyGraph& g) { return g.graph->frame_count(); })
      .def("__len__", [](const PyGraph& g) { return g.graph->frame_count(); })
      .def_property_readonly("fps", [](const PyGraph& g) { return g.graph->motion.fps; })
      .def_property_readonly("has_face", [](const PyGraph& g) { return g.graph->body.has_face(); })
      .def_property_readonly("clips",
                             [](const PyGraph& g) {
                               py::list out;
                               for (const ClipInfo& c : g.graph->clips) {
                                 py::dict d;
                                 d["name"] = c.name;
                                 d["first_frame"] = c.first_frame;
                                 d["frame_count"] = c.frame_count;
                                 out.append(d);
                               }
                               return out;
                             })
      .def_property_readonly("motion", graph_motion, "the reference motion, every clip in order, with its body")
      .def(
          "stats",
          [](const PyGraph& g) {
            const GraphStats s = graph_stats(*g.graph);
            py::dict d;
            d["frames"] = s.frames;
            d["clips"] = s.clips;
            d["onset_nodes"] = s.onset_nodes;
            d["keyword_nodes"] = s.keyword_nodes;
            d["break_nodes"] = s.break_nodes;
            d["key_nodes"] = s.key_nodes;
            d["natural_edges"] = s.natural_edges;
            d["unnatural_edges"] = s.unnatural_edges;
            d["mean_out_degree"] = s.mean_out_degree;
            return d;
          },
          "the counts `gmg inspect` prints")
      .def(
          "save",
          [](const PyGraph& g, const py::object& path) {
            const std::string file = path_of(path);
            check_output_file({"", file}, {".gmg"});  // as `gmg build -o g.bvh` refuses it
            const py::gil_scoped_release release;
            graph_save(file, *g.graph);
          },
          py::arg("path"), "writes the graph file (as `gmg build -o` writes it)")
      .def("__repr__", [](const PyGraph& g) {
        return "<gmg.Graph " + g.name + ": " + std::to_string(g.graph->frame_count()) + " frames, " +
               std::to_string(g.graph->clips.size()) + " clip(s)" + (g.graph->body.has_face() ? ", with a face" : "") +
               ">";
      });
}

void bind_reenactment(py::module_& m) {
  py::class_<PyReenactment>(m, "Reenactment", "A reenacted motion in the graph's skeleton, with its body and report.")
      .def_property_readonly("motion", [](const PyReenactment& r) { return r.motion; })
      .def_property_readonly(
          "report", [](const PyReenactment& r) { return to_python(r.report); },
          "the report as a dict (what `gmg reenact --report` writes)")
      .def_property_readonly("frame_count", [](const PyReenactment& r) { return r.motion.motion.frame_count; })
      .def("__len__", [](const PyReenactment& r) { return r.motion.motion.frame_count; })
      .def_property_readonly("fps", [](const PyReenactment& r) { return r.motion.motion.fps; })
      .def_property_readonly("rotations",
                             [](const py::object& r) -> py::object { return r.attr("motion").attr("rotations"); })
      .def_property_readonly("axis_angle",
                             [](const py::object& r) -> py::object { return r.attr("motion").attr("axis_angle"); })
      .def_property_readonly("translations",
                             [](const py::object& r) -> py::object { return r.attr("motion").attr("translations"); })
      .def_property_readonly("root", [](const py::object& r) -> py::object { return r.attr("motion").attr("root"); })
      .def_property_readonly("positions",
                             [](const py::object& r) -> py::object { return r.attr("motion").attr("positions"); })
      .def_property_readonly("expressions",
                             [](const py::object& r) -> py::object { return r.attr("motion").attr("expressions"); })
      .def_property_readonly("betas", [](const py::object& r) -> py::object { return r.attr("motion").attr("betas"); })
      .def_property_readonly(
          "jaw",
          [](const PyReenactment& r) -> py::object {
            const std::vector<double> jaw = jaw_angles(r.motion.motion);
            if (jaw.empty()) return py::none();
            py::array_t<double> out(static_cast<py::ssize_t>(jaw.size()));
            std::copy(jaw.begin(), jaw.end(), out.mutable_data());
            return std::move(out);
          },
          "the jaw's opening per frame (radians; the face track's, like expressions), or None without a jaw joint")
      .def(
          "write",
          [](const PyReenactment& r, const py::object& path, const std::string& npz_dtype) {
            py::cast(r.motion).attr("write")(path, npz_dtype);
          },
          py::arg("path"), py::arg("npz_dtype") = "beat2",
          "writes the motion: .npz (SMPL-X with the reference's shape and face) or BVH, as `gmg reenact -o`")
      .def(
          "write_report",
          [](const PyReenactment& r, const py::object& path) {
            const std::string file = path_of(path);
            check_output_file({"", file}, {".json"});  // as `gmg reenact --report r.bvh` refuses it
            const py::gil_scoped_release release;
            write_json_file(file, r.report);
          },
          py::arg("path"), "writes the report JSON, as `gmg reenact --report`")
      .def("__repr__", [](const PyReenactment& r) {
        return "<gmg.Reenactment " + std::to_string(r.motion.motion.frame_count) + " frames of " + r.motion.name + ">";
      });
}

}  // namespace

void bind_engine(py::module_& m) {
  bind_graph(m);
  bind_reenactment(m);

  m.def("build", build, py::arg("motion") = py::none(), py::arg("audio") = py::none(),
        py::arg("transcript") = py::none(), py::kw_only(), py::arg("clips") = py::none(),
        py::arg("skeleton") = py::none(), py::arg("sample_rate") = py::none(), py::arg("words") = py::none(),
        py::arg("tier") = py::none(), py::arg("transcript_format") = "auto", py::arg("config") = py::none(),
        py::arg("set") = py::none(), py::arg("jobs") = 1, py::arg("allow_silence") = false,
        R"(Builds a graph from one reference clip (motion=, audio=, transcript=) or several (clips=[dict, ...]).

motion: a BVH or SMPL-X .npz path (with skeleton=) or a gmg.Motion; audio: a path or samples
(with sample_rate=); transcript: a path, or words=[(start, end, text), ...] (one of the two).
config: a JSON file's path or a dict; set: {key: value}. Audio that cannot be speech (shorter
than 0.5 s, silent, or without an onset in more than 10 s), as a file or as samples, is an
error unless allow_silence=True, as `gmg build --allow-silence`. Files only: exactly what
`gmg build` does.)");
  m.def("load", load, py::arg("path"), "loads a graph file");
  m.def("reenact", reenact, py::arg("graph"), py::arg("audio"), py::arg("transcript") = py::none(), py::kw_only(),
        py::arg("sample_rate") = py::none(), py::arg("words") = py::none(), py::arg("transcript_format") = "auto",
        py::arg("tier") = py::none(), py::arg("seed") = py::none(), py::arg("config") = py::none(),
        py::arg("set") = py::none(), py::arg("betas") = py::none(), py::arg("name") = py::none(),
        py::arg("allow_silence") = false, py::arg("keep") = py::none(), py::arg("ranges") = py::list(),
        py::arg("pins") = py::list(),
        R"(Reenacts new speech from a graph (a gmg.Graph or a graph file's path).

audio: a path, or samples (1-D mono or (samples, channels), real numbers) with sample_rate=
(name= labels them in errors and the report); as a file or as samples, audio that cannot be
speech is an error unless allow_silence=True, as `gmg reenact --allow-silence`;
transcript: a path, or words=[(start, end, text), ...] (one of the two); seed, config, set as
for `gmg reenact`;
betas: an .npz/.npy path or an array, the output's body shape. keep: an earlier output for this
audio (a gmg.Reenactment, gmg.Motion or path) kept outside ranges=[(from, to), ...] seconds, which
are planned afresh; pins=[(at, from, to), ...] or (at, clip, from, to): play the reference's
from..to seconds at output time at. From files, the motion is byte for byte `gmg reenact`'s with
the same inputs and seed.)");
  m.def("evaluate", evaluate, py::arg("generated"), py::kw_only(), py::arg("truth") = py::none(),
        py::arg("audio") = py::none(), py::arg("sample_rate") = py::none(), py::arg("other_audio") = py::list(),
        py::arg("report") = py::none(), py::arg("reference") = py::none(), py::arg("skeleton") = py::none(),
        py::arg("trim") = false, py::arg("hellinger") = "overflow", py::arg("hist_width") = 1.0,
        py::arg("plot") = py::none(), py::arg("allow_silence") = false,
        R"(The metrics of `gmg evaluate` as a dict. generated/truth: paths, gmg.Motion or gmg.Reenactment
(whose report is then used unless report= is given); audio: a path or samples (sample_rate=),
refused when silent or too short unless allow_silence=True;
report: a path, a dict or a Reenactment; reference: a BVH/.npz/.gmg path, a gmg.Graph or a gmg.Motion.)");
  m.def("convert", convert, py::arg("input"), py::arg("output"), py::kw_only(), py::arg("skeleton") = py::none(),
        py::arg("betas") = py::none(), py::arg("npz_dtype") = "beat2", "`gmg convert`: BVH <-> SMPL-X .npz");
  m.def(
      "config",
      [](const py::object& config, const py::object& set, const py::object& seed) {
        return to_python(parse_ordered_json_text(config_to_json(config_of(config, set, seed)), "config"));
      },
      py::arg("config") = py::none(), py::arg("set") = py::none(), py::arg("seed") = py::none(),
      "every parameter and its value (the defaults, then config, set and seed), as `gmg config` prints them");
  m.def(
      "config_keys",
      [] {
        py::dict d;
        for (const ConfigKey& k : config_keys()) d[py::str(k.name)] = k.help;
        return d;
      },
      "every parameter key and its one-line help");
}

}  // namespace gmg::python
