// The synthetic experiments of the paper (Section IV; protocol of derivations.md section 8.5) on
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
#include <random>
#include <string>
#include <vector>

#include "common/output_paths.h"
#include "common/paper_protocol.h"
#include "common/require_flag.h"
#include "common/tool_flags.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/statistics.h"
#include "trigrav/evaluation/synthetic_scene.h"
#include "trigrav/initializers/essential_5pt.h"
#include "trigrav/initializers/essential_8pt.h"
#include "trigrav/initializers/parallel_for.h"
#include "trigrav/initializers/robust_three_view.h"
#include "trigrav/initializers/trifocal_3pt.h"
#include "trigrav/initializers/trifocal_4pt.h"
#include "trigrav/initializers/trifocal_linear.h"
#include "trigrav/initializers/two_view_to_three_view.h"

DEFINE_string(output_dir, "paper_experiments", "Folder for the CSV files (created if missing).");
DEFINE_bool(quick, false, "Few trials per setting: a smoke test for ctest.");
DEFINE_int32(threads, 2, "Worker threads (the timing experiment always runs on one).");
DEFINE_double(trials, 1.0, "Scale of every trial count (1 = the paper's 5000 / 1000).");
DEFINE_uint64(seed, 1, "Seed of the scenes (the same scenes for every method).");

