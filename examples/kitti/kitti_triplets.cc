// The paper's KITTI evaluation (Section IV-B): SIFT point triplets on consecutive frames of a KITTI
// odometry sequence, every method in RANSAC with the same threshold, raw and refined (three-view
// bundle adjustment, yaw-only and gravity-prior), errors of views 2 and 3 against ground truth,
// chained trajectories and their ATE. Gravity of each frame from the ground-truth pitch and roll,
// optionally with IMU noise. With --peers, OpenCV's and OpenGV's five-point RANSAC
// (examples/peers/) run as more methods, and a table of ratios trigrav / peer follows.
//
//   kitti_triplets --kitti_dir=../shared/data/kitti --sequence=00 --output_dir=kitti_00
//
// Writes to --output_dir: poses.csv (one row per triplet, method and stage), summary.csv (medians,
// failures, time, ATE per method and stage), trajectories.csv (chained, aligned camera centres;
// plot with plot_kitti_trajectories.py), frames.csv (per frame: SIFT time, tracks and matching
// time of the triplet it starts). Features (per frame) and matches (per pair) are cached in
// --cache_dir.
//
// Defaults are the settings chosen on 00 and 02 (README.md, "Settings").

#include <gflags/gflags.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <opencv2/core.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "common/output_paths.h"
#include "common/require_flag.h"
#include "common/tool_flags.h"
#include "kitti_methods.h"
#include "kitti_report.h"
#include "kitti_sequence.h"
#include "sequence_evaluation.h"
#include "trigrav/evaluation/statistics.h"
#include "trigrav/initializers/initial_solver.h"
#ifdef TRIGRAV_WITH_PEERS
#include "peer_methods.h"
#endif

DEFINE_string(kitti_dir,
              "",
              "KITTI odometry folder with sequences/XX/image_0, sequences/XX/calib.txt and "
              "poses/XX.txt (required).");
DEFINE_string(sequence, "00", "Sequence: two digits, e.g. 00.");
DEFINE_int32(first_frame, 0, "First frame of the range.");
DEFINE_int32(last_frame, 299, "Last frame of the range (included).");
DEFINE_string(output_dir, "", "Folder for the CSVs (created; required).");
DEFINE_string(cache_dir,
              "",
              "Feature and match cache folder (created; must not be inside --kitti_dir). Default: "
              "<output_dir>/feature_cache.");
DEFINE_string(methods,
              "all",
              "Comma-separated trigrav methods (3pt, 3pt-sextic, 4pt, 7pt-linear, 5pt, 8pt), or "
              "'all' for every one in that order.");
DEFINE_string(refine,
              "3pt",
              "Methods whose estimate is also refined (yaw-only and gravity-prior bundle "
              "adjustment): a comma-separated subset of --methods, 'all' or 'none'.");
DEFINE_bool(peers,
            false,
            "Also run the OpenCV / OpenGV five-point peers (examples/peers/), if built with them, "
            "and print the ratios trigrav / peer.");
DEFINE_double(threshold_px,
              1.5,
              "RANSAC inlier threshold (largest reprojection error over the three views, px), the "
              "same for every method, peers included; also the re-classification threshold of the "
              "refinement.");
DEFINE_double(confidence, 0.9999, "RANSAC confidence of an all-inlier sample.");
DEFINE_int32(min_iterations, 100, "RANSAC minimum number of samples.");
DEFINE_int32(max_iterations, 10000, "RANSAC maximum number of samples.");
DEFINE_bool(local_optimization, true, "RANSAC local optimisation (LO+, ransac.h).");
DEFINE_bool(check_gravity,
            true,
            "Compare with a gravity-free estimate also after a success "
            "(RobustThreeViewOptions::check_gravity_after_success).");
DEFINE_string(mistake,
              "none",
              "A user's mistake applied to every triplet's tracks (track_mistakes.h): none, "
              "views-2-3-swapped, other-intrinsics, half-resolution, row-column, five-tracks, "
              "gravity-sign-camera-2.");
DEFINE_double(imu_noise_deg,
              0.0,
              "IMU noise: sigma (deg) of each frame's pitch and roll error; 0 = exact gravity.");
DEFINE_double(gravity_sigma_deg,
              -1.0,
              "Gravity sigma of the gravity-prior refinement (deg); default (-1): --imu_noise_deg, "
              "or 0.03 with exact gravity (the size of the disagreement between the images and "
              "the ground-truth tilt: a free refinement moves the tilt by about 0.03 deg).");
