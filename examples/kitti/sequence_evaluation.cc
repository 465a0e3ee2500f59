#include "sequence_evaluation.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <iostream>
#include <mutex>
#include <utility>

#include "../common/thread_note.h"
#include "trigrav/initializers/parallel_for.h"

namespace trigrav::kitti {
namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// "\r<stage> done/total" on stderr, from any thread; silent when disabled.
class Progress {
 public:
  Progress(bool enabled, const char* stage, int total)
      : enabled_(enabled), stage_(stage), total_(total) {
    Print(0);
  }
  void Step() { Print(++done_); }
  ~Progress() {
    if (enabled_) std::cerr << "\n";
  }

 private:
  void Print(int done) {
    if (!enabled_) return;
    const std::lock_guard<std::mutex> lock(mutex_);
    std::cerr << "\r" << stage_ << " " << done << "/" << total_ << std::flush;
  }
  bool enabled_;
  const char* stage_;
  int total_;
  std::atomic<int> done_{0};
  std::mutex mutex_;
};

// The first error of any worker; later ones are dropped.
class FirstError {
 public:
  void Set(const std::string& message) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!failed_.exchange(true)) message_ = message;
  }
  bool failed() const { return failed_; }
  const std::string& message() const { return message_; }

 private:
  std::atomic<bool> failed_{false};
  std::string message_;
  std::mutex mutex_;
};

}  // namespace

bool EvaluateSequence(const KittiSequence& sequence,
                      const std::vector<Method>& methods,
                      const SequenceEvaluationOptions& options,
                      SequenceEvaluation* evaluation,
                      std::string* error) {
  const std::vector<Eigen::Vector3d> imu_gravity =
      ImuGravityInCameras(sequence, options.imu_noise_deg, options.seed);
  const std::vector<Eigen::Vector3d> exact_gravity =
      ImuGravityInCameras(sequence, 0.0, options.seed);
  FirstError first_error;
  *evaluation = SequenceEvaluation();

  // 1. Features of every frame into the cache, in parallel.
  const auto features_start = std::chrono::steady_clock::now();
  evaluation->detect_ms.assign(sequence.num_frames(), -1.0);
  if (!options.cache_dir.empty()) {
    const TripletSource cache_filler(sequence, imu_gravity, options.cache_dir, options.sift,
                                     options.match);
    Progress progress(options.show_progress, "features (frames)", sequence.num_frames());
    examples::NoteFewerThreads(
        ParallelFor(sequence.num_frames(), options.threads, [&](std::size_t i) {
          if (first_error.failed()) return;
          const auto start = std::chrono::steady_clock::now();
          bool detected = false;
          std::string message;
          if (!cache_filler.CacheFrame(sequence.first_frame + static_cast<int>(i), &detected,
                                       &message)) {
            first_error.Set(message);
          }
          if (detected) evaluation->detect_ms[i] = 1e3 * SecondsSince(start);
          progress.Step();
        }));
  }
  evaluation->features_wall_s = SecondsSince(features_start);

  // 2. Triplets: chunks of consecutive triplets per thread, every method on each triplet.
  const auto triplets_start = std::chrono::steady_clock::now();
  const int num_triplets = sequence.num_frames() - 2;
  const int chunk = std::max(4, num_triplets / (4 * options.threads));
  const int num_chunks = (num_triplets + chunk - 1) / chunk;
  std::vector<std::vector<PoseRecord>> records_of_triplet(num_triplets);
  evaluation->triplets.resize(num_triplets);
  if (!first_error.failed()) {
    Progress progress(options.show_progress, "triplets", num_triplets);
    examples::NoteFewerThreads(ParallelFor(num_chunks, options.threads, [&](std::size_t c) {
      TripletSource source(sequence, imu_gravity, options.cache_dir, options.sift, options.match);
      const int end = std::min(num_triplets, static_cast<int>(c + 1) * chunk);
      for (int t = static_cast<int>(c) * chunk; t < end && !first_error.failed(); ++t) {
        const int frame = sequence.first_frame + t;
        TripletData triplet;
        std::string message;
        if (!source.Get(frame, &triplet, &message)) {
          first_error.Set(message);
          return;
        }
        const ThreeViewPose ground_truth = sequence.GroundTruthTriplet(frame);
        ApplyTrackMistake(options.mistake, &triplet.observations);
        for (const Method& method : methods) {
          for (const MethodPose& pose : method.run(triplet.observations, options.seed + frame)) {
            records_of_triplet[t].push_back(
                EvaluatePose(frame, method.name, pose, static_cast<int>(triplet.tracks.size()),
                             ground_truth, exact_gravity[t + 1], exact_gravity[t + 2]));
          }
        }
        triplet.observations = {};
        evaluation->triplets[t] = std::move(triplet);
        progress.Step();
      }
    }));
  }
  evaluation->triplets_wall_s = SecondsSince(triplets_start);
  if (first_error.failed()) {
    *error = first_error.message();
    return false;
  }
  for (std::vector<PoseRecord>& triplet_records : records_of_triplet) {
    for (PoseRecord& record : triplet_records) evaluation->records.push_back(std::move(record));
  }
  evaluation->summaries = Summarize(sequence, evaluation->records);
  return true;
}

}  // namespace trigrav::kitti