namespace {

using Rays = std::vector<Eigen::Vector3d>;
using trigrav::InitialSolver;
using trigrav::PaperExperiment;
using trigrav::ThreeViewPose;

// ---------------------------------------------------------------------------------------------
// Direct (non-RANSAC) methods on the first m triplets of a scene.

constexpr int kMaxSampleSize = 8;

struct Input {
  std::array<std::array<Rays, 3>, kMaxSampleSize + 1> rays;  // rays[m][k]: the first m triplets
  std::array<Eigen::Vector3d, 3> gravity;
};

Input MakeInput(const trigrav::SyntheticScene& scene) {
  Input input;
  for (int m = 3; m <= kMaxSampleSize; ++m) {
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

// 4pt-paper, the paper's own 4-point variant (III-D): constraint enforcement with the tensor's
// epipoles, translations read from the enforced tensor (no re-solve), no polish.
bool Paper4(const Input& in, Workspace* w, ThreeViewPose* pose) {
  const auto& x = in.rays[4];
  trigrav::Trifocal4ptOptions options;
  options.recovery = trigrav::Trifocal4ptRecovery::kEnforced;
  options.epipoles = trigrav::Trifocal4ptEpipoles::kTensorNullVectors;
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

DirectSolve SolveOf(InitialSolver solver) {
  switch (solver) {
    case InitialSolver::kTrifocal3pt:
      return &Decoupled3;
    case InitialSolver::kTrifocal3ptSextic:
      return &Sextic3;
    case InitialSolver::kTrifocal4pt:
      return &Default4;
    case InitialSolver::kTrifocalLinear:
      return &Linear7;
    case InitialSolver::kEssential5pt:
      return &TwoView<trigrav::SolveEssential5pt, 5>;
    case InitialSolver::kEssential8pt:
      return &TwoView<trigrav::SolveEssential8pt, 8>;
  }
  LOG(FATAL) << "unknown InitialSolver";
  return nullptr;
}

struct DirectMethod {
  std::string name;
  int sample_size;
  DirectSolve solve;
  bool has_ransac;  // an InitialSolver of the robust estimator
  InitialSolver solver;
};

// kInitialSolvers, then 4pt-paper.
const std::vector<DirectMethod>& DirectMethods() {
  static const std::vector<DirectMethod> methods = [] {
    std::vector<DirectMethod> list;
    for (const InitialSolver solver : trigrav::kInitialSolvers) {
      list.push_back({trigrav::InitialSolverName(solver), trigrav::MinimalSampleSize(solver),
                      SolveOf(solver), true, solver});
    }
    list.push_back({"4pt-paper", 4, &Paper4, false, InitialSolver::kTrifocal4pt});
    return list;
  }();
  return methods;
}

// ---------------------------------------------------------------------------------------------
// Experiments: the paper protocol's levels (paper_protocol.h) but sample20, each run in chunks of
// trials on the worker threads.

const std::vector<PaperExperiment> kExperiments = {PaperExperiment::kStability,
                                                   PaperExperiment::kNoise, PaperExperiment::kPitch,
                                                   PaperExperiment::kRoll};

std::vector<trigrav::LevelErrors> RunChunk(const trigrav::PaperLevel& level,
                                           int trials,
                                           std::uint64_t seed) {
  const std::size_t methods = DirectMethods().size();
  std::vector<trigrav::LevelErrors> errors(methods);
  trigrav::SyntheticSceneOptions scene_options;
  scene_options.num_points = kMaxSampleSize;
  scene_options.pixel_noise_px = level.noise_px;
  scene_options.imu_pitch_noise_deg = level.pitch_deg;
  scene_options.imu_roll_noise_deg = level.roll_deg;
  std::mt19937_64 rng(seed);
  Workspace workspace;
  for (int trial = 0; trial < trials; ++trial) {
    const trigrav::SyntheticScene scene = trigrav::GenerateSyntheticScene(scene_options, &rng);
    const Input input = MakeInput(scene);
    for (std::size_t m = 0; m < methods; ++m) {
      ThreeViewPose pose;
      const bool ok = DirectMethods()[m].solve(input, &workspace, &pose);
      errors[m].Add(scene.ground_truth, ok, pose);
    }
  }
  return errors;
}

// ---------------------------------------------------------------------------------------------
// CSV output.

// log10(trigrav::kMinLoggedError): where Log10Error shows errors below 1e-17 deg, the histogram's
// lower end.
constexpr double kLog10Floor = -17.0;

std::ofstream OpenCsv(const std::string& name) {
  const std::string path = FLAGS_output_dir + "/" + name;
  std::ofstream csv(path);
  trigrav::examples::RequireFlag(static_cast<bool>(csv), "cannot write " + path);
  csv.precision(6);
  return csv;
}

void WriteAccuracy(const std::vector<trigrav::PaperLevel>& levels,
                   const std::vector<std::vector<trigrav::LevelErrors>>& results,
                   PaperExperiment experiment) {
  std::ofstream csv = OpenCsv(std::string(trigrav::PaperExperimentName(experiment)) + ".csv");
  trigrav::WritePaperAccuracyHeader(/*with_stage=*/false, &csv);
  for (std::size_t m = 0; m < DirectMethods().size(); ++m) {
    for (std::size_t l = 0; l < levels.size(); ++l) {
      if (levels[l].experiment != experiment) continue;
      trigrav::WritePaperAccuracyRow(levels[l], DirectMethods()[m].name, "",
                                     DirectMethods()[m].sample_size, results[l][m], &csv);
    }
  }
}

void WriteStability(const std::vector<trigrav::LevelErrors>& errors) {
  std::ofstream summary = OpenCsv("stability_summary.csv");
  summary << "method,trials,failures,rotation_median_deg,rotation_p99_deg,rotation_mean_deg,"
             "rotation_max_deg,rotation_mean_log10,translation_median_deg,translation_p99_deg,"
             "translation_mean_deg,translation_max_deg,translation_mean_log10,scale_median,"
             "scale_max\n";
  std::ofstream histogram = OpenCsv("stability_histogram.csv");
  histogram << "method,quantity,log10_lo,log10_hi,count,density\n";
  const double floor = kLog10Floor;
  const double bin = 0.25;
  const int bins = static_cast<int>(std::lround((2.0 - floor) / bin));
  for (std::size_t m = 0; m < errors.size(); ++m) {
    const trigrav::LevelErrors& e = errors[m];
    const std::string& name = DirectMethods()[m].name;
    summary << name << ',' << e.trials << ',' << e.failures << ',';
    for (const std::vector<double>* v : {&e.pooled.rotation_deg, &e.pooled.translation_deg}) {
      summary << trigrav::Median(*v) << ',' << trigrav::Quantile(*v, 0.99) << ','
              << trigrav::Mean(*v) << ',' << trigrav::Quantile(*v, 1.0) << ','
              << trigrav::MeanLog10Error(*v) << ',';
    }
    summary << trigrav::Median(e.pooled.relative_scale) << ','
            << trigrav::Quantile(e.pooled.relative_scale, 1.0) << '\n';
    for (const auto& [quantity, values] :
         {std::make_pair("rotation", &e.pooled.rotation_deg),
          std::make_pair("translation", &e.pooled.translation_deg)}) {
      std::vector<int> counts(bins, 0);
      for (const double v : *values) {
        const int b = static_cast<int>(std::floor((trigrav::Log10Error(v) - floor) / bin));
        ++counts[std::clamp(b, 0, bins - 1)];
      }
      for (int b = 0; b < bins; ++b) {
        const double density = values->empty() ? 0.0 : counts[b] / (bin * values->size());
        histogram << name << ',' << quantity << ',' << floor + b * bin << ','
                  << floor + (b + 1) * bin << ',' << counts[b] << ',' << density << '\n';
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Run time, on one thread while nothing else runs.

int Scaled(int trials) { return std::max(1, static_cast<int>(std::lround(trials * FLAGS_trials))); }

void RunTiming() {
  std::ofstream csv = OpenCsv("timing.csv");
  csv << "method,sample_size,solver_ns_per_call,solver_calls,ransac_ms_median,"
         "ransac_iterations_median,ransac_scenes,ransac_failures,ransac_rotation_deg,"
         "ransac_translation_deg\n";
  // Solver alone: the stability scenes (noise-free), several passes, the fastest pass counts.
  const int scenes = FLAGS_quick ? 100 : 2000;
  const int passes = FLAGS_quick ? 1 : 3;
  trigrav::SyntheticSceneOptions scene_options;
  scene_options.num_points = kMaxSampleSize;
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
      std::fprintf(stderr, "timing %-11s %9.0f ns\n", method.name.c_str(), best_ns);
      continue;
    }
    trigrav::RobustThreeViewOptions options;
    options.solver = method.solver;
    options.ransac.max_error = 3.0;
    std::vector<double> ms, iterations;
    trigrav::LevelErrors errors;
    for (std::size_t i = 0; i < robust.size(); ++i) {
      options.ransac.seed = i;
      const trigrav::ThreeViewObservations observations = trigrav::ToObservations(robust[i]);
      const auto start = std::chrono::steady_clock::now();
      const trigrav::RobustThreeViewEstimate estimate =
          trigrav::EstimateThreeViewPoseRobust(observations, options);
      ms.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count());
      iterations.push_back(estimate.ransac.iterations);
      errors.Add(robust[i].ground_truth, estimate.success, estimate.pose);
    }
    csv << trigrav::Median(ms) << ',' << trigrav::Median(iterations) << ',' << errors.trials << ','
        << errors.failures << ',' << trigrav::Median(errors.pooled.rotation_deg) << ','
        << trigrav::Median(errors.pooled.translation_deg) << '\n';
    std::fprintf(stderr, "timing %-11s %9.0f ns, RANSAC %.2f ms\n", method.name.c_str(), best_ns,
                 trigrav::Median(ms));
  }
}

}  // namespace

int main(int argc, char** argv) {
  trigrav::examples::ParseToolFlags(
      "The paper's synthetic experiments on trigrav's solvers; writes CSVs.", __FILE__, &argc,
      &argv);
  google::InitGoogleLogging(argv[0]);
  using trigrav::examples::RequireFlag;
  RequireFlag(FLAGS_threads >= 1 && FLAGS_threads <= 256, "--threads must be in [1, 256]");
  // Up to 100 x the paper's trial counts (500000 scenes per level) keeps every count an int.
  RequireFlag(FLAGS_trials > 0.0 && FLAGS_trials <= 100.0, "--trials must be in (0, 100]");
  // Checked before the run, so that a bad folder fails at once, not after the experiments.
  std::vector<trigrav::examples::ToolPath> outputs;
  for (const std::string name : {"stability_summary", "stability_histogram", "timing"}) {
    outputs.push_back({name + ".csv of --output_dir", FLAGS_output_dir + "/" + name + ".csv"});
  }
  for (const PaperExperiment experiment : kExperiments) {
    const std::string name = trigrav::PaperExperimentName(experiment);
    outputs.push_back({name + ".csv of --output_dir", FLAGS_output_dir + "/" + name + ".csv"});
  }
  trigrav::examples::RequireOutputsApartFromInputs({}, outputs);
  ::mkdir(FLAGS_output_dir.c_str(), 0755);
  struct stat folder;
  RequireFlag(::stat(FLAGS_output_dir.c_str(), &folder) == 0 && S_ISDIR(folder.st_mode) &&
                  ::access(FLAGS_output_dir.c_str(), W_OK) == 0,
              "cannot create or write --output_dir=" + FLAGS_output_dir);
  const auto start = std::chrono::steady_clock::now();

  const std::vector<trigrav::PaperLevel> levels = trigrav::PaperLevels(FLAGS_quick, FLAGS_trials);
  const std::vector<trigrav::PaperChunk> chunks =
      trigrav::PaperChunks(levels, kExperiments, FLAGS_seed);
  const std::vector<std::vector<trigrav::LevelErrors>> results = trigrav::RunPaperChunks(
      levels, chunks, DirectMethods().size(), FLAGS_threads, RunChunk,
      [&](std::size_t done, std::size_t total) {
        const double s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::fprintf(stderr, "\r%zu / %zu chunks, %.0f s", done, total, s);
      });
  std::fprintf(stderr, "\n");

  for (std::size_t l = 0; l < levels.size(); ++l) {
    if (levels[l].experiment == PaperExperiment::kStability) WriteStability(results[l]);
  }
  for (const PaperExperiment experiment : kExperiments) WriteAccuracy(levels, results, experiment);
  RunTiming();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf(
      "wrote stability_summary, stability_histogram, stability, noise, pitch, roll and timing CSVs "
      "to %s in %.1f s\n",
      FLAGS_output_dir.c_str(), seconds);
  return 0;
}
