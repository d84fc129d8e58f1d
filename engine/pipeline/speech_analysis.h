// Speech analysed for the engine: a speech's onsets, keywords and features, in seconds and on a
// motion's frame grid, from files or from memory, with the checks that refuse what cannot be speech.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "audio/face_features.h"
#include "audio/onset.h"
#include "audio/speech_features.h"
#include "audio/wav.h"
#include "graph/params.h"
#include "text/keywords.h"
#include "text/phones.h"
#include "text/transcript.h"

namespace gmg {

// One speech: an audio file and, optionally, a word-timed transcript.
struct SpeechFiles {
  std::string audio;       // audio path (required): WAV, or any format audio/audio_file.h reads
  std::string transcript;  // "" = none
  text::TranscriptFormat transcript_format = text::TranscriptFormat::Auto;
  std::string tier{};  // the TextGrid tier to read; "" = the default (text/transcript.h read_textgrid)
  // Take audio that cannot be speech as it is: shorter than 0.5 s, silent, or without any onset
  // in more than 10 s (audio/speech_check.h). false: such audio is an error naming the file.
  bool allow_silence = false;
};

// Speech as frames on a motion grid.
struct SpeechEvents {
  double duration_s = 0.0;        // audio duration
  int total_frames = 0;           // round(duration_s * fps) for test speech; the motion length for a reference
  std::vector<int> onset_frames;  // ascending, unique, in [0, total_frames)
  std::vector<std::pair<int, std::string>> keyword_frames;  // ascending, in [0, total_frames)
  int words = 0;                                            // transcript words read
  audio::SpeechFeatures features;                           // total_frames frames
  audio::FaceFeatures face_features;                        // total_frames frames (engine/face)
  std::vector<text::Phone> phones;    // the transcript's phones tier, seconds; empty: none (text/phones.h)
  std::vector<std::string> warnings;  // what did not stop the analysis (decoder damage), naming the file
};

// Detects onsets (SPEC "Onset nodes") and keywords in a speech. frame_count < 0 means a test
// speech (T = round(duration * fps)); otherwise events at or after frame_count are dropped (a
// reference whose audio outlasts its motion). A transcript that runs past the audio's end is an
// error naming the transcript; audio that cannot be speech (audio/speech_check.h) is an error
// naming the audio unless files.allow_silence.
SpeechEvents speech_analyse(const SpeechFiles& files, double fps, int frame_count, const GraphParams& params,
                            const text::Lexicon& lexicon);

// Speech analysed in seconds, before it is put on a motion's frame grid. A reference's audio is
// analysed (and released) before its motion is read, so the two are never in memory together.
struct SpeechTimes {
  double duration_s = 0.0;
  audio::OnsetAnalysis onsets;
  audio::EnergyTrack energy;
  std::vector<text::Word> words;
  bool has_words = false;
  audio::FaceAudio face_audio;        // what the face track compares speech by (audio/face_features.h)
  std::vector<text::Phone> phones;    // the transcript's phones tier; empty: none
  std::string name;                   // labels errors: the transcript's file name, else the audio's
  std::vector<std::string> warnings;  // what did not stop the reading (decoder damage), naming the file
};

// Reads and analyses a speech (the transcript past the audio's end and audio that cannot be
// speech are errors here already).
SpeechTimes speech_times(const SpeechFiles& files, const GraphParams& params);

// The events of analysed speech on a grid of `fps` (frame_count as for speech_analyse).
SpeechEvents speech_events_on_grid(const SpeechTimes& times, double fps, int frame_count, const text::Lexicon& lexicon);

// Analyses speech in memory (words may be null: no transcript); `name` labels errors. Without
// allow_silence, audio that cannot be speech is refused as speech_times refuses a file's.
SpeechTimes speech_times_of(const audio::Audio& sound, const std::vector<text::Word>* words, const std::string& name,
                            const GraphParams& params, bool allow_silence = true);

// Audio given in memory, checked as the readers check a file's: gmg::Error "name: ..." for a
// sample rate outside engine/core/limits.h, no samples, more than a day, or a value that is not
// finite.
void check_audio_samples(const audio::Audio& sound, const std::string& name);

// Words given in memory, checked as the transcript readers check a file's (finite times, 0 <=
// start <= end, non-empty text) and sorted by start time as they sort them.
void check_words(std::vector<text::Word>& words, const std::string& name);

// Same as speech_analyse, from audio and words already in memory (words may be null: no
// transcript). `name` labels errors (the transcript's file name). allow_silence as for
// speech_times_of.
SpeechEvents speech_events(const audio::Audio& sound, const std::vector<text::Word>* words, const std::string& name,
                           double fps, int frame_count, const GraphParams& params, const text::Lexicon& lexicon,
                           bool allow_silence = true);

// The lexicon named by params.keywords, or assets/keywords.txt.
text::Lexicon lexicon_for(const GraphParams& params);

}  // namespace gmg
