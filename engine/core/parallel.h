// Running independent work on several threads: the one thread pool of the engine (the graph's
// candidate search, the clips of `gmg build --clips`, the workers of `gmg batch`).
#pragma once

#include <cstddef>
#include <functional>
#include <limits>

namespace gmg {

// How many threads to give `work_items` independent items: `requested` when positive, else one
// per hardware thread (1 when the hardware does not say); never more than the items (a thread
// with nothing to do is not started) and at least 1.
int worker_count(int requested, std::size_t work_items = std::numeric_limits<std::size_t>::max());

// Runs fn(index, worker) for every index in [0, count) on `workers` threads, the caller's among
// them (worker 0); `worker` < workers tells a thread its own scratch. Indices are handed out one
// at a time, so uneven items balance. Every index runs exactly once even when some throw; once
// all are done, the exception of the lowest failing index is rethrown, so which error a caller
// sees does not depend on scheduling.
void parallel_for(std::size_t count, int workers, const std::function<void(std::size_t index, int worker)>& fn);

}  // namespace gmg
