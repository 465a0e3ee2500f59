#ifndef TRIGRAV_EXAMPLES_COMMON_PAPER_PROTOCOL_H_
#define TRIGRAV_EXAMPLES_COMMON_PAPER_PROTOCOL_H_

// The levels of the paper's synthetic experiments (Section IV; protocol of derivations.md
// section 8.5), the seeds of their scenes and their accuracy CSV, shared by the tools that run
// them: paper_experiments (stability, noise, pitch, roll) and initialize_and_refine_synthetic
// --experiment=sample20. A level's trials run in chunks whose seeds derive from the level's index
// in PaperLevels(), so that a tool running some of the levels draws the same scenes as a run of
// all. Experiment scaffolding of the example tools (header only), not part of the installed
// library.

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "common/pooled_errors.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/statistics.h"
#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/parallel_for.h"

namespace trigrav {

enum class PaperExperiment { kStability, kNoise, kPitch, kRoll, kSample20 };

// "stability", "noise", "pitch", "roll", "sample20".
inline const char* PaperExperimentName(PaperExperiment experiment) {
  switch (experiment) {
    case PaperExperiment::kStability:
      return "stability";
    case PaperExperiment::kNoise:
      return "noise";
    case PaperExperiment::kPitch:
      return "pitch";
    case PaperExperiment::kRoll:
      return "roll";
    case PaperExperiment::kSample20:
      return "sample20";
  }
  return "?";
}

struct PaperLevel {
  PaperExperiment experiment = PaperExperiment::kStability;
  double noise_px = 0.0;   // image noise sigma
  double pitch_deg = 0.0;  // IMU pitch noise sigma
  double roll_deg = 0.0;   // IMU roll noise sigma
  int trials = 0;          // scenes
};

// In this order: stability (5000 noise-free scenes); noise (0, 0.5, 1, 1.5, 2 px, exact IMU); pitch
// and roll (0, 0.25, 0.5, 0.75, 1 deg at 1 px); sample20 (the noise levels, then the non-zero pitch
// and roll levels at 1 px); 1000 scenes per level except stability. quick: 200, 40 and 6 scenes,
// sample20 at 0 and 1 px only. trial_scale multiplies every count (rounded, at least 1).
inline std::vector<PaperLevel> PaperLevels(bool quick, double trial_scale) {
  const auto scaled = [trial_scale](int trials) {
    return std::max(1, static_cast<int>(std::lround(trials * trial_scale)));
  };
  const int stability = scaled(quick ? 200 : 5000);
  const int accuracy = scaled(quick ? 40 : 1000);
  const int sample20 = scaled(quick ? 6 : 1000);
  std::vector<PaperLevel> levels;
  levels.push_back({PaperExperiment::kStability, 0.0, 0.0, 0.0, stability});
  const std::vector<double> noise = {0.0, 0.5, 1.0, 1.5, 2.0};
  const std::vector<double> imu = {0.0, 0.25, 0.5, 0.75, 1.0};
  for (const double n : noise) levels.push_back({PaperExperiment::kNoise, n, 0.0, 0.0, accuracy});
  for (const double a : imu) levels.push_back({PaperExperiment::kPitch, 1.0, a, 0.0, accuracy});
  for (const double a : imu) levels.push_back({PaperExperiment::kRoll, 1.0, 0.0, a, accuracy});
  const std::vector<double> quick_noise = {0.0, 1.0};
  for (const double n : quick ? quick_noise : noise)
    levels.push_back({PaperExperiment::kSample20, n, 0.0, 0.0, sample20});
  if (!quick) {
    for (std::size_t i = 1; i < imu.size(); ++i)
      levels.push_back({PaperExperiment::kSample20, 1.0, imu[i], 0.0, sample20});
    for (std::size_t i = 1; i < imu.size(); ++i)
      levels.push_back({PaperExperiment::kSample20, 1.0, 0.0, imu[i], sample20});
  }
  return levels;
}

struct PaperChunk {
  std::size_t level = 0;  // index into the levels
  int trials = 0;
  std::uint64_t seed = 0;  // of the chunk's std::mt19937_64 scene generator
};

// The chunks of the levels of the given experiments, in level order: 25 trials (sample20, whose
// trials are slow) or 250, chunk c of level l seeded with seed * 1000003 + l * 10007 + c * 101.
inline std::vector<PaperChunk> PaperChunks(const std::vector<PaperLevel>& levels,
                                           const std::vector<PaperExperiment>& experiments,
                                           std::uint64_t seed) {
  std::vector<PaperChunk> chunks;
  for (std::size_t l = 0; l < levels.size(); ++l) {
    if (std::find(experiments.begin(), experiments.end(), levels[l].experiment) ==
        experiments.end()) {
      continue;
    }
    const int size = levels[l].experiment == PaperExperiment::kSample20 ? 25 : 250;
    for (int first = 0, c = 0; first < levels[l].trials; first += size, ++c) {
      chunks.push_back({l, std::min(size, levels[l].trials - first),
                        seed * 1000003ULL + l * 10007ULL + c * 101ULL});
    }
  }
  return chunks;
}

// The errors of one method at one level. Failures are counted, not pooled: the medians are over the
// estimates that returned a pose.
struct LevelErrors {
  PooledErrors pooled;
  int trials = 0;
  int failures = 0;

