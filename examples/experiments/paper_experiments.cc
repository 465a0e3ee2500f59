// The synthetic experiments of the paper (Section IV; protocol of math note section 6) on
// minimal samples, run on trigrav's own solvers side by side:
//   stability   5000 noise-free scenes: log10 rotation / translation error densities and a summary
//               (median, p99, mean, max, and the mean of log10 errors);
//   noise       image noise 0, 0.5, 1, 1.5, 2 px, exact IMU, 1000 scenes per level;
//   pitch, roll IMU pitch or roll noise 0, 0.25, 0.5, 0.75, 1 deg at 1 px, 1000 scenes per level;
//   timing      solver alone (ns per call over the stability scenes) and inside RANSAC
//               (EstimateThreeViewPoseRobust, 200 triplets, 30 % outliers, 1 px, 3 px threshold).
// The protocol's last experiment, equal sample sizes of 20 triplets with RANSAC and bundle
// adjustment, is initialize_and_refine_synthetic --experiment=sample20 (same levels list and seeds,
// paper_protocol.h).
// Methods: every solver of kInitialSolvers with the paper's sample sizes (minimal: 3, 3, 4, 7, 5, 8
// triplets), and 4pt-paper, the paper's own 4-point variant (III-D: enforced tensor, translations
// read from it, no re-solve, no polish); every method sees the same scenes. Two-view methods (8pt,
// 5pt) solve pairs (1,2) and (1,3) and are made three-view with the view-1 depth ratio
// (CombineTwoViewPairs); among their combinations, and among the candidates of a multi-solution
// solver, the best-ranked one is reported (smallest depth-ratio residual; the solver's own first
// candidate), never the one closest to the truth. Errors (pose_errors.h): rotation and
// translation-direction errors of views 2 and 3 pooled, and the relative-scale error
// |log(s_est / s_gt)|, s = |C3| / |C2|; statistics as in statistics.h. One CSV per experiment in
// --output_dir; plot with plot_paper_experiments.py.
//
//   paper_experiments --output_dir=paper            # the full protocol (about 2 min on 2 cores)
//   paper_experiments --quick --output_dir=quick    # a smoke test (seconds)

#include <gflags/gflags.h>
#include <glog/logging.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "parallel_for.h"
#include "pooled_errors.h"
#include "require_flag.h"
#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/initializers/essential_5pt.h"
#include "trigrav/initializers/essential_8pt.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/statistics.h"
#include "trigrav/initializers/robust_three_view.h"
#include "trigrav/evaluation/synthetic_scene.h"
#include "trigrav/initializers/trifocal_3pt.h"
#include "trigrav/initializers/trifocal_4pt.h"
#include "trigrav/initializers/trifocal_linear.h"
#include "trigrav/initializers/two_view_to_three_view.h"

#include "peer_estimators.h"  // the estimator interface; the peers themselves are optional

#ifdef TRIGRAV_WITH_PEERS
constexpr bool kBuiltWithPeers = true;
#else
constexpr bool kBuiltWithPeers = false;
#endif

DEFINE_string(output_dir, "paper_experiments", "Folder for the CSV files (created if missing).");
DEFINE_bool(quick, false, "Few trials per setting: a smoke test for ctest.");
DEFINE_int32(threads, 2, "Worker threads (the timing experiment always runs on one).");
DEFINE_double(trials, 1.0, "Scale of every trial count (1 = the paper's 5000 / 1000).");
DEFINE_uint64(seed, 1, "Seed of the scenes (the same scenes for every method).");
DEFINE_int32(sample20_triplets, 20, "Triplets per scene in the equal-sample-size experiment.");
DEFINE_bool(peers,
            kBuiltWithPeers,
            "sample20: one more column per OpenCV / OpenGV five-point RANSAC (needs a build with "
            "them; default: on if built with them).");

