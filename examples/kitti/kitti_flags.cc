#include "kitti_flags.h"

#include <gflags/gflags.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <sstream>

#include "../require_flag.h"

DEFINE_string(kitti_dir,
              "",
              "KITTI odometry folder with sequences/XX/image_0, sequences/XX/calib.txt and "
              "poses/XX.txt.");
DEFINE_string(sequence, "00", "Sequence: two digits, e.g. 00.");
DEFINE_int32(first_frame, 0, "First frame of the range.");
DEFINE_int32(last_frame, 299, "Last frame of the range (included).");
DEFINE_string(cache_dir,
              "",
              "Feature cache folder (created; must not be inside --kitti_dir). Default: "
              "kitti_triplets <output_dir>/feature_cache; peer_comparison no cache.");
DEFINE_string(methods,
              "8pt,5pt,7pt-linear,3pt,3pt-sextic,4pt",
              "Comma-separated trigrav methods: 8pt, 5pt, 7pt-linear, 3pt, 3pt-sextic, 4pt.");
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

namespace trigrav::kitti {
namespace {

namespace fs = std::filesystem;
using examples::RequireFlag;

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

// The gravity-prior refinement's sigma (deg): --gravity_sigma_deg, else the IMU noise, else the
// exact-gravity default.
double GravitySigmaDegFromFlags() {
  if (FLAGS_gravity_sigma_deg > 0.0) return FLAGS_gravity_sigma_deg;
  return FLAGS_imu_noise_deg > 0.0 ? FLAGS_imu_noise_deg : kExactGravitySigmaDeg;
}

}  // namespace

const std::string& KittiDirFlag() { return FLAGS_kitti_dir; }

double ThresholdPxFlag() { return FLAGS_threshold_px; }

void PrintEvaluationHeader(const KittiSequence& sequence) {
  std::printf(
      "KITTI %s frames %d-%d (%d triplets), threshold %.2f px, IMU noise %.3f deg, gravity "
      "sigma %.3f deg\n",
      sequence.sequence.c_str(), sequence.first_frame, sequence.last_frame,
      sequence.num_frames() - 2, FLAGS_threshold_px, FLAGS_imu_noise_deg,
      GravitySigmaDegFromFlags());
}

std::string CacheDirFromFlags(const std::string& default_cache_dir) {
  return FLAGS_cache_dir.empty() ? default_cache_dir : FLAGS_cache_dir;
}

void ValidateKittiFlags(const std::string& output_dir) {
  RequireFlag(!FLAGS_kitti_dir.empty(), "--kitti_dir is required (the KITTI odometry folder)");
  RequireFlag(fs::is_directory(FLAGS_kitti_dir), "--kitti_dir: no folder " + FLAGS_kitti_dir);
  RequireFlag(std::regex_match(FLAGS_sequence, std::regex("[0-9][0-9]")),
              "--sequence must be two digits (e.g. 00), not \"" + FLAGS_sequence + "\"");
  RequireFlag(FLAGS_first_frame >= 0, "--first_frame must be >= 0");
  RequireFlag(FLAGS_last_frame >= FLAGS_first_frame + 2,
              "--last_frame must be at least --first_frame + 2 (one triplet)");
  RequireFlag(FLAGS_cache_dir.empty() || !IsInside(FLAGS_cache_dir, FLAGS_kitti_dir),
              "--cache_dir (" + FLAGS_cache_dir + ") must not be inside the dataset --kitti_dir");
  RequireFlag(output_dir.empty() || !IsInside(output_dir, FLAGS_kitti_dir),
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
}

KittiSequence LoadSequenceFromFlags() {
  KittiSequence sequence;
  std::string error;
  const bool loaded = LoadKittiSequence(FLAGS_kitti_dir, FLAGS_sequence, FLAGS_first_frame,
                                        FLAGS_last_frame, &sequence, &error);
  RequireFlag(loaded, error);
  return sequence;
}

std::vector<Method> TrigravMethodsFromFlags() {
  const std::vector<std::string> method_names = SplitCommas(FLAGS_methods);
  RequireFlag(!method_names.empty(), "--methods is empty");
  TrigravMethodSettings settings;
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
  settings.bundle_adjustment.gravity_sigma_deg = GravitySigmaDegFromFlags();
  std::vector<Method> methods;
  std::string error;
  const bool methods_ok = MakeTrigravMethods(method_names, settings, &methods, &error);
  RequireFlag(methods_ok, "--methods: " + error);
  return methods;
}

SequenceEvaluationOptions EvaluationOptionsFromFlags(const std::string& cache_dir,
                                                     std::uint64_t seed,
                                                     int threads) {
  SequenceEvaluationOptions options;
  options.cache_dir = cache_dir;
  options.sift.max_features = FLAGS_sift_max_features;
  options.sift.contrast_threshold = FLAGS_sift_contrast_threshold;
  options.match.ratio = FLAGS_ratio;
  options.match.mutual = FLAGS_mutual;
  options.match.window_x_px = FLAGS_window_x_px;
  options.match.window_y_px = FLAGS_window_y_px;
  options.imu_noise_deg = FLAGS_imu_noise_deg;
  options.seed = seed;
  options.threads = threads;
  return options;
}

}  // namespace trigrav::kitti
