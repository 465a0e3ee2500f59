#ifndef TRIGRAV_EVALUATION_PARALLEL_FOR_H_
#define TRIGRAV_EVALUATION_PARALLEL_FOR_H_

// The tools' and tests' worker pool: independent work items (scenes, settings, chunks of trials) on
// a few threads, each thread taking the next unclaimed index.

#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace trigrav {

// Calls work(i) for every i in [0, count) on `threads` threads and returns when all calls are done.
// Calls for different i run concurrently: work must write only to the i-th slot of shared results
// (or lock).
template <typename Work>
void ParallelFor(std::size_t count, int threads, const Work& work) {
  std::atomic<std::size_t> next{0};
  const auto run = [&] {
    for (std::size_t i = next++; i < count; i = next++) work(i);
  };
  std::vector<std::thread> workers;
  for (int t = 0; t < threads; ++t) workers.emplace_back(run);
  for (std::thread& worker : workers) worker.join();
}

}  // namespace trigrav

#endif  // TRIGRAV_EVALUATION_PARALLEL_FOR_H_
