#include "trigrav/evaluation/paper_protocol.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/statistics.h"

namespace trigrav {

const char* PaperExperimentName(PaperExperiment experiment) {
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

std::vector<PaperLevel> PaperLevels(bool quick, double trial_scale) {
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

std::vector<PaperChunk> PaperChunks(const std::vector<PaperLevel>& levels,
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

void LevelErrors::Add(const ThreeViewPose& ground_truth,
                      bool ok,
                      const ThreeViewPose& pose,
                      bool relative_scale_known) {
  ++trials;
  if (!ok || !pose.IsFinite()) {
    ++failures;
    return;
  }
  ThreeViewPoseErrors errors = ComputeThreeViewPoseErrors(ground_truth, pose);
  if (!relative_scale_known) errors.relative_scale = std::numeric_limits<double>::infinity();
  pooled.Add(errors);
}

void LevelErrors::Append(const LevelErrors& other) {
  pooled.Append(other.pooled);
  trials += other.trials;
  failures += other.failures;
}

void WritePaperAccuracyHeader(bool with_stage, std::ostream* csv) {
  *csv << "experiment,method," << (with_stage ? "stage," : "")
       << "sample_size,noise_px,pitch_deg,roll_deg,trials,failures,rotation_deg,translation_deg,"
          "scale,rotation_p90_deg,translation_p90_deg\n";
}

void WritePaperAccuracyRow(const PaperLevel& level,
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