DEFINE_double(pixel_sigma_px, 0.5, "Pixel noise that weights the gravity prior against pixels.");
DEFINE_double(loss_px, 1.0, "Huber scale of the bundle adjustment's pixel residuals.");
DEFINE_string(
    engine,
    trigrav::EngineName(trigrav::ThreeViewBundleAdjustmentOptions().engine),
    "Bundle-adjustment engine (ThreeViewBundleAdjustmentOptions::Engine, the same optimum): "
    "ceres_points_eliminated (the library's default) or ceres (a block per point).");
DEFINE_int32(reclassification_rounds,
             1,
             "Refinement: re-classify the tracks against the refined pose and refine again, up to "
             "this many times (InitializeAndRefineOptions).");
DEFINE_int32(sift_max_features, 0, "SIFT: keep the strongest n keypoints per frame; 0 = all.");
DEFINE_double(sift_contrast_threshold, 0.04, "SIFT contrast threshold.");
DEFINE_double(ratio, 0.8, "Lowe's ratio test.");
DEFINE_bool(mutual, true, "Keep a pair match only if it is the nearest neighbour both ways.");
DEFINE_double(window_x_px, 250.0, "Matching search window: largest |dx| between frames (px).");
DEFINE_double(window_y_px, 120.0, "Matching search window: largest |dy| between frames (px).");
DEFINE_uint64(seed, 1, "Seed of the IMU noise and of RANSAC (triplet f uses seed + f).");
DEFINE_int32(threads, 2, "Worker threads.");
DEFINE_bool(markdown, false, "Print the tables as markdown instead of fixed-width text.");

