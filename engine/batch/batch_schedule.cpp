// The workers of `gmg batch`. Each reference's graph is built once, by the first worker that
// needs it, and shared by every clip that drew it; it is released when the last of them is done.
// A worker prefers a clip whose graph is ready, then a graph nobody builds yet, and only waits
// when every clip left needs a graph under construction, so about `jobs` graphs live at once.
#include <condition_variable>
#include <deque>
#include <memory>

#include "engine/batch/batch_internal.h"
#include "engine/core/files.h"
#include "engine/core/json.h"
#include "engine/core/parallel.h"
#include "engine/core/strings.h"
#include "engine/motion/bvh.h"
#include "engine/pipeline/pipeline.h"
#include "graph/graph_io.h"

namespace gmg::batch {
namespace {

struct RefState {
  std::deque<std::size_t> pending;  // clip indices not started
  int outstanding = 0;              // clips not finished
  enum class State { Unbuilt, Building, Ready, Failed } state = State::Unbuilt;
  std::shared_ptr<const MotionGraph> graph;
  std::string error;
};

class Scheduler {
 public:
  Scheduler(BatchSummary& summary, const RunSetup& setup, std::size_t finished)
      : summary_(summary), setup_(setup), refs_(summary.references.size()), finished_(finished) {
    std::map<std::string, std::size_t> ref_index;
    for (std::size_t k = 0; k < summary.references.size(); ++k) ref_index[summary.references[k].stem] = k;
    for (std::size_t i = 0; i < summary.clips.size(); ++i) {
      if (summary.clips[i].status != BatchClipStatus::Pending) continue;
      RefState& r = refs_.at(ref_index.at(summary.clips[i].reference_stem));
      r.pending.push_back(i);
      ++r.outstanding;
      ++pending_total_;
    }
  }

  // Each of the `workers` items of the pool is one worker's loop: the loops take their clips from
  // the shared state, in the order graphs become ready.
  void run(int workers) {
    if (pending_total_ == 0) return;
    parallel_for(static_cast<std::size_t>(workers), workers, [this](std::size_t, int) { worker(); });
  }

 private:
  bool cancelled() const { return setup_.options.cancel && setup_.options.cancel->load(); }

  void worker() {
    std::unique_lock<std::mutex> lock(m_);
    while (!cancelled() && pending_total_ > 0) {
      // Pick: a clip whose graph is ready (or failed), else a graph to build, else wait.
      RefState* ready = nullptr;
      RefState* unbuilt = nullptr;
      for (RefState& r : refs_) {
        if (r.pending.empty()) continue;
        if (r.state == RefState::State::Ready || r.state == RefState::State::Failed) {
          ready = &r;
          break;
        }
        if (r.state == RefState::State::Unbuilt && !unbuilt) unbuilt = &r;
      }
      if (ready) {
        run_next_clip(*ready, lock);
      } else if (unbuilt) {
        build(*unbuilt, lock);
      } else {
        cv_.wait_for(lock, std::chrono::milliseconds(200));  // every clip left waits for a graph under construction
      }
    }
  }

  // Runs the next clip of r (called and returning with the lock held; the work is unlocked).
  void run_next_clip(RefState& r, std::unique_lock<std::mutex>& lock) {
    const std::size_t i = r.pending.front();
    r.pending.pop_front();
    --pending_total_;
    std::shared_ptr<const MotionGraph> graph = r.graph;
    const std::string ref_error = r.error;
    const std::size_t ref = static_cast<std::size_t>(&r - refs_.data());
    lock.unlock();
    std::vector<std::string> warnings;
    run_clip(summary_.clips[i], summary_.references[ref], graph.get(), ref_error, warnings);
    graph.reset();
    lock.lock();
    report_clip(summary_.clips[i]);
    for (const std::string& w : warnings) setup_.progress.line("batch: warning: " + escape_nonprintable(w));
    if (--r.outstanding == 0) r.graph.reset();  // the last clip of this reference
    cv_.notify_all();
  }