namespace {

using Rays = std::vector<Eigen::Vector3d>;
using trigrav::InitialSolver;
using trigrav::ThreeViewPose;

// ---------------------------------------------------------------------------------------------
// Direct (non-RANSAC) methods on the first m triplets of a scene.

struct Input {
  std::array<std::array<Rays, 3>, 9> rays;  // rays[m][k]: the first m triplets, view k
  std::array<Eigen::Vector3d, 3> gravity;
};

Input MakeInput(const trigrav::SyntheticScene& scene) {
  Input input;
  for (int m = 3; m <= 8; ++m) {
    for (int k = 0; k < 3; ++k) {
      input.rays[m][k].assign(scene.rays[k].begin(), scene.rays[k].begin() + m);
    }
  }
  input.gravity = scene.gravity_in_cam_measured;
  return input;
}

struct Workspace {
  std::vector<ThreeViewPose> three_view;
  std::vector<trigrav::CameraPose> pair12, pair13;
  std::vector<double> residuals;
};

using DirectSolve = bool (*)(const Input&, Workspace*, ThreeViewPose*);

bool First(const std::vector<ThreeViewPose>& poses, ThreeViewPose* pose) {
  if (poses.empty()) return false;
  *pose = poses.front();
  return true;
}

template <int (*kSolvePair)(const Rays&, const Rays&, std::vector<trigrav::CameraPose>*), int kM>
bool TwoView(const Input& in, Workspace* w, ThreeViewPose* pose) {
  const auto& x = in.rays[kM];
  kSolvePair(x[0], x[1], &w->pair12);
  kSolvePair(x[0], x[2], &w->pair13);
  w->three_view.clear();
  w->residuals.clear();
  trigrav::CombineTwoViewPairs(x[0], x[1], x[2], w->pair12, w->pair13, &w->three_view,
                               &w->residuals);
  if (w->three_view.empty()) return false;
  const std::size_t best =
      std::min_element(w->residuals.begin(), w->residuals.end()) - w->residuals.begin();
  *pose = w->three_view[best];
  return true;
}

bool Linear7(const Input& in, Workspace* w, ThreeViewPose* pose) {
  const auto& x = in.rays[7];
  trigrav::SolveTrifocalLinear(x[0], x[1], x[2], &w->three_view);
  return First(w->three_view, pose);
}

bool Sextic3(const Input& in, Workspace* w, ThreeViewPose* pose) {
  const auto& x = in.rays[3];
  trigrav::SolveTrifocal3ptSextic(x[0], x[1], x[2], in.gravity[0], in.gravity[1], in.gravity[2],
                                  &w->three_view);
  return First(w->three_view, pose);
}

bool Decoupled3(const Input& in, Workspace* w, ThreeViewPose* pose) {
  const auto& x = in.rays[3];
  trigrav::SolveTrifocal3pt(x[0], x[1], x[2], in.gravity[0], in.gravity[1], in.gravity[2],
                            &w->three_view);
  return First(w->three_view, pose);
}

// "4pt-Our-3view" as in the paper (III-D): constraint enforcement, translations read from the
// enforced tensor (no re-solve), no polish.
bool Paper4(const Input& in, Workspace* w, ThreeViewPose* pose) {
  const auto& x = in.rays[4];
  trigrav::Trifocal4ptOptions options;
  options.recovery = trigrav::Trifocal4ptRecovery::kEnforced;
  options.resolve_translations = false;
  options.polish_iterations = 0;
  trigrav::SolveTrifocal4pt(x[0], x[1], x[2], in.gravity[0], in.gravity[1], in.gravity[2], options,
                            &w->three_view);
  return First(w->three_view, pose);
}

bool Default4(const Input& in, Workspace* w, ThreeViewPose* pose) {
  const auto& x = in.rays[4];
  trigrav::SolveTrifocal4pt(x[0], x[1], x[2], in.gravity[0], in.gravity[1], in.gravity[2],
                            &w->three_view);
  return First(w->three_view, pose);
}

struct DirectMethod {
  const char* name;
  int sample_size;
  DirectSolve solve;
  bool has_ransac;  // an InitialSolver exists for it
  InitialSolver solver;
};

const std::vector<DirectMethod>& DirectMethods() {
  static const std::vector<DirectMethod> methods = {
      {"8pt", 8, &TwoView<trigrav::SolveEssential8pt, 8>, true, InitialSolver::kEssential8pt},
      {"5pt", 5, &TwoView<trigrav::SolveEssential5pt, 5>, true, InitialSolver::kEssential5pt},
      {"7pt-linear", 7, &Linear7, true, InitialSolver::kTrifocalLinear},
      {"3pt-sextic", 3, &Sextic3, true, InitialSolver::kTrifocal3ptSextic},
      {"4pt-paper", 4, &Paper4, false, InitialSolver::kTrifocal4pt},
      {"3pt", 3, &Decoupled3, true, InitialSolver::kTrifocal3pt},
      {"4pt", 4, &Default4, true, InitialSolver::kTrifocal4pt},
  };
  return methods;
}

const std::vector<InitialSolver>& RansacSolvers() {
  static const std::vector<InitialSolver> solvers = {
      InitialSolver::kEssential8pt,   InitialSolver::kEssential5pt,
      InitialSolver::kTrifocalLinear, InitialSolver::kTrifocal3ptSextic,
      InitialSolver::kTrifocal3pt,    InitialSolver::kTrifocal4pt};
  return solvers;
}

// sample20's peer columns (--peers): the OpenCV / OpenGV robust estimates, without gravity, at an
// inlier threshold in pixels (examples/peers/peer_estimators.h); none when built without them.
const std::vector<trigrav::peers::NamedEstimator>& Peers() {
  static const std::vector<trigrav::peers::NamedEstimator> peers = [] {
#ifdef TRIGRAV_WITH_PEERS
    if (FLAGS_peers) {
      trigrav::peers::RunPeersSingleThreaded();  // the worker threads are ours
      return trigrav::peers::PeerEstimators();
    }
#endif
    return std::vector<trigrav::peers::NamedEstimator>();
  }();
  return peers;
}

// ---------------------------------------------------------------------------------------------
// Experiments: a list of levels, each run in chunks of trials on the worker threads.

enum class Experiment { kStability, kNoise, kPitch, kRoll, kSample20 };

const char* ExperimentName(Experiment e) {
  switch (e) {
    case Experiment::kStability:
      return "stability";
    case Experiment::kNoise:
      return "noise";
    case Experiment::kPitch:
      return "pitch";
    case Experiment::kRoll:
      return "roll";
    case Experiment::kSample20:
      return "sample20";
  }
  return "?";
}

struct Level {
  Experiment experiment;
  double noise_px, pitch_deg, roll_deg;
  int trials;
};

// Errors of one output column (a method, or a method's raw / refined estimate) at one level;
// failures are counted, not pooled.
struct Errors {
  trigrav::examples::PooledErrors pooled;
  int trials = 0, failures = 0;
  void Append(const Errors& other) {
    pooled.Append(other.pooled);
    trials += other.trials;
    failures += other.failures;
  }
  // relative_scale_known: false when |C3| is a placeholder (a pairwise peer without common
  // inliers); its relative-scale error then counts as +inf.
  void Add(const trigrav::SyntheticScene& scene, bool ok, const ThreeViewPose& pose,
           bool relative_scale_known = true) {
    ++trials;
    if (!ok || !pose.IsFinite()) {
      ++failures;
      return;
    }
    trigrav::ThreeViewPoseErrors errors =
        trigrav::ComputeThreeViewPoseErrors(scene.ground_truth, pose);
    if (!relative_scale_known) errors.relative_scale = std::numeric_limits<double>::infinity();
    pooled.Add(errors);
  }
};

std::vector<std::string> ColumnNames(Experiment experiment) {
  std::vector<std::string> names;
  if (experiment == Experiment::kSample20) {
    for (const InitialSolver s : RansacSolvers()) {
      names.push_back(std::string(trigrav::InitialSolverName(s)) + "+ransac");
      names.push_back(std::string(trigrav::InitialSolverName(s)) + "+ransac+ba");
    }
    for (const trigrav::peers::NamedEstimator& peer : Peers()) names.push_back(peer.name);
  } else {
    for (const DirectMethod& m : DirectMethods()) names.push_back(m.name);
  }
  return names;
}

int MaxSampleSize() { return 8; }

std::vector<Errors> RunChunk(const Level& level, int trials, std::uint64_t seed) {
  const std::size_t columns = ColumnNames(level.experiment).size();
  std::vector<Errors> errors(columns);
  trigrav::SyntheticSceneOptions scene_options;
  scene_options.num_points =
      level.experiment == Experiment::kSample20 ? FLAGS_sample20_triplets : MaxSampleSize();
  scene_options.pixel_noise_px = level.noise_px;
  scene_options.imu_pitch_noise_deg = level.pitch_deg;
  scene_options.imu_roll_noise_deg = level.roll_deg;
  std::mt19937_64 rng(seed);
  Workspace workspace;
  for (int trial = 0; trial < trials; ++trial) {
    const trigrav::SyntheticScene scene = trigrav::GenerateSyntheticScene(scene_options, &rng);
    if (level.experiment != Experiment::kSample20) {
      const Input input = MakeInput(scene);
      for (std::size_t c = 0; c < columns; ++c) {
        ThreeViewPose pose;
        const bool ok = DirectMethods()[c].solve(input, &workspace, &pose);
        errors[c].Add(scene, ok, pose);
      }
      continue;
    }
    const trigrav::ThreeViewObservations observations = trigrav::ToObservations(scene);
    const double imu_deg = std::max(level.pitch_deg, level.roll_deg);
    const double threshold_px = 3.0 * std::max(1.0, level.noise_px);
    for (std::size_t s = 0; s < RansacSolvers().size(); ++s) {
      trigrav::InitializeAndRefineOptions options;
      options.solver = RansacSolvers()[s];
      options.inlier_threshold_px = threshold_px;
      options.refine = true;
      options.seed = seed + trial;
      if (imu_deg > 0.0) {
        options.bundle_adjustment.rotation_model =
            trigrav::ThreeViewBundleAdjustmentOptions::RotationModel::kGravityPrior;
        options.bundle_adjustment.gravity_sigma_deg = imu_deg;
        options.bundle_adjustment.pixel_sigma_px = std::max(level.noise_px, 0.1);
        // Both columns start from the paper's upright RANSAC: "+ BA" refines the raw column.
        options.correct_tilt_in_ransac = false;
      }
      const trigrav::ThreeViewEstimate estimate =
          trigrav::InitializeAndRefine(observations, options);
      errors[2 * s].Add(scene, estimate.success, estimate.initial);
      errors[2 * s + 1].Add(scene, estimate.success && estimate.refinement_ran, estimate.refined);
    }
    for (std::size_t p = 0; p < Peers().size(); ++p) {
      const trigrav::peers::EstimatorResult peer = Peers()[p].estimate(observations, threshold_px);
      errors[2 * RansacSolvers().size() + p].Add(scene, peer.success, peer.pose,
                                                 peer.relative_scale_known);
    }
  }
  return errors;
}

int Scaled(int trials) { return std::max(1, static_cast<int>(std::lround(trials * FLAGS_trials))); }

std::vector<Level> Levels() {
  const int stability = Scaled(FLAGS_quick ? 200 : 5000);
  const int accuracy = Scaled(FLAGS_quick ? 40 : 1000);
  const int sample20 = Scaled(FLAGS_quick ? 6 : 1000);
  std::vector<Level> levels;
  levels.push_back({Experiment::kStability, 0.0, 0.0, 0.0, stability});
  const std::vector<double> noise = {0.0, 0.5, 1.0, 1.5, 2.0};
  const std::vector<double> imu = {0.0, 0.25, 0.5, 0.75, 1.0};
  for (const double n : noise) levels.push_back({Experiment::kNoise, n, 0.0, 0.0, accuracy});
  for (const double a : imu) levels.push_back({Experiment::kPitch, 1.0, a, 0.0, accuracy});
  for (const double a : imu) levels.push_back({Experiment::kRoll, 1.0, 0.0, a, accuracy});
  const std::vector<double> quick_noise = {0.0, 1.0};
  for (const double n : FLAGS_quick ? quick_noise : noise)
    levels.push_back({Experiment::kSample20, n, 0.0, 0.0, sample20});
  if (!FLAGS_quick) {
    for (std::size_t i = 1; i < imu.size(); ++i)
      levels.push_back({Experiment::kSample20, 1.0, imu[i], 0.0, sample20});
    for (std::size_t i = 1; i < imu.size(); ++i)
      levels.push_back({Experiment::kSample20, 1.0, 0.0, imu[i], sample20});
  }
  return levels;
}

// ---------------------------------------------------------------------------------------------
// Statistics and CSV output.

double Quantile(std::vector<double> values, double q) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const std::size_t i =
      std::min(values.size() - 1, static_cast<std::size_t>(std::ceil(q * values.size())) - 1);
  return values[i];
}