namespace {

namespace fs = std::filesystem;
namespace kitti = trigrav::kitti;
using trigrav::InitialSolver;
using trigrav::examples::IsWithin;
using trigrav::examples::RequireFlag;

// The files written to --output_dir.
constexpr const char* kOutputCsvs[] = {"poses.csv", "summary.csv", "trajectories.csv",
                                       "frames.csv"};

// Exact gravity: the size of the disagreement between the images and the ground-truth tilt.
constexpr double kExactGravitySigmaDeg = 0.03;

std::vector<std::string> SplitCommas(const std::string& list) {
  std::vector<std::string> items;
  std::stringstream stream(list);
  std::string item;
  while (std::getline(stream, item, ',')) {
    if (!item.empty()) items.push_back(item);
  }
  return items;
}

// The gravity-prior refinement's sigma (deg): --gravity_sigma_deg, else the IMU noise, else the
// exact-gravity default.
double GravitySigmaDegFromFlags() {
  if (FLAGS_gravity_sigma_deg > 0.0) return FLAGS_gravity_sigma_deg;
  return FLAGS_imu_noise_deg > 0.0 ? FLAGS_imu_noise_deg : kExactGravitySigmaDeg;
}

// A bad value prints "error: <message>" and exits with status 2 (common/require_flag.h). With
// TrigravMethodsFromFlags, everything is checked before any file is read.
void ValidateFlags() {
  RequireFlag(!FLAGS_kitti_dir.empty(), "--kitti_dir is required (the KITTI odometry folder)");
  RequireFlag(fs::is_directory(FLAGS_kitti_dir), "--kitti_dir: no folder " + FLAGS_kitti_dir);
  RequireFlag(!FLAGS_output_dir.empty(), "--output_dir is required (folder for the CSVs)");
  RequireFlag(std::regex_match(FLAGS_sequence, std::regex("[0-9][0-9]")),
              "--sequence must be two digits (e.g. 00), not \"" + FLAGS_sequence + "\"");
  RequireFlag(FLAGS_first_frame >= 0, "--first_frame must be >= 0");
  RequireFlag(FLAGS_last_frame >= FLAGS_first_frame + 2,
              "--last_frame must be at least --first_frame + 2 (one triplet)");
  RequireFlag(FLAGS_cache_dir.empty() || !IsWithin(FLAGS_cache_dir, FLAGS_kitti_dir),
              "--cache_dir (" + FLAGS_cache_dir + ") must not be inside the dataset --kitti_dir");
  RequireFlag(!IsWithin(FLAGS_output_dir, FLAGS_kitti_dir),
              "--output_dir must not be inside the dataset --kitti_dir");
  // The CSVs, apart from the dataset and from --flagfile's files.
  std::vector<trigrav::examples::ToolPath> outputs;
  for (const char* file : kOutputCsvs) {
    outputs.push_back(
        {std::string(file) + " of --output_dir", (fs::path(FLAGS_output_dir) / file).string()});
  }
  trigrav::examples::RequireOutputsApartFromInputs(
      {{"--kitti_dir", FLAGS_kitti_dir, trigrav::examples::ToolPath::kFolder}}, outputs);
  RequireFlag(FLAGS_threshold_px > 0.0 && std::isfinite(FLAGS_threshold_px),
              "--threshold_px must be positive and finite");
  RequireFlag(FLAGS_confidence > 0.0 && FLAGS_confidence < 1.0, "--confidence must be in (0, 1)");
  RequireFlag(FLAGS_min_iterations >= 0, "--min_iterations must be >= 0");
  RequireFlag(FLAGS_max_iterations >= 1 && FLAGS_max_iterations >= FLAGS_min_iterations,
              "--max_iterations must be >= 1 and >= --min_iterations");
  RequireFlag(FLAGS_imu_noise_deg >= 0.0 && std::isfinite(FLAGS_imu_noise_deg),
              "--imu_noise_deg must be >= 0 and finite");
  RequireFlag(FLAGS_gravity_sigma_deg == -1.0 ||
                  (FLAGS_gravity_sigma_deg > 0.0 && std::isfinite(FLAGS_gravity_sigma_deg)),
              "--gravity_sigma_deg must be positive and finite (or -1 for the default)");
  RequireFlag(FLAGS_pixel_sigma_px > 0.0 && std::isfinite(FLAGS_pixel_sigma_px),
              "--pixel_sigma_px must be positive and finite");
  RequireFlag(FLAGS_loss_px > 0.0 && std::isfinite(FLAGS_loss_px),
              "--loss_px must be positive and finite");
  RequireFlag(FLAGS_reclassification_rounds >= 0, "--reclassification_rounds must be >= 0");
  RequireFlag(FLAGS_sift_max_features >= 0, "--sift_max_features must be >= 0");
  RequireFlag(FLAGS_sift_contrast_threshold > 0.0 && std::isfinite(FLAGS_sift_contrast_threshold),
              "--sift_contrast_threshold must be positive and finite");
  RequireFlag(FLAGS_ratio > 0.0 && FLAGS_ratio <= 1.0, "--ratio must be in (0, 1]");
  RequireFlag(FLAGS_window_x_px > 0.0 && FLAGS_window_y_px > 0.0 &&
                  std::isfinite(FLAGS_window_x_px) && std::isfinite(FLAGS_window_y_px),
              "--window_x_px and --window_y_px must be positive and finite");
  RequireFlag(FLAGS_threads >= 1 && FLAGS_threads <= 256, "--threads must be in 1..256");
#ifndef TRIGRAV_WITH_PEERS
  RequireFlag(!FLAGS_peers, "--peers: built without OpenCV's calib3d and OpenGV (no peers)");
#endif
}

// The methods of a --methods or --refine list: 'all' is every method of kInitialSolvers.
std::vector<InitialSolver> SolversFromList(const std::string& list, const char* flag) {
  std::vector<InitialSolver> solvers;
  if (list == "all") return {trigrav::kInitialSolvers.begin(), trigrav::kInitialSolvers.end()};
  for (const std::string& name : SplitCommas(list)) {
    InitialSolver solver;
    RequireFlag(trigrav::ParseInitialSolver(name, &solver),
                std::string(flag) + ": unknown method \"" + name + "\" (expected " +
                    trigrav::InitialSolverNames() + ")");
    solvers.push_back(solver);
  }
  return solvers;
}

// trigrav's methods of --methods, those of --refine also refined, with the RANSAC and bundle
// adjustment settings of the flags.
std::vector<kitti::Method> TrigravMethodsFromFlags() {
  const std::vector<InitialSolver> solvers = SolversFromList(FLAGS_methods, "--methods");
  RequireFlag(!solvers.empty(), "--methods is empty");
  const std::vector<InitialSolver> refined = FLAGS_refine == "none"
                                                 ? std::vector<InitialSolver>()
                                                 : SolversFromList(FLAGS_refine, "--refine");
  // The default (3pt) is dropped quietly when 3pt is not among --methods; an explicit list must be.
  const bool refine_is_default = gflags::GetCommandLineFlagInfoOrDie("refine").is_default;
  for (const InitialSolver solver : refined) {
    RequireFlag(refine_is_default || FLAGS_refine == "all" ||
                    std::find(solvers.begin(), solvers.end(), solver) != solvers.end(),
                std::string("--refine: \"") + trigrav::InitialSolverName(solver) +
                    "\" is not in --methods");
  }
  trigrav::InitializeAndRefineOptions options;
  options.robust.ransac.max_error = FLAGS_threshold_px;
  options.robust.ransac.confidence = FLAGS_confidence;
  options.robust.ransac.min_iterations = FLAGS_min_iterations;
  options.robust.ransac.max_iterations = FLAGS_max_iterations;
  options.robust.ransac.local_optimization = FLAGS_local_optimization;
  options.robust.check_gravity_after_success = FLAGS_check_gravity;
  options.reclassification_rounds = FLAGS_reclassification_rounds;
  options.bundle_adjustment.loss_scale_px = FLAGS_loss_px;
  RequireFlag(trigrav::ParseEngine(FLAGS_engine, &options.bundle_adjustment.engine),
              "--engine must be " + trigrav::EngineNames());
  // Ceres stops at a relative cost change of 1e-6 (library default 1e-8): on 00 and 02 the medians
  // agree to 0.001 deg and the refinement takes a quarter fewer iterations.
  options.bundle_adjustment.function_tolerance = 1e-6;
  options.bundle_adjustment.pixel_sigma_px = FLAGS_pixel_sigma_px;
  options.bundle_adjustment.gravity_sigma_deg = GravitySigmaDegFromFlags();
  std::vector<kitti::Method> methods;
  for (const InitialSolver solver : solvers) {
    const bool refine = std::find(refined.begin(), refined.end(), solver) != refined.end();
    methods.push_back(kitti::TrigravMethod(solver, refine, options));
  }
  return methods;
}

kitti::SequenceEvaluationOptions EvaluationOptionsFromFlags(const std::string& cache_dir) {
  kitti::SequenceEvaluationOptions options;
  options.cache_dir = cache_dir;
  options.sift.max_features = FLAGS_sift_max_features;
  options.sift.contrast_threshold = FLAGS_sift_contrast_threshold;
  options.match.ratio = FLAGS_ratio;
  options.match.mutual = FLAGS_mutual;
  options.match.window_x_px = FLAGS_window_x_px;
  options.match.window_y_px = FLAGS_window_y_px;
  options.imu_noise_deg = FLAGS_imu_noise_deg;
  RequireFlag(kitti::ParseTrackMistake(FLAGS_mistake, &options.mistake),
              "--mistake: unknown mistake \"" + FLAGS_mistake + "\"");
  options.seed = FLAGS_seed;
  options.threads = FLAGS_threads;
  return options;
}

// Per frame f: SIFT time if detected in this run (empty if from the cache); tracks and loading /
// matching time of the triplet (f, f+1, f+2) (empty for the last two frames).
bool WriteFramesCsv(const std::string& path,
                    const kitti::KittiSequence& sequence,
                    const kitti::SequenceEvaluation& evaluation) {
  std::ofstream frames(path);
  frames << "frame,sift_ms,triplet_tracks,triplet_features_ms,triplet_matching_ms\n";
  for (int i = 0; i < sequence.num_frames(); ++i) {
    frames << sequence.first_frame + i << ",";
    if (evaluation.detect_ms[i] >= 0.0) frames << evaluation.detect_ms[i];
    if (i < static_cast<int>(evaluation.triplets.size())) {
      const kitti::TripletData& s = evaluation.triplets[i];
      frames << "," << s.tracks.size() << "," << 1e3 * s.features_s << "," << 1e3 * s.matching_s
             << "\n";
    } else {
      frames << ",,,\n";
    }
  }
  return static_cast<bool>(frames);
}

}  // namespace

