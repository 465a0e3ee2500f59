// The paper's KITTI evaluation (Section IV-B): SIFT point triplets on consecutive frames of a KITTI
// odometry sequence, every method in RANSAC with the same threshold, raw and refined (three-view
// bundle adjustment, yaw-only and gravity-prior), errors of views 2 and 3 against ground truth,
// chained trajectories and their ATE. Gravity of each frame from the ground-truth pitch and roll,
// optionally with IMU noise.
//
//   kitti_triplets --kitti_dir=../shared/data/kitti --sequence=00 --output_dir=kitti_00
//
// Writes to --output_dir: poses.csv (one row per triplet, method and stage), summary.csv (medians,
// failures, time, ATE per method and stage), trajectories.csv (chained, aligned camera centres;
// plot with plot_kitti_trajectories.py), frames.csv (per frame: SIFT time, tracks and matching
// time of the triplet it starts). Features are cached per frame in --cache_dir.

#include <gflags/gflags.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <opencv2/core.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../require_flag.h"
#include "descriptor_matching.h"
#include "kitti_methods.h"
#ifdef TRIGRAV_KITTI_WITH_PEERS
#include "peer_methods.h"
#endif
#include "kitti_report.h"
#include "kitti_sequence.h"
#include "sift_features.h"
#include "triplet_source.h"

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
              "Feature cache folder (created); default <output_dir>/feature_cache. Must not be "
              "inside --kitti_dir.");
DEFINE_string(methods,
              "8pt,5pt,7pt-linear,3pt,3pt-sextic,4pt",
              "Comma-separated methods: 8pt, 5pt, 7pt-linear, 3pt, 3pt-sextic, 4pt.");
DEFINE_string(refine,
              "3pt",
              "Methods whose estimate is also refined (yaw-only and gravity-prior bundle "
              "adjustment): a comma-separated subset of --methods, 'all' or 'none'.");
DEFINE_double(threshold_px,
              1.5,
              "RANSAC inlier threshold (largest reprojection error over the three views, px), the "
              "same for every method; also the re-classification threshold of the refinement.");
DEFINE_double(confidence, 0.9999, "RANSAC confidence of an all-inlier sample.");
DEFINE_int32(min_iterations, 100, "RANSAC minimum number of samples.");
DEFINE_int32(max_iterations, 10000, "RANSAC maximum number of samples.");
DEFINE_bool(local_optimization, true, "RANSAC local optimisation (LO+, ransac.h).");
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
DEFINE_bool(peers,
            false,
            "Also run the OpenCV / OpenGV five-point peers (examples/peers/), if built with them.");

namespace {

namespace fs = std::filesystem;
using trigrav::examples::RequireFlag;
namespace kitti = trigrav::kitti;

std::vector<std::string> SplitCommas(const std::string& list) {
  std::vector<std::string> items;
  std::stringstream stream(list);
  std::string item;
  while (std::getline(stream, item, ',')) {
    if (!item.empty()) items.push_back(item);
  }
  return items;
}

// True when `path` is `folder` or below it (after resolving symlinks, "." and ".."); false when
// either cannot be resolved.
bool IsInside(const fs::path& path, const fs::path& folder) {
  std::error_code ec_path, ec_folder;
  const fs::path p = fs::weakly_canonical(path, ec_path);
  const fs::path f = fs::weakly_canonical(folder, ec_folder);
  if (ec_path || ec_folder) return false;
  auto pi = p.begin();
  for (auto fi = f.begin(); fi != f.end(); ++fi, ++pi) {
    if (fi->empty()) continue;  // trailing separator
    if (pi == p.end() || *pi != *fi) return false;
  }
  return true;
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// "\r<stage> done/total" on stderr, from any thread.
class Progress {
 public:
  Progress(const char* stage, int total) : stage_(stage), total_(total) { Print(0); }
  void Step() { Print(++done_); }
  ~Progress() { std::cerr << "\n"; }

 private:
  void Print(int done) {
    const std::lock_guard<std::mutex> lock(mutex_);
    std::cerr << "\r" << stage_ << " " << done << "/" << total_ << std::flush;
  }
  const char* stage_;
  int total_;
  std::atomic<int> done_{0};
  std::mutex mutex_;
};

// Runs work(i) for i in [0, n) on `threads` threads, items handed out in order.
template <typename Work>
void ParallelFor(int n, int threads, Work work) {
  std::atomic<int> next{0};
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) {
    pool.emplace_back([&] {
      for (int i = next++; i < n; i = next++) work(i);
    });
  }
  for (std::thread& thread : pool) thread.join();
}

void ValidateFlags() {
  RequireFlag(!FLAGS_kitti_dir.empty(), "--kitti_dir is required (the KITTI odometry folder)");
  RequireFlag(fs::is_directory(FLAGS_kitti_dir), "--kitti_dir: no folder " + FLAGS_kitti_dir);
  RequireFlag(std::regex_match(FLAGS_sequence, std::regex("[0-9][0-9]")),
              "--sequence must be two digits (e.g. 00), not \"" + FLAGS_sequence + "\"");
  RequireFlag(FLAGS_first_frame >= 0, "--first_frame must be >= 0");
  RequireFlag(FLAGS_last_frame >= FLAGS_first_frame + 2,
              "--last_frame must be at least --first_frame + 2 (one triplet)");
  RequireFlag(!FLAGS_output_dir.empty(), "--output_dir is required (folder for the CSVs)");
  const std::string cache_dir = FLAGS_cache_dir.empty()
                                    ? (fs::path(FLAGS_output_dir) / "feature_cache").string()
                                    : FLAGS_cache_dir;
  RequireFlag(!IsInside(cache_dir, FLAGS_kitti_dir),
              "--cache_dir (" + cache_dir + ") must not be inside the dataset --kitti_dir");
  RequireFlag(!IsInside(FLAGS_output_dir, FLAGS_kitti_dir),
              "--output_dir must not be inside the dataset --kitti_dir");
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
}

}  // namespace