double Mean(const std::vector<double>& values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  return std::accumulate(values.begin(), values.end(), 0.0) / values.size();
}

constexpr double kLogFloor = -17.0;  // log10 of an exactly zero error is shown at this value

double Log10Error(double error_deg) {
  return std::max(kLogFloor, std::log10(std::max(error_deg, 0.0)));
}

double MeanLog10(const std::vector<double>& values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0.0;
  for (const double v : values) sum += Log10Error(v);
  return sum / values.size();
}

std::ofstream OpenCsv(const std::string& name) {
  const std::string path = FLAGS_output_dir + "/" + name;
  std::ofstream csv(path);
  trigrav::examples::RequireFlag(static_cast<bool>(csv), "cannot write " + path);
  csv.precision(6);
  return csv;
}

void WriteAccuracy(const std::vector<Level>& levels,
                   const std::vector<std::vector<Errors>>& results,
                   Experiment experiment,
                   const std::string& file) {
  std::ofstream csv = OpenCsv(file);
  csv << "experiment,method,sample_size,noise_px,pitch_deg,roll_deg,trials,failures,"
         "rotation_deg,translation_deg,scale,rotation_p90_deg,translation_p90_deg\n";
  const std::vector<std::string> names = ColumnNames(experiment);
  for (std::size_t c = 0; c < names.size(); ++c) {
    for (std::size_t l = 0; l < levels.size(); ++l) {
      if (levels[l].experiment != experiment) continue;
      const Errors& e = results[l][c];
      const int sample = experiment == Experiment::kSample20 ? FLAGS_sample20_triplets
                                                             : DirectMethods()[c].sample_size;
      csv << ExperimentName(experiment) << ',' << names[c] << ',' << sample << ','
          << levels[l].noise_px << ',' << levels[l].pitch_deg << ',' << levels[l].roll_deg << ','
          << e.trials << ',' << e.failures << ',' << trigrav::Median(e.pooled.rotation_deg) << ','
          << trigrav::Median(e.pooled.translation_deg) << ','
          << trigrav::Median(e.pooled.relative_scale) << ',' << Quantile(e.pooled.rotation_deg, 0.9)
          << ',' << Quantile(e.pooled.translation_deg, 0.9) << '\n';
    }
  }
}

