#include "engine/core/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>
#include <vector>

namespace gmg {

int worker_count(int requested, std::size_t work_items) {
  const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t wanted = requested > 0 ? static_cast<std::size_t>(requested) : hardware;
  return static_cast<int>(std::max<std::size_t>(1, std::min(wanted, work_items)));
}

void parallel_for(std::size_t count, int workers, const std::function<void(std::size_t index, int worker)>& fn) {
  // One slot per index (not a first-come error): the lowest failing index wins whatever the order
  // the threads reached them in.
  std::vector<std::exception_ptr> errors(count);
  std::atomic<std::size_t> next{0};
  auto run = [&](int worker) {
    for (std::size_t i = next++; i < count; i = next++) {
      try {
        fn(i, worker);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  };
  const std::size_t threads = std::min<std::size_t>(static_cast<std::size_t>(std::max(1, workers)), count);
  std::vector<std::thread> pool;
  pool.reserve(threads > 0 ? threads - 1 : 0);
  for (std::size_t w = 1; w < threads; ++w) pool.emplace_back(run, static_cast<int>(w));
  run(0);
  for (std::thread& t : pool) t.join();
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace gmg
