#ifndef TRIGRAV_INITIALIZERS_PARALLEL_FOR_H_
#define TRIGRAV_INITIALIZERS_PARALLEL_FOR_H_

// trigrav's one worker pool (library, Python bindings, tools): independent work items on a few
// threads, each thread taking the next unclaimed index.

#include <cstddef>
#include <functional>
#include <string>

namespace trigrav {

struct ParallelForOptions {
  // Threads working on the items; 0: one per core (std::thread::hardware_concurrency).
  int num_threads = 0;
  // When set, the calling thread does not take items: it calls keep_going() about every
  // poll_interval_s while the workers run (and between items when it must run them itself), and a
  // false stops handing out items; items already started finish. For a caller that must react
  // while the items run, e.g. to a signal (Python's Ctrl-C).
  std::function<bool()> keep_going;
  double poll_interval_s = 0.05;
};

struct ParallelForReport {
  int threads = 0;                // threads that took items (the calling thread included)
  std::size_t items_started = 0;  // items whose work(i) ran; count unless stopped
  bool stopped = false;           // keep_going returned false before every item started
  std::string thread_error;       // why fewer threads than asked were created; empty if none
};

// Calls work(i) for every i in [0, count) and returns when every call is done. Calls for different
// i run concurrently: work must write only to the i-th slot of shared results (or lock).
//
// Never aborts the process: when the system cannot create a thread (std::system_error, e.g. a
// process or memory limit), it goes on with the threads it has, at worst the calling thread alone,
// and says why in thread_error. Every thread is joined on every path. An exception thrown by work
// stops handing out items and is rethrown (the first one) once all threads are joined.
ParallelForReport ParallelFor(std::size_t count,
                              const ParallelForOptions& options,
                              const std::function<void(std::size_t)>& work);

// The same with num_threads threads and no polling.
inline ParallelForReport ParallelFor(std::size_t count,
                                     int num_threads,
                                     const std::function<void(std::size_t)>& work) {
  ParallelForOptions options;
  options.num_threads = num_threads;
  return ParallelFor(count, options, work);
}

}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_PARALLEL_FOR_H_