  // One trial: a failure if !ok or the pose is not finite. relative_scale_known = false (a pairwise
  // peer without common inliers, whose |C3| is a placeholder) counts the relative-scale error as
  // +inf.
  void Add(const ThreeViewPose& ground_truth,
           bool ok,
           const ThreeViewPose& pose,
           bool relative_scale_known = true) {
    ++trials;
    if (!ok || !pose.IsFinite()) {
      ++failures;
      return;
    }
    ThreeViewPoseErrors errors = ComputeThreeViewPoseErrors(ground_truth, pose);
    if (!relative_scale_known) errors.relative_scale = std::numeric_limits<double>::infinity();
    pooled.Add(errors);
  }
  void Append(const LevelErrors& other) {
    pooled.Append(other.pooled);
    trials += other.trials;
    failures += other.failures;
  }
};

// Runs run_chunk(level, trials, seed), which returns one LevelErrors per method row (num_rows of
// them), for every chunk on `threads` threads, and merges the chunks of each level in chunk order,
// so that the result does not depend on which thread finished first. progress(done, total), if
// given, is called after each chunk (from the worker threads, one call at a time per chunk).
// Returns results[level][row].
template <typename RunChunk, typename Progress>
std::vector<std::vector<LevelErrors>> RunPaperChunks(const std::vector<PaperLevel>& levels,
                                                     const std::vector<PaperChunk>& chunks,
                                                     std::size_t num_rows,
                                                     int threads,
                                                     const RunChunk& run_chunk,
                                                     const Progress& progress) {
  std::vector<std::vector<LevelErrors>> chunk_errors(chunks.size());
  std::atomic<std::size_t> done{0};
  ParallelFor(chunks.size(), threads, [&](std::size_t i) {
    chunk_errors[i] = run_chunk(levels[chunks[i].level], chunks[i].trials, chunks[i].seed);
    progress(++done, chunks.size());
  });
  std::vector<std::vector<LevelErrors>> results(levels.size());
  for (std::size_t i = 0; i < chunks.size(); ++i) {
    std::vector<LevelErrors>& level = results[chunks[i].level];
    level.resize(num_rows);
    for (std::size_t r = 0; r < num_rows; ++r) level[r].Append(chunk_errors[i][r]);
  }
  return results;
}

// The accuracy CSV of the experiments (stability.csv, noise.csv, pitch.csv, roll.csv,
// sample20.csv): one row per method (and stage) and level, 6 significant digits: the median and the
// 90 % quantile (statistics.h) of the pooled rotation and translation errors (deg) and the median
// relative-scale error. with_stage adds a column `stage` after `method` ("raw" for a RANSAC
// estimate, "refined" for its bundle adjustment); rows then pass a non-empty stage.
inline void WritePaperAccuracyHeader(bool with_stage, std::ostream* csv) {
  *csv << "experiment,method," << (with_stage ? "stage," : "")
       << "sample_size,noise_px,pitch_deg,roll_deg,trials,failures,rotation_deg,translation_deg,"
          "scale,rotation_p90_deg,translation_p90_deg\n";
}
inline void WritePaperAccuracyRow(const PaperLevel& level,
                                  const std::string& method,
                                  const std::string& stage,
                                  int sample_size,
                                  const LevelErrors& errors,
                                  std::ostream* csv) {
  std::ostringstream row;
  row.precision(6);
  const PooledErrors& e = errors.pooled;
  row << PaperExperimentName(level.experiment) << ',' << method << ',';
  if (!stage.empty()) row << stage << ',';
  row << sample_size << ',' << level.noise_px << ',' << level.pitch_deg << ',' << level.roll_deg
      << ',' << errors.trials << ',' << errors.failures << ',' << Median(e.rotation_deg) << ','
      << Median(e.translation_deg) << ',' << Median(e.relative_scale) << ','
      << Quantile(e.rotation_deg, 0.9) << ',' << Quantile(e.translation_deg, 0.9) << '\n';
  *csv << row.str();
}

}  // namespace trigrav

#endif  // TRIGRAV_EXAMPLES_COMMON_PAPER_PROTOCOL_H_