int main(int argc, char** argv) {
  gflags::SetUsageMessage(
      "KITTI three-view evaluation: kitti_triplets --kitti_dir=DIR --sequence=00 "
      "--output_dir=OUT");
  gflags::ParseCommandLineFlags(&argc, &argv, true);
  ValidateFlags();

  kitti::KittiSequence sequence;
  std::string error;
  const bool loaded = kitti::LoadKittiSequence(FLAGS_kitti_dir, FLAGS_sequence, FLAGS_first_frame,
                                               FLAGS_last_frame, &sequence, &error);
  RequireFlag(loaded, error);
  const std::vector<std::string> method_names = SplitCommas(FLAGS_methods);
  RequireFlag(!method_names.empty(), "--methods is empty");
  kitti::TrigravMethodSettings settings;
  settings.ransac.max_error = FLAGS_threshold_px;
  settings.ransac.confidence = FLAGS_confidence;
  settings.ransac.min_iterations = FLAGS_min_iterations;
  settings.ransac.max_iterations = FLAGS_max_iterations;
  settings.ransac.local_optimization = FLAGS_local_optimization;
  // The default (3pt) is dropped quietly when 3pt is not among --methods; an explicit list must be.
  const bool refine_is_default = gflags::GetCommandLineFlagInfoOrDie("refine").is_default;
  const std::vector<std::string> refine = FLAGS_refine == "all"    ? method_names
                                          : FLAGS_refine == "none" ? std::vector<std::string>()
                                                                   : SplitCommas(FLAGS_refine);
  for (const std::string& name : refine) {
    if (std::find(method_names.begin(), method_names.end(), name) != method_names.end()) {
      settings.refined_methods.push_back(name);
    } else {
      RequireFlag(refine_is_default, "--refine: \"" + name + "\" is not in --methods");
    }
  }
  settings.bundle_adjustment.loss_scale_px = FLAGS_loss_px;
  settings.reclassification_rounds = FLAGS_reclassification_rounds;
  // Ceres stops at a relative cost change of 1e-6 (library default 1e-8): on 00 and 02 the medians
  // agree to 0.001 deg and the refinement takes a quarter fewer iterations.
  settings.bundle_adjustment.function_tolerance = 1e-6;
  settings.bundle_adjustment.pixel_sigma_px = FLAGS_pixel_sigma_px;
  settings.bundle_adjustment.gravity_sigma_deg = 0.03;  // exact gravity (see the flag)
  if (FLAGS_gravity_sigma_deg > 0.0) {
    settings.bundle_adjustment.gravity_sigma_deg = FLAGS_gravity_sigma_deg;
  } else if (FLAGS_imu_noise_deg > 0.0) {
    settings.bundle_adjustment.gravity_sigma_deg = FLAGS_imu_noise_deg;
  }
  std::vector<kitti::Method> methods;
  const bool methods_ok = kitti::MakeTrigravMethods(method_names, settings, &methods, &error);
  RequireFlag(methods_ok, "--methods: " + error);
#ifdef TRIGRAV_KITTI_WITH_PEERS
  if (FLAGS_peers) kitti::AppendPeerMethods(FLAGS_threshold_px, &methods);
#else
  RequireFlag(!FLAGS_peers, "--peers: built without OpenCV's calib3d and OpenGV (no peers)");
#endif

  const std::string cache_dir = FLAGS_cache_dir.empty()
                                    ? (fs::path(FLAGS_output_dir) / "feature_cache").string()
                                    : FLAGS_cache_dir;
  std::error_code ec;
  fs::create_directories(FLAGS_output_dir, ec);
  RequireFlag(!ec, "--output_dir: cannot create " + FLAGS_output_dir + ": " + ec.message());
  fs::create_directories(cache_dir, ec);
  RequireFlag(!ec, "--cache_dir: cannot create " + cache_dir + ": " + ec.message());

  const std::vector<Eigen::Vector3d> imu_gravity =
      kitti::ImuGravityInCameras(sequence, FLAGS_imu_noise_deg, FLAGS_seed);
  const std::vector<Eigen::Vector3d> exact_gravity =
      kitti::ImuGravityInCameras(sequence, 0.0, FLAGS_seed);
  kitti::SiftOptions sift_options;
  sift_options.max_features = FLAGS_sift_max_features;
  sift_options.contrast_threshold = FLAGS_sift_contrast_threshold;
  kitti::MatchOptions match_options;
  match_options.ratio = FLAGS_ratio;
  match_options.mutual = FLAGS_mutual;
  match_options.window_x_px = FLAGS_window_x_px;
  match_options.window_y_px = FLAGS_window_y_px;
  // Parallelism is ours (one frame or triplet per thread); OpenCV's own threads would
  // oversubscribe.
  cv::setNumThreads(1);

  // 1. Features of every frame into the cache, in parallel.
  const auto features_start = std::chrono::steady_clock::now();
  const kitti::TripletSource cache_filler(sequence, imu_gravity, cache_dir, sift_options,
                                          match_options);
  std::vector<double> detect_ms(sequence.num_frames(), -1.0);
  std::atomic<bool> failed{false};
  std::string first_error;
  std::mutex error_mutex;
  auto fail = [&](const std::string& message) {
    const std::lock_guard<std::mutex> lock(error_mutex);
    if (!failed.exchange(true)) first_error = message;
  };
  {
    Progress progress("features (frames)", sequence.num_frames());
    ParallelFor(sequence.num_frames(), FLAGS_threads, [&](int i) {
      if (failed) return;
      const auto start = std::chrono::steady_clock::now();
      bool detected = false;
      std::string message;
      if (!cache_filler.CacheFrame(sequence.first_frame + i, &detected, &message)) fail(message);
      if (detected) detect_ms[i] = 1e3 * SecondsSince(start);
      progress.Step();
    });
  }
  RequireFlag(!failed, first_error);
  const double features_wall_s = SecondsSince(features_start);

  // 2. Triplets: chunks of consecutive triplets per thread (each chunk loads a frame and matches a
  //    pair once), every method on each triplet.
  const auto triplets_start = std::chrono::steady_clock::now();
  const int num_triplets = sequence.num_frames() - 2;
  const int chunk = std::max(4, num_triplets / (4 * FLAGS_threads));
  const int num_chunks = (num_triplets + chunk - 1) / chunk;
  std::vector<std::vector<kitti::PoseRecord>> records_of_triplet(num_triplets);
  std::vector<kitti::TripletData> frame_stats(num_triplets);
  {
    Progress progress("triplets", num_triplets);
    ParallelFor(num_chunks, FLAGS_threads, [&](int c) {
      kitti::TripletSource source(sequence, imu_gravity, cache_dir, sift_options, match_options);
      for (int t = c * chunk; t < std::min(num_triplets, (c + 1) * chunk) && !failed; ++t) {
        const int frame = sequence.first_frame + t;
        kitti::TripletData triplet;
        std::string message;
        if (!source.Get(frame, &triplet, &message)) {
          fail(message);
          return;
        }
        const trigrav::ThreeViewPose ground_truth = sequence.GroundTruthTriplet(frame);
        for (const kitti::Method& method : methods) {
          for (const kitti::MethodPose& pose :
               method.run(triplet.observations, FLAGS_seed + frame)) {
            records_of_triplet[t].push_back(kitti::EvaluatePose(
                frame, method.name, pose, static_cast<int>(triplet.tracks.size()), ground_truth,
                exact_gravity[t + 1], exact_gravity[t + 2]));
          }
        }
        triplet.observations = {};
        frame_stats[t] = std::move(triplet);
        progress.Step();
      }
    });
  }
  RequireFlag(!failed, first_error);
  const double triplets_wall_s = SecondsSince(triplets_start);

  std::vector<kitti::PoseRecord> records;
  for (auto& triplet_records : records_of_triplet) {
    for (auto& record : triplet_records) records.push_back(std::move(record));
  }
  const std::vector<kitti::MethodSummary> summaries = kitti::Summarize(sequence, records);

  // 3. Output.
  const fs::path out(FLAGS_output_dir);
  RequireFlag(kitti::WritePoseRecordsCsv((out / "poses.csv").string(), records),
              "cannot write " + (out / "poses.csv").string());
  RequireFlag(kitti::WriteSummaryCsv((out / "summary.csv").string(), summaries),
              "cannot write " + (out / "summary.csv").string());
  RequireFlag(kitti::WriteTrajectoriesCsv((out / "trajectories.csv").string(), sequence, summaries),
              "cannot write " + (out / "trajectories.csv").string());
  {
    // Per frame f: SIFT time if detected in this run (empty if from the cache); tracks and
    // loading / matching time of the triplet (f, f+1, f+2) (empty for the last two frames).
    std::ofstream frames(out / "frames.csv");
    frames << "frame,sift_ms,triplet_tracks,triplet_features_ms,triplet_matching_ms\n";
    for (int i = 0; i < sequence.num_frames(); ++i) {
      frames << sequence.first_frame + i << ",";
      if (detect_ms[i] >= 0.0) frames << detect_ms[i];
      if (i < num_triplets) {
        const kitti::TripletData& s = frame_stats[i];
        frames << "," << s.tracks.size() << "," << 1e3 * s.features_s << "," << 1e3 * s.matching_s
               << "\n";
      } else {
        frames << ",,,\n";
      }
    }
    RequireFlag(static_cast<bool>(frames), "cannot write " + (out / "frames.csv").string());
  }

  std::vector<double> tracks, matching_ms, detected_ms;
  for (const kitti::TripletData& s : frame_stats) {
    tracks.push_back(static_cast<double>(s.tracks.size()));
    matching_ms.push_back(1e3 * s.matching_s);
  }
  for (const double ms : detect_ms) {
    if (ms >= 0.0) detected_ms.push_back(ms);
  }
  std::printf(
      "KITTI %s frames %d-%d (%d triplets), threshold %.2f px, IMU noise %.3f deg, gravity "
      "sigma %.3f deg\n",
      sequence.sequence.c_str(), sequence.first_frame, sequence.last_frame, num_triplets,
      FLAGS_threshold_px, FLAGS_imu_noise_deg, settings.bundle_adjustment.gravity_sigma_deg);
  std::printf("tracks per triplet: median %.0f, min %.0f\n", trigrav::Median(tracks),
              *std::min_element(tracks.begin(), tracks.end()));
  std::printf(
      "errors: median over triplets of views 2 and 3 pooled (deg); ATE: RMSE (m) of the chained "
      "trajectory after rigid alignment\n");
  kitti::PrintSummaryTable(summaries, std::cout);
  std::printf(
      "time: features %.1f s wall (%zu frames detected, median %.0f ms per frame on one thread; "
      "%d from the cache), triplets %.1f s wall (matching median %.1f ms per triplet), %d "
      "threads\n",
      features_wall_s, detected_ms.size(), detected_ms.empty() ? 0.0 : trigrav::Median(detected_ms),
      sequence.num_frames() - static_cast<int>(detected_ms.size()), triplets_wall_s,
      trigrav::Median(matching_ms), FLAGS_threads);
  return 0;
}
