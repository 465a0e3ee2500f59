#include "trigrav/initializers/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace trigrav {
namespace {

// The items' shared state: the next index, the first exception, and the count of running workers
// the polling caller waits on.
class ItemQueue {
 public:
  ItemQueue(std::size_t count, const std::function<void(std::size_t)>& work)
      : count_(count), work_(work) {}

  // Runs the next item; false when none is left, Stop() was called or an item threw.
  bool RunNext() {
    if (stopped_.load()) return false;
    const std::size_t i = next_++;
    if (i >= count_) return false;
    started_++;
    try {
      work_(i);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!error_) error_ = std::current_exception();
      stopped_ = true;
    }
    return true;
  }
  void Drain() {
    while (RunNext()) {
    }
  }
  void Stop() { stopped_ = true; }
  std::size_t started() const { return started_.load(); }
  void RethrowError() {
    if (error_) std::rethrow_exception(error_);
  }

  // Worker bookkeeping for a caller that waits with a timeout.
  void WorkerStarted() {
    std::lock_guard<std::mutex> lock(mutex_);
    ++running_;
  }
  void WorkerFinished() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      --running_;
    }
    idle_.notify_all();
  }
  // Waits until every worker has finished or the timeout passed; true when all have finished.
  bool WaitForWorkers(std::chrono::duration<double> timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    return idle_.wait_for(lock, timeout, [&] { return running_ == 0; });
  }

 private:
  const std::size_t count_;
  const std::function<void(std::size_t)>& work_;
  std::atomic<std::size_t> next_{0};
  std::atomic<std::size_t> started_{0};
  std::atomic<bool> stopped_{false};
  std::mutex mutex_;
  std::condition_variable idle_;
  int running_ = 0;
  std::exception_ptr error_;
};

}  // namespace

ParallelForReport ParallelFor(std::size_t count,
                              const ParallelForOptions& options,
                              const std::function<void(std::size_t)>& work) {
  ParallelForReport report;
  if (count == 0) return report;
  const int wanted = options.num_threads > 0
                         ? options.num_threads
                         : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const bool polling = static_cast<bool>(options.keep_going);
  // Without polling the calling thread is one of the workers.
  const std::size_t to_create =
      std::min<std::size_t>(count, static_cast<std::size_t>(wanted)) - (polling ? 0 : 1);

  ItemQueue queue(count, work);
  std::vector<std::thread> workers;
  workers.reserve(to_create);
  for (std::size_t t = 0; t < to_create; ++t) {
    queue.WorkerStarted();
    try {
      workers.emplace_back([&queue] {
        queue.Drain();
        queue.WorkerFinished();
      });
    } catch (const std::system_error& e) {
      queue.WorkerFinished();
      report.thread_error = "could create " + std::to_string(workers.size()) + " of " +
                            std::to_string(to_create) + " threads: " + e.what();
      break;
    }
  }
  report.threads = static_cast<int>(workers.size());

  bool stop_requested = false;
  if (!polling) {
    queue.Drain();
    ++report.threads;
  } else if (workers.empty()) {
    // No worker: the caller runs the items, polling between them.
    ++report.threads;
    while (!(stop_requested = !options.keep_going()) && queue.RunNext()) {
    }
  } else {
    const std::chrono::duration<double> interval(std::max(1e-3, options.poll_interval_s));
    while (!queue.WaitForWorkers(interval)) {
      if (!options.keep_going()) {
        stop_requested = true;
        break;
      }
    }
  }
  if (stop_requested) queue.Stop();
  for (std::thread& worker : workers) worker.join();
  report.items_started = queue.started();
  report.stopped = stop_requested && report.items_started < count;
  queue.RethrowError();
  return report;
}

}  // namespace trigrav
