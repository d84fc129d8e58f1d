#include "engine/pipeline/speech_analysis.h"

#include <algorithm>
#include <cmath>

#include "audio/audio_file.h"
#include "audio/speech_check.h"
#include "engine/core/error.h"
#include "engine/core/limits.h"
#include "engine/core/strings.h"

namespace gmg {

text::Lexicon lexicon_for(const GraphParams& params) {
  return params.keywords.empty() ? text::default_lexicon() : text::load_lexicon(params.keywords);
}

namespace {

SpeechTimes times_of(audio::OnsetAnalysis onsets, audio::EnergyTrack energy, double duration_s,
                     const std::vector<text::Word>* words, const std::string& name) {
  SpeechTimes t;
  t.duration_s = duration_s;
  t.onsets = std::move(onsets);
  t.energy = std::move(energy);
  t.name = name;
  if (words) {
    text::check_transcript_fits(*words, duration_s, name);
    t.words = *words;
    t.has_words = true;
  }
  return t;
}

audio::OnsetParams onset_params_of(const GraphParams& params) {
  audio::OnsetParams p;
  p.min_onset_strength = params.min_onset_strength;
  return p;
}

}  // namespace

SpeechEvents speech_events_on_grid(const SpeechTimes& times, double fps, int frame_count,
                                   const text::Lexicon& lexicon) {
  SpeechEvents ev;
  ev.duration_s = times.duration_s;
  if (frame_count < 0 && !(ev.duration_s * fps <= limits::kMaxFrames))
    throw Error(times.name + ": " + format_number(ev.duration_s) + " s of speech at " + format_number(fps) +
                " fps is more than the " + std::to_string(limits::kMaxFrames) + " frames gmg makes");
  ev.total_frames = frame_count >= 0 ? frame_count : static_cast<int>(std::lround(ev.duration_s * fps));
  if (ev.total_frames < 1) throw Error(times.name + ": audio is shorter than one motion frame");
  ev.onset_frames = audio::onset_motion_frames(times.onsets, fps, ev.total_frames);
  ev.features = audio::speech_features(times.energy, times.onsets.envelope, fps, ev.total_frames);
  ev.face_features = audio::face_features(times.face_audio, times.energy, fps, ev.total_frames);
  ev.phones = times.phones;
  ev.warnings = times.warnings;
  if (times.has_words) {
    ev.words = static_cast<int>(times.words.size());
    for (const text::KeywordFrame& k :
         text::keyword_frames(text::detect_keywords(times.words, lexicon), fps, ev.total_frames))
      ev.keyword_frames.emplace_back(k.frame, k.keyword);
  }
  return ev;
}

SpeechTimes speech_times_of(const audio::Audio& sound, const std::vector<text::Word>* words, const std::string& name,
                            const GraphParams& params, bool allow_silence) {
  // The checks of speech_times, in its order: the cheap one before the onset analysis.
  audio::EnergyTrack energy = audio::energy_track(sound);
  if (!allow_silence) {
    const std::string problem = audio::speech_level_problem(sound.duration(), energy);
    if (!problem.empty()) throw Error(audio::speech_refusal(name, problem, {}));
  }
  audio::OnsetAnalysis onsets = audio::detect_onsets(sound, onset_params_of(params));
  if (!allow_silence) {
    const std::string problem =
        audio::speech_onset_problem(sound.duration(), onsets.onset_frames.size(), params.min_onset_strength);
    if (!problem.empty()) throw Error(audio::speech_refusal(name, problem, {}));
  }
  SpeechTimes t = times_of(std::move(onsets), std::move(energy), sound.duration(), words, name);
  t.face_audio = audio::face_audio(sound);
  return t;
}

SpeechEvents speech_events(const audio::Audio& sound, const std::vector<text::Word>* words, const std::string& name,
                           double fps, int frame_count, const GraphParams& params, const text::Lexicon& lexicon,
                           bool allow_silence) {
  return speech_events_on_grid(speech_times_of(sound, words, name, params, allow_silence), fps, frame_count, lexicon);
}

void check_audio_samples(const audio::Audio& sound, const std::string& name) {
  if (sound.sample_rate < limits::kMinSampleRate || sound.sample_rate > limits::kMaxSampleRate)
    throw Error(name + ": sample rate " + std::to_string(sound.sample_rate) + " Hz is outside the " +
                std::to_string(limits::kMinSampleRate) + " to " + std::to_string(limits::kMaxSampleRate) +
                " Hz gmg reads");
  if (sound.samples.empty()) throw Error(name + ": the audio has no samples");
  if (sound.duration() > limits::kMaxAudioSeconds)
    throw Error(name + ": " + format_number(sound.duration()) + " s of audio is more than the " +
                format_number(limits::kMaxAudioSeconds) + " s gmg reads");
  for (std::size_t i = 0; i < sound.samples.size(); ++i)
    if (!std::isfinite(sound.samples[i]))
      throw Error(name + ": sample " + std::to_string(i) + " is not a finite number");
}

void check_words(std::vector<text::Word>& words, const std::string& name) {
  for (std::size_t i = 0; i < words.size(); ++i) {
    const text::Word& w = words[i];
    if (!std::isfinite(w.start) || !std::isfinite(w.end) || w.start < 0 || w.end < w.start)
      throw Error(name + ": word " + std::to_string(i + 1) + " ('" + w.text + "') has times " + format_number(w.start) +
                  " to " + format_number(w.end) + " s; a word needs 0 <= start <= end, finite");
    if (w.text.empty()) throw Error(name + ": word " + std::to_string(i + 1) + " is empty");
  }
  // The readers' order (text/transcript.h): by start time, ties in the given order.
  std::stable_sort(words.begin(), words.end(),
                   [](const text::Word& a, const text::Word& b) { return a.start < b.start; });
}

SpeechTimes speech_times(const SpeechFiles& files, const GraphParams& params) {
  std::vector<std::string> warnings;
  audio::Audio sound = audio::read_audio(files.audio, &warnings);
  const double duration_s = sound.duration();
  audio::EnergyTrack energy = audio::energy_track(sound);
  // Before the long onset analysis: silence or a click of audio fails at once.
  if (!files.allow_silence) {
    const std::string problem = audio::speech_level_problem(duration_s, energy);
    if (!problem.empty()) throw Error(audio::speech_refusal(files.audio, problem, warnings));
  }
  std::vector<text::Word> words;
  std::vector<text::Phone> phones;
  if (!files.transcript.empty()) {
    words = text::read_transcript(files.transcript, files.transcript_format, files.tier);
    phones = text::read_phones(files.transcript, files.transcript_format);
  }
  const std::string& name = files.transcript.empty() ? files.audio : files.transcript;
  // Checked before the long onset analysis: a transcript of another recording fails at once.
  if (!files.transcript.empty()) {
    text::check_transcript_fits(words, duration_s, name);
    text::check_phones_fit(phones, duration_s, name);
  }
  audio::FaceAudio face = audio::face_audio(sound);
  audio::OnsetAnalysis onsets = audio::detect_onsets(std::move(sound), onset_params_of(params));
  if (!files.allow_silence) {
    const std::string problem =
        audio::speech_onset_problem(duration_s, onsets.onset_frames.size(), params.min_onset_strength);
    if (!problem.empty()) throw Error(audio::speech_refusal(files.audio, problem, warnings));
  }
  SpeechTimes t =
      times_of(std::move(onsets), std::move(energy), duration_s, files.transcript.empty() ? nullptr : &words, name);
  t.warnings = std::move(warnings);
  t.face_audio = std::move(face);
  t.phones = std::move(phones);
  return t;
}

SpeechEvents speech_analyse(const SpeechFiles& files, double fps, int frame_count, const GraphParams& params,
                            const text::Lexicon& lexicon) {
  return speech_events_on_grid(speech_times(files, params), fps, frame_count, lexicon);
}

}  // namespace gmg