void WriteStability(const std::vector<Errors>& errors) {
  std::ofstream summary = OpenCsv("stability_summary.csv");
  summary << "method,trials,failures,rotation_median_deg,rotation_p99_deg,rotation_mean_deg,"
             "rotation_max_deg,rotation_mean_log10,translation_median_deg,translation_p99_deg,"
             "translation_mean_deg,translation_max_deg,translation_mean_log10,scale_median,"
             "scale_max\n";
  std::ofstream histogram = OpenCsv("stability_histogram.csv");
  histogram << "method,quantity,log10_lo,log10_hi,count,density\n";
  const double bin = 0.25;
  const int bins = static_cast<int>((2.0 - kLogFloor) / bin);
  for (std::size_t c = 0; c < errors.size(); ++c) {
    const Errors& e = errors[c];
    const char* name = DirectMethods()[c].name;
    summary << name << ',' << e.trials << ',' << e.failures << ',';
    for (const std::vector<double>* v : {&e.pooled.rotation_deg, &e.pooled.translation_deg}) {
      summary << trigrav::Median(*v) << ',' << Quantile(*v, 0.99) << ',' << Mean(*v) << ','
              << Quantile(*v, 1.0) << ',' << MeanLog10(*v) << ',';
    }
    summary << trigrav::Median(e.pooled.relative_scale) << ','
            << Quantile(e.pooled.relative_scale, 1.0) << '\n';
    for (const auto& [quantity, values] :
         {std::make_pair("rotation", &e.pooled.rotation_deg),
          std::make_pair("translation", &e.pooled.translation_deg)}) {
      std::vector<int> counts(bins, 0);
      for (const double v : *values) {
        const int b = static_cast<int>(std::floor((Log10Error(v) - kLogFloor) / bin));
        ++counts[std::clamp(b, 0, bins - 1)];
      }
      for (int b = 0; b < bins; ++b) {
        const double density = values->empty() ? 0.0 : counts[b] / (bin * values->size());
        histogram << name << ',' << quantity << ',' << kLogFloor + b * bin << ','
                  << kLogFloor + (b + 1) * bin << ',' << counts[b] << ',' << density << '\n';
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Run time, on one thread while nothing else runs.

void RunTiming() {
  std::ofstream csv = OpenCsv("timing.csv");
  csv << "method,sample_size,solver_ns_per_call,solver_calls,ransac_ms_median,"
         "ransac_iterations_median,ransac_scenes,ransac_failures,ransac_rotation_deg,"
         "ransac_translation_deg\n";
  // Solver alone: the stability scenes (noise-free), several passes, the fastest pass counts.
  const int scenes = FLAGS_quick ? 100 : 2000;
  const int passes = FLAGS_quick ? 1 : 3;
  trigrav::SyntheticSceneOptions scene_options;
  scene_options.num_points = MaxSampleSize();
  std::mt19937_64 rng(FLAGS_seed);
  std::vector<Input> inputs;
  for (int i = 0; i < scenes; ++i)
    inputs.push_back(MakeInput(trigrav::GenerateSyntheticScene(scene_options, &rng)));
  // Robust: 200 triplets, 30 % outliers, 1 px, 3 px threshold.
  const int robust_scenes = Scaled(FLAGS_quick ? 2 : 30);
  trigrav::SyntheticSceneOptions robust_options;
  robust_options.num_points = 200;
  robust_options.outlier_ratio = 0.3;
  robust_options.pixel_noise_px = 1.0;
  std::vector<trigrav::SyntheticScene> robust;
  std::mt19937_64 robust_rng(FLAGS_seed + 7);
  for (int i = 0; i < robust_scenes; ++i)
    robust.push_back(trigrav::GenerateSyntheticScene(robust_options, &robust_rng));

  Workspace workspace;
  for (const DirectMethod& method : DirectMethods()) {
    double best_ns = std::numeric_limits<double>::infinity();
    int sink = 0;
    for (int pass = 0; pass < passes; ++pass) {
      const auto start = std::chrono::steady_clock::now();
      for (const Input& input : inputs) {
        ThreeViewPose pose;
        sink += method.solve(input, &workspace, &pose) ? 1 : 0;
      }
      const double ns =
          std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start)
              .count();
      best_ns = std::min(best_ns, ns / inputs.size());
    }
    CHECK_GE(sink, 0);
    csv << method.name << ',' << method.sample_size << ',' << best_ns << ',' << inputs.size()
        << ',';
    if (!method.has_ransac) {
      csv << "nan,nan,0,0,nan,nan\n";  // not an InitialSolver of the robust estimator
      std::fprintf(stderr, "timing %-11s %9.0f ns\n", method.name, best_ns);
      continue;
    }
    trigrav::RobustThreeViewOptions options;
    options.solver = method.solver;
    options.ransac.max_error = 3.0;
    std::vector<double> ms, iterations;
    Errors errors;
    for (std::size_t i = 0; i < robust.size(); ++i) {
      options.ransac.seed = i;
      const trigrav::ThreeViewObservations observations = trigrav::ToObservations(robust[i]);
      const auto start = std::chrono::steady_clock::now();
      const trigrav::RobustThreeViewEstimate estimate =
          trigrav::EstimateThreeViewPoseRobust(observations, options);
      ms.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count());
      iterations.push_back(estimate.iterations);
      errors.Add(robust[i], estimate.success, estimate.pose);
    }
    csv << trigrav::Median(ms) << ',' << trigrav::Median(iterations) << ',' << errors.trials << ','
        << errors.failures << ',' << trigrav::Median(errors.pooled.rotation_deg) << ','
        << trigrav::Median(errors.pooled.translation_deg) << '\n';
    std::fprintf(stderr, "timing %-11s %9.0f ns, RANSAC %.2f ms\n", method.name, best_ns,
                 trigrav::Median(ms));
  }
}

}  // namespace

int main(int argc, char** argv) {
  gflags::SetUsageMessage("The paper's synthetic experiments on trigrav's solvers; writes CSVs.");
  gflags::ParseCommandLineFlags(&argc, &argv, true);
  google::InitGoogleLogging(argv[0]);
  using trigrav::examples::RequireFlag;
  RequireFlag(FLAGS_threads >= 1 && FLAGS_threads <= 256, "--threads must be in [1, 256]");
  // Up to 100 x the paper's trial counts (500000 scenes per level) keeps every count an int.
  RequireFlag(FLAGS_trials > 0.0 && FLAGS_trials <= 100.0, "--trials must be in (0, 100]");
  RequireFlag(FLAGS_sample20_triplets >= 8, "--sample20_triplets must be >= 8");
  RequireFlag(!FLAGS_peers || kBuiltWithPeers, "--peers: built without OpenCV and OpenGV");
  // Checked before the run, so that a bad folder fails at once, not after the experiments.
  ::mkdir(FLAGS_output_dir.c_str(), 0755);
  struct stat folder;
  RequireFlag(::stat(FLAGS_output_dir.c_str(), &folder) == 0 && S_ISDIR(folder.st_mode) &&
                  ::access(FLAGS_output_dir.c_str(), W_OK) == 0,
              "cannot create or write --output_dir=" + FLAGS_output_dir);
  for (const trigrav::peers::NamedEstimator& peer : Peers()) {
    std::fprintf(stderr, "sample20 peer %s (no gravity): %s\n", peer.name.c_str(),
                 peer.description.c_str());
  }
  const auto start = std::chrono::steady_clock::now();

  // Work items: chunks of trials of every level, each with its own seed.
  const std::vector<Level> levels = Levels();
  struct Item {
    std::size_t level;
    int trials;
    std::uint64_t seed;
  };
  std::vector<Item> items;
  for (std::size_t l = 0; l < levels.size(); ++l) {
    const int chunk = levels[l].experiment == Experiment::kSample20 ? 25 : 250;
    for (int first = 0, c = 0; first < levels[l].trials; first += chunk, ++c) {
      items.push_back({l, std::min(chunk, levels[l].trials - first),
                       FLAGS_seed * 1000003ULL + l * 10007ULL + c * 101ULL});
    }
  }
  // Slow (bundle-adjustment) items first, so that the threads finish together.
  std::stable_sort(items.begin(), items.end(), [&](const Item& a, const Item& b) {
    return (levels[a.level].experiment == Experiment::kSample20) >
           (levels[b.level].experiment == Experiment::kSample20);
  });
  std::vector<std::vector<Errors>> chunks(items.size());
  std::atomic<std::size_t> done{0};
  trigrav::examples::ParallelFor(items.size(), FLAGS_threads, [&](std::size_t i) {
    chunks[i] = RunChunk(levels[items[i].level], items[i].trials, items[i].seed);
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "\r%zu / %zu chunks, %.0f s", ++done, items.size(), s);
  });
  std::fprintf(stderr, "\n");
  // Merged in item order, so that the output does not depend on which thread finished first.
  std::vector<std::vector<Errors>> results(levels.size());
  for (std::size_t l = 0; l < levels.size(); ++l)
    results[l].resize(ColumnNames(levels[l].experiment).size());
  for (std::size_t i = 0; i < items.size(); ++i) {
    for (std::size_t c = 0; c < chunks[i].size(); ++c)
      results[items[i].level][c].Append(chunks[i][c]);
  }

  for (std::size_t l = 0; l < levels.size(); ++l) {
    if (levels[l].experiment == Experiment::kStability) WriteStability(results[l]);
  }
  WriteAccuracy(levels, results, Experiment::kStability, "stability.csv");
  WriteAccuracy(levels, results, Experiment::kNoise, "noise.csv");
  WriteAccuracy(levels, results, Experiment::kPitch, "pitch.csv");
  WriteAccuracy(levels, results, Experiment::kRoll, "roll.csv");
  WriteAccuracy(levels, results, Experiment::kSample20, "sample20.csv");
  RunTiming();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf(
      "wrote stability_summary, stability_histogram, stability, noise, pitch, roll, "
      "sample20 and timing CSVs to %s in %.1f s\n",
      FLAGS_output_dir.c_str(), seconds);
  return 0;
}
