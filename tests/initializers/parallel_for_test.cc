// The worker pool: every item once for any thread count, exceptions and stop requests, and a
// system that cannot create the threads asked for (the process's address space capped, so that a
// thread's stack cannot be mapped: this fails also for root, whom process limits do not bind).

#include "trigrav/initializers/parallel_for.h"

#include <gtest/gtest.h>
#include <malloc.h>
#include <sys/resource.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace trigrav {
namespace {

TEST(ParallelForTest, RunsEveryItemOnceForAnyThreadCount) {
  for (const int threads : {0, 1, 2, 8, 64}) {
    for (const std::size_t count : {0u, 1u, 3u, 500u}) {
      std::vector<std::atomic<int>> runs(count);
      const ParallelForReport report =
          ParallelFor(count, threads, [&](std::size_t i) { runs[i]++; });
      for (std::size_t i = 0; i < count; ++i) EXPECT_EQ(runs[i].load(), 1) << i;
      EXPECT_EQ(report.items_started, count);
      EXPECT_TRUE(report.thread_error.empty());
      EXPECT_FALSE(report.stopped);
      if (count > 0 && threads > 0) {
        EXPECT_EQ(report.threads, std::min<int>(threads, static_cast<int>(count)));
      }
    }
  }
}

TEST(ParallelForTest, RethrowsTheFirstExceptionAfterJoiningAndStartsNoMoreItems) {
  // The items after the throwing one wait for it and then take 100 us each, so that the other
  // threads cannot run out the 10000 items before the pool sees the exception (on a loaded
  // machine, instant items could: the test then failed with 10000 started).
  std::atomic<int> started{0};
  std::atomic<bool> thrown{false};
  EXPECT_THROW(ParallelFor(10000, 4,
                           [&](std::size_t i) {
                             started++;
                             if (i == 10) {
                               thrown = true;
                               throw std::runtime_error("item 10");
                             }
                             if (i < 10) return;
                             while (!thrown.load()) std::this_thread::yield();
                             std::this_thread::sleep_for(std::chrono::microseconds(100));
                           }),
               std::runtime_error);
  EXPECT_LT(started.load(), 10000);
}

TEST(ParallelForTest, KeepGoingFalseStopsHandingOutItems) {
  for (const int threads : {1, 2}) {
    std::atomic<int> done{0};
    ParallelForOptions options;
    options.num_threads = threads;
    options.poll_interval_s = 0.001;
    options.keep_going = [&] { return done.load() < 5; };
    const ParallelForReport report = ParallelFor(100000, options, [&](std::size_t) {
      done++;
      volatile double x = 0.0;
      for (int k = 0; k < 100000; ++k) x = x + 1.0;
    });
    EXPECT_TRUE(report.stopped);
    EXPECT_LT(report.items_started, 100000u);
    EXPECT_EQ(static_cast<std::size_t>(done.load()), report.items_started);
  }
}

// VmSize of this process in bytes.
std::size_t VirtualMemoryBytes() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmSize:") {
      std::size_t kilobytes = 0;
      status >> kilobytes;
      return kilobytes * 1024;
    }
  }
  return 0;
}

// In a child process: the address space capped at its size + 24 MB, room for about two thread
// stacks (8 MB each by default), then 16 threads asked for 200 items. Exit code 0: every item ran
// once, fewer threads ran, and the report says why.
void RunWithCappedAddressSpace() {
  mallopt(M_ARENA_MAX, 1);  // no 64 MB arena reservation per thread
  std::vector<std::atomic<int>> runs(200);
  const std::size_t cap = VirtualMemoryBytes() + (24u << 20);
  rlimit limit{cap, cap};
  if (setrlimit(RLIMIT_AS, &limit) != 0) std::_Exit(3);
  const ParallelForReport report = ParallelFor(runs.size(), 16, [&](std::size_t i) { runs[i]++; });
  for (const std::atomic<int>& r : runs) {
    if (r.load() != 1) std::_Exit(4);
  }
  if (report.threads >= 16 || report.threads < 1) std::_Exit(5);
  if (report.thread_error.find("could create") == std::string::npos) std::_Exit(6);
  std::_Exit(0);
}

TEST(ParallelForTest, GoesOnWithTheThreadsItCouldCreate) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space: no cap is possible";
#else
  EXPECT_EXIT(RunWithCappedAddressSpace(), ::testing::ExitedWithCode(0), "");
#endif
}

}  // namespace
}  // namespace trigrav
