// engine/core/parallel: the worker-count rule and the one thread pool.
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "engine/core/parallel.h"

namespace gmg {
namespace {

TEST(Parallel, WorkerCountTakesTheRequestUpToTheItems) {
  EXPECT_EQ(worker_count(3, 10), 3);
  EXPECT_EQ(worker_count(8, 2), 2);  // no thread without an item
  EXPECT_EQ(worker_count(1, 1000), 1);
  EXPECT_EQ(worker_count(5), 5);  // items unbounded
}

TEST(Parallel, WorkerCountIsAtLeastOne) {
  EXPECT_EQ(worker_count(4, 0), 1);
  EXPECT_EQ(worker_count(0, 0), 1);
  EXPECT_EQ(worker_count(-3, 7), worker_count(0, 7));  // not positive: the hardware's
}

TEST(Parallel, WorkerCountDefaultsToTheHardwareThreads) {
  // The contract: one per hardware thread, 1 when the hardware does not say.
  const int hardware =
      std::thread::hardware_concurrency() == 0 ? 1 : static_cast<int>(std::thread::hardware_concurrency());
  EXPECT_EQ(worker_count(0), hardware);
  EXPECT_EQ(worker_count(0, 1), 1);
}

TEST(Parallel, EveryIndexRunsExactlyOnce) {
  for (int workers : {1, 2, 4, 9}) {
    constexpr std::size_t kCount = 1000;
    std::vector<std::atomic<int>> runs(kCount);
    std::atomic<int> wrong_worker{0};
    parallel_for(kCount, workers, [&](std::size_t i, int worker) {
      ++runs[i];
      if (worker < 0 || worker >= workers) ++wrong_worker;
    });
    for (std::size_t i = 0; i < kCount; ++i)
      EXPECT_EQ(runs[i].load(), 1) << "index " << i << ", " << workers << " workers";
    EXPECT_EQ(wrong_worker.load(), 0);
  }
}

TEST(Parallel, NothingToDo) {
  int calls = 0;
  parallel_for(0, 4, [&](std::size_t, int) { ++calls; });
  EXPECT_EQ(calls, 0);
}

TEST(Parallel, WorkersShareTheItems) {
  // With one item per worker that waits until every worker holds one, the call only returns when
  // the items really ran on that many threads at once.
  constexpr int kWorkers = 3;
  std::atomic<int> arrived{0};
  std::mutex m;
  std::set<int> workers_seen;
  parallel_for(kWorkers, kWorkers, [&](std::size_t, int worker) {
    ++arrived;
    while (arrived.load() < kWorkers) std::this_thread::yield();
    const std::lock_guard<std::mutex> lock(m);
    workers_seen.insert(worker);
  });
  EXPECT_EQ(workers_seen, (std::set<int>{0, 1, 2}));
}

TEST(Parallel, TheLowestFailingIndexWinsAndEveryIndexStillRuns) {
  for (int workers : {1, 2, 4}) {
    constexpr std::size_t kCount = 200;
    std::vector<std::atomic<int>> runs(kCount);
    try {
      parallel_for(kCount, workers, [&](std::size_t i, int) {
        ++runs[i];
        // Whichever of the three fails first in time, the lowest index's error comes out.
        if (i == 150 || i == 17 || i == 90) throw std::runtime_error("item " + std::to_string(i));
      });
      ADD_FAILURE() << "nothing was thrown";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "item 17") << workers << " workers";
    }
    for (std::size_t i = 0; i < kCount; ++i) EXPECT_EQ(runs[i].load(), 1) << "index " << i;
  }
}

}  // namespace
}  // namespace gmg
