#ifndef TRIGRAV_PYTHON_SIGNAL_WATCH_H_
#define TRIGRAV_PYTHON_SIGNAL_WATCH_H_

// Long calls with the GIL released that still answer Ctrl-C: the work runs on trigrav's pool while
// the calling thread checks Python's signals every 50 ms. On a signal the library's stop_requested
// (RansacOptions, ThreeViewBundleAdjustmentOptions) turns true, no further item starts, and the
// signal's exception (KeyboardInterrupt) is raised once every thread has returned. Python runs
// signal handlers in the main thread only: a call from another thread is not interruptible.

#include <atomic>
#include <cstddef>
#include <functional>
#include <string>

#include "bindings.h"
#include "trigrav/initializers/parallel_for.h"

namespace trigrav::python {

class SignalWatch {
 public:
  // For the library's stop_requested fields; valid while this object lives.
  std::function<bool()> StopRequested() const {
    return [this] { return stop_.load(std::memory_order_relaxed); };
  }

  // ParallelFor(count, num_threads (0: one per core), work) with the GIL released. Call with the
  // GIL held; raises the signal's exception, or rethrows the first exception of work; a
  // RuntimeWarning when fewer threads than asked could be created.
  ParallelForReport Run(std::size_t count,
                        int num_threads,
                        const std::function<void(std::size_t)>& work) {
    PyObject *type = nullptr, *value = nullptr, *traceback = nullptr;
    ParallelForOptions pool;
    pool.num_threads = num_threads;
    pool.poll_interval_s = 0.05;
    pool.keep_going = [&] {
      py::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() == 0) return true;
      PyErr_Fetch(&type, &value, &traceback);
      stop_ = true;
      return false;
    };
    ParallelForReport report;
    try {
      py::gil_scoped_release release;
      report = ParallelFor(count, pool, work);
    } catch (...) {
      if (type == nullptr) throw;  // a signal outranks an error of the interrupted work
    }
    if (type != nullptr) {
      PyErr_Restore(type, value, traceback);
      throw py::error_already_set();
    }
    // Fewer threads than asked: the results are the same, only later (and a call the calling
    // thread ran itself saw no signal until it returned).
    if (!report.thread_error.empty() &&
        PyErr_WarnEx(PyExc_RuntimeWarning, ("trigrav: " + report.thread_error).c_str(), 1) != 0) {
      throw py::error_already_set();
    }
    return report;
  }

 private:
  std::atomic<bool> stop_{false};
};

}  // namespace trigrav::python

#endif  // TRIGRAV_PYTHON_SIGNAL_WATCH_H_