int main(int argc, char** argv) {
  trigrav::examples::ParseToolFlags(
      "KITTI three-view evaluation: kitti_triplets --kitti_dir=DIR --sequence=00 "
      "--output_dir=OUT",
      __FILE__, &argc, &argv);
  ValidateFlags();

  std::vector<kitti::Method> methods = TrigravMethodsFromFlags();
  const std::size_t num_trigrav_methods = methods.size();
#ifdef TRIGRAV_WITH_PEERS
  if (FLAGS_peers) kitti::AppendPeerMethods(FLAGS_threshold_px, &methods);
#endif
  kitti::KittiSequence sequence;
  std::string error;
  RequireFlag(kitti::LoadKittiSequence(FLAGS_kitti_dir, FLAGS_sequence, FLAGS_first_frame,
                                       FLAGS_last_frame, &sequence, &error),
              error);
  const std::string cache_dir = FLAGS_cache_dir.empty()
                                    ? (fs::path(FLAGS_output_dir) / "feature_cache").string()
                                    : FLAGS_cache_dir;
  std::error_code ec;
  fs::create_directories(FLAGS_output_dir, ec);
  RequireFlag(!ec, "--output_dir: cannot create " + FLAGS_output_dir + ": " + ec.message());
  fs::create_directories(cache_dir, ec);
  RequireFlag(!ec, "--cache_dir: cannot create " + cache_dir + ": " + ec.message());
  // Parallelism is ours (one frame or triplet per thread); OpenCV's own threads would
  // oversubscribe.
  cv::setNumThreads(1);

  kitti::SequenceEvaluation evaluation;
  RequireFlag(kitti::EvaluateSequence(sequence, methods, EvaluationOptionsFromFlags(cache_dir),
                                      &evaluation, &error),
              error);

  const fs::path out(FLAGS_output_dir);
  for (const auto& [file, written] :
       {std::pair{"poses.csv",
                  kitti::WritePoseRecordsCsv((out / "poses.csv").string(), evaluation.records)},
        std::pair{"summary.csv",
                  kitti::WriteSummaryCsv((out / "summary.csv").string(), evaluation.summaries)},
        std::pair{"trajectories.csv",
                  kitti::WriteTrajectoriesCsv((out / "trajectories.csv").string(), sequence,
                                              evaluation.summaries)},
        std::pair{"frames.csv",
                  WriteFramesCsv((out / "frames.csv").string(), sequence, evaluation)}}) {
    RequireFlag(written, std::string("cannot write ") + (out / file).string());
  }

  std::vector<double> tracks, matching_ms, detected_ms;
  for (const kitti::TripletData& s : evaluation.triplets) {
    tracks.push_back(static_cast<double>(s.tracks.size()));
    matching_ms.push_back(1e3 * s.matching_s);
  }
  for (const double ms : evaluation.detect_ms) {
    if (ms >= 0.0) detected_ms.push_back(ms);
  }
  const kitti::TableFormat format =
      FLAGS_markdown ? kitti::TableFormat::kMarkdown : kitti::TableFormat::kText;
  std::printf(
      "KITTI %s frames %d-%d (%d triplets), threshold %.2f px, IMU noise %.3f deg, gravity "
      "sigma %.3f deg\n",
      sequence.sequence.c_str(), sequence.first_frame, sequence.last_frame,
      sequence.num_frames() - 2, FLAGS_threshold_px, FLAGS_imu_noise_deg,
      GravitySigmaDegFromFlags());
  std::printf("camera (P0 of calib.txt): fx %g, fy %g, cx %g, cy %g px\n", sequence.camera.fx,
              sequence.camera.fy, sequence.camera.cx, sequence.camera.cy);
  std::printf("tracks per triplet: median %.0f, min %.0f\n", trigrav::Median(tracks),
              *std::min_element(tracks.begin(), tracks.end()));
  std::printf(
      "errors: median over triplets of views 2 and 3 pooled (deg); ATE: RMSE (m) of the chained "
      "trajectory after rigid alignment\n");
  std::fflush(stdout);
  kitti::PrintSummaryTable(evaluation.summaries, std::cout, format);
  std::cout << "verdict (successes; failures by cause; messages in poses.csv):\n";
  kitti::PrintVerdictCounts(evaluation.records, std::cout);
  if (methods.size() > num_trigrav_methods) {
    // Rows: trigrav's methods and stages; columns: the peers.
    std::vector<const kitti::MethodSummary*> rows, columns;
    for (const kitti::MethodSummary& s : evaluation.summaries) {
      const bool is_trigrav =
          std::any_of(methods.begin(), methods.begin() + num_trigrav_methods,
                      [&](const kitti::Method& m) { return m.name == s.method; });
      (is_trigrav ? rows : columns).push_back(&s);
    }
    std::cout << "ratios trigrav / peer: mean time per triplet / median rotation error / median "
                 "translation error\n";
    kitti::PrintRatioTable(rows, columns, std::cout, format);
  }
  std::cout << std::flush;
  std::printf(
      "time: features %.1f s wall (%zu frames detected, median %.0f ms per frame on one thread; "
      "%d from the cache), triplets %.1f s wall (matching median %.1f ms per triplet), %d "
      "threads\n",
      evaluation.features_wall_s, detected_ms.size(),
      detected_ms.empty() ? 0.0 : trigrav::Median(detected_ms),
      sequence.num_frames() - static_cast<int>(detected_ms.size()), evaluation.triplets_wall_s,
      trigrav::Median(matching_ms), FLAGS_threads);
  return 0;
}
