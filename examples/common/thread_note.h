#ifndef TRIGRAV_EXAMPLES_COMMON_THREAD_NOTE_H_
#define TRIGRAV_EXAMPLES_COMMON_THREAD_NOTE_H_

// The tools' one line when the worker pool ran on fewer threads than asked (header only): the run
// goes on and its results are the same, only slower.

#include <cstdio>

#include "trigrav/initializers/parallel_for.h"

namespace trigrav::examples {

inline void NoteFewerThreads(const ParallelForReport& report) {
  if (report.thread_error.empty()) return;
  std::fprintf(stderr, "note: ran on %d thread(s): %s\n", report.threads,
               report.thread_error.c_str());
}

}  // namespace trigrav::examples

#endif  // TRIGRAV_EXAMPLES_COMMON_THREAD_NOTE_H_