  // Builds r's graph (called and returning with the lock held; the build is unlocked).
  void build(RefState& r, std::unique_lock<std::mutex>& lock) {
    r.state = RefState::State::Building;
    BatchReferenceResult& rr = summary_.references[static_cast<std::size_t>(&r - refs_.data())];
    ReferenceFiles files;
    files.motion = rr.motion;
    files.speech.audio = rr.audio;
    files.speech.transcript = rr.transcript;
    lock.unlock();
    const Clock::time_point t0 = Clock::now();
    std::shared_ptr<const MotionGraph> graph;
    std::string error;
    std::vector<std::string> warnings;  // a reference's audio and motion of different lengths, decoder damage
    try {
      // A --graph, loaded before the run, is shared like a built one.
      graph =
          setup_.graph
              ? setup_.graph
              : std::make_shared<const MotionGraph>(graph_build_from_files({files}, setup_.config, {}, 1, &warnings));
    } catch (const std::exception& e) {
      error = e.what();
    }
    const double secs = setup_.graph ? setup_.graph_seconds : seconds_since(t0);
    lock.lock();
    for (const std::string& w : warnings) setup_.progress.line("batch: warning: " + escape_nonprintable(w));
    rr.build_seconds = secs;
    if (graph) {
      rr.frames = graph->frame_count();
      r.graph = std::move(graph);
      r.state = RefState::State::Ready;
      setup_.progress.line("batch: graph of " + rr.stem + ": " + std::to_string(rr.frames) + " frames, " +
                           (setup_.options.graph.empty() ? "built" : "loaded") + " in " + fixed(secs, 2) + "s");
    } else {
      rr.error = error;
      r.error = error;
      r.state = RefState::State::Failed;
      setup_.progress.line("batch: reference " + rr.stem + " FAILED: " + error);
    }
    cv_.notify_all();
  }

  // Makes one clip (only this worker touches c; of ref, only the fields no worker writes are
  // read). graph is null when the reference failed.
  void run_clip(BatchClipResult& c, const BatchReferenceResult& ref, const MotionGraph* graph,
                const std::string& ref_error, std::vector<std::string>& warnings) const {
    const Clock::time_point t0 = Clock::now();
    if (!graph) {
      c.status = BatchClipStatus::Failed;
      c.error = "reference '" + ref.stem + "' is unusable: " + ref_error;
      c.output.clear();
      return;
    }
    const ClipFiles& t = setup_.tests.at(c.test_stem);
    try {
      const std::string report = (setup_.out_dir / (c.test_stem + ".json")).string();
      check_outputs_apart({{"the output", c.output}, {"the report", setup_.options.reports ? report : ""}},
                          {{"its WAV", t.wav},
                           {"its transcript", t.transcript},
                           {"the reference BVH", ref.motion},
                           {"the reference WAV", ref.audio},
                           {"the reference transcript", ref.transcript}});
      SpeechFiles speech;
      speech.audio = t.wav;
      speech.transcript = t.transcript;
      const Reenactment re = reenact(*graph, speech, setup_.config, ref.motion);
      warnings = re.warnings;
      OutputTransaction outputs;  // the BVH and its report, both or neither
      bvh_write(c.output, re.motion);
      if (setup_.options.reports) {
        const std::string json = json_dump(re.report, 2) + "\n";
        write_file_atomically(report, [&](std::ostream& os) { os << json; });
      }
      outputs.commit();
      c.frames = re.motion.frame_count;
      c.fallbacks = re.plan.fallback_total();
      c.failures = re.plan.failure_count();
      c.status = BatchClipStatus::Ok;
    } catch (const std::exception& e) {
      c.status = BatchClipStatus::Failed;
      c.error = e.what();
      c.output.clear();
    }
    c.seconds = seconds_since(t0);
  }

  // The "[k/N]" line of a finished clip (lock held).
  void report_clip(const BatchClipResult& c) {
    ++finished_;
    const std::string head =
        "[" + std::to_string(finished_) + "/" + std::to_string(summary_.clips.size()) + "] " + c.test_stem;
    if (c.status != BatchClipStatus::Ok) {
      setup_.progress.line(head + " FAILED: " + c.error);
      return;
    }
    const std::string t = fixed(c.seconds, 2) + "s";
    std::string plain =
        head + " ok " + t + " (reference " + c.reference_stem + ", " + std::to_string(c.frames) + " frames";
    if (c.fallbacks) plain += ", " + std::to_string(c.fallbacks) + " fallbacks";
    if (c.failures) plain += ", " + std::to_string(c.failures) + " failures";
    setup_.progress.status(head + " ok " + t, plain + ")");
  }

  BatchSummary& summary_;
  const RunSetup& setup_;
  std::vector<RefState> refs_;  // parallel to summary_.references
  std::size_t finished_ = 0;
  std::size_t pending_total_ = 0;
  std::mutex m_;  // guards refs_, finished_, pending_total_, summary_.references
  std::condition_variable cv_;
};

}  // namespace

void run_clips(BatchSummary& summary, const RunSetup& setup, int workers, std::size_t finished) {
  Scheduler(summary, setup, finished).run(workers);
}

}  // namespace gmg::batch
