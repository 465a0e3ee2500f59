// Where gravity pays in an N-view bundle adjustment, measured both ways (issue 34, item 4): the
// same start refined by RefineWithGravity (trigrav/ba/nview_bundle_adjustment.h) without gravity
// and with it, on
//  - long synthetic driving sequences (tests/scenes/nview_scene.h, fixed intrinsics) at IMU noise
//    levels from 0.05 to 1 deg, started from a drifted odometry-like reconstruction;
//  - weak geometry: short tracks and few points, and a short baseline (low parallax);
//  - optionally COLMAP models of KITTI sequences (--kitti_models; gravity_pays_kitti.py runs COLMAP
//    and then this program), with exact and noisy gravity made from the ground truth.
// Variants per scenario (one RefineWithGravity call each, from the same start):
//   start        the start itself (synthetic: the drifted reconstruction; KITTI: COLMAP alone)
//   vision-only  gravity prior with sigma 10 deg, no verdict: the images alone decide every
//                relative rotation; the priors only hold the tilt's gauge (the verdict's own
//                images-dominated solve, NViewBundleAdjustmentOptions::kVerdictGravitySigmaDeg)
//   prior        gravity prior with the IMU's true sigma (0.01 deg for exact gravity), no verdict
//   default      the library's defaults: yaw-only requested, the gravity verdict decides the model
//                and estimates the sigma (check_gravity, gravity_sigma_from_data)
//   yaw-only     yaw-only forced, no verdict
// Columns (ba README: examples/experiments/README.md, "Where gravity pays"):
//   tilt     RMS over images of the angle between the model's vertical seen from camera k,
//            R_k g, and the truth's (g: the normalised sum of R_k^T times each image's measured
//            unit gravity, the world vertical the model's own poses and its IMU give); no
//            alignment needed
//   vdrift   largest |height error| along the trajectory (m), heights measured along each one's
//            vertical from the first image, the model's scaled by its Sim(3) alignment to the
//            truth (Umeyama on the camera centres, no gravity used)
//   ATE      RMSE of the camera centres after that Sim(3) alignment (m)
//   RPE rot  median angle of the error of the relative rotation of consecutive images (deg)
//   RPE yaw  median angle of its twist about the true vertical (deg): its yaw part, the part
//            exact gravity cannot fix (on KITTI the "exact" gravity is the ground truth's tilt)
//   RPE dir  median angle between the estimated and true directions of the step from image k to
//            k+1, in camera k's frame (deg)
//
//   gravity_pays                                   # the README's synthetic rows
//   gravity_pays_kitti.py ... -- <flags>           # with the KITTI rows (README's command)
//   gravity_pays --quick                           # smoke test (ctest gravity_pays_quick)

#include <gflags/gflags.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/require_flag.h"
#include "common/tool_flags.h"
#include "nview_scene.h"
#include "trigrav/ba/nview_bundle_adjustment.h"

#ifdef TRIGRAV_GRAVITY_PAYS_WITH_COLMAP
#include "trigrav/colmap/model_io.h"
#include "trigrav/colmap/nview_conversion.h"
#endif

DEFINE_int32(frames, 1000, "Images of the long synthetic trajectory.");
DEFINE_int32(points_per_image,
             40,
             "New points per image of the long trajectory (each seen by 2..max_track_length "
             "consecutive images while in view).");
DEFINE_int32(max_track_length, 8, "Longest track of the long trajectory.");
DEFINE_string(imu_noise_deg,
              "0.05,0.1,0.2,0.5,1",
              "IMU pitch and roll sigmas (deg) of the long trajectory, comma-separated.");
DEFINE_double(noise_px, 1.0, "Pixel noise sigma.");
DEFINE_double(drift_rotation_deg,
              0.02,
              "Start: odometry drift, sigma per axis of the rotation error added to each step "
              "(deg, a random walk).");
DEFINE_double(drift_translation,
              0.01,
              "Start: odometry drift, sigma per axis of the translation error of each step, as a "
              "fraction of the step's length.");
DEFINE_bool(weak, true, "Also the weak-geometry scenarios (short tracks; short baseline).");
DEFINE_int32(weak_frames, 500, "Images of each weak-geometry scenario.");
DEFINE_double(weak_imu_noise_deg, 0.1, "IMU sigma (deg) of the weak-geometry scenarios.");
DEFINE_string(kitti_path, "", "KITTI odometry folder (poses/<seq>.txt), for --kitti_models.");
DEFINE_string(kitti_models,
              "",
              "COLMAP models of KITTI sequences, comma-separated <seq>=<model folder> (images "
              "named by frame number, e.g. 000012.png); needs --kitti_path.");
DEFINE_string(kitti_imu_noise_deg, "0,0.1", "IMU sigmas (deg) of the KITTI rows; 0 = exact.");
DEFINE_double(kitti_gravity_pitch_deg,
              0.0,
              "Turn every KITTI image's gravity about its camera's x axis (pitch) by this angle "
              "(deg) before the noise: a camera-to-IMU misalignment added or removed.");
DEFINE_double(kitti_gravity_roll_deg,
              0.0,
              "The same about the camera's z axis (roll), after the pitch.");
DEFINE_int32(threads, 2, "Ceres threads per solve.");
DEFINE_uint64(seed, 1, "Seed of the scenes, the drift and the KITTI gravity noise.");
DEFINE_string(csv, "", "Write the table as CSV here.");
DEFINE_string(profile_csv,
              "",
              "Write per-image height and tilt errors here (scenario, variant, image, distance, "
              "height error, tilt error) for plot_gravity_pays.py.");
DEFINE_bool(quick, false, "Smoke test: 60 frames, noise 0.1 deg, 60-frame weak scenarios.");

namespace {

using trigrav::CameraPose;
using trigrav::NViewBundleAdjustmentOptions;
using trigrav::NViewBundleAdjustmentSummary;
using trigrav::NViewReconstruction;
using RotationModel = trigrav::BundleAdjustmentOptions::RotationModel;

constexpr double kDegToRad = M_PI / 180.0;
constexpr double kRadToDeg = 180.0 / M_PI;
// The prior's sigma for exact gravity (a sigma of 0 is not a prior): it all but fixes the tilt.
constexpr double kExactGravitySigmaDeg = 0.01;

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<double> ParseList(const std::string& text, const char* flag) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    char* end = nullptr;
    const double value = std::strtod(item.c_str(), &end);
    trigrav::examples::RequireFlag(
        !item.empty() && *end == '\0' && std::isfinite(value) && value >= 0.0,
        std::string("--") + flag + " must list numbers >= 0");
    values.push_back(value);
  }
  return values;
}

double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return kRadToDeg * std::atan2(a.cross(b).norm(), a.dot(b));
}

double RotationAngleDeg(const Eigen::Matrix3d& r) {
  return kRadToDeg * Eigen::AngleAxisd(r).angle();
}

// The angle (deg) of the twist of rotation r about the unit axis v (swing-twist decomposition):
// the yaw part of an error rotation when v is the vertical.
double TwistAngleDeg(const Eigen::Matrix3d& r, const Eigen::Vector3d& v) {
  const Eigen::Quaterniond q(r);
  return kRadToDeg * 2.0 * std::atan2(std::abs(q.vec().dot(v)), std::abs(q.w()));
}

double Median(std::vector<double> values) {
  if (values.empty()) return std::nan("");
  const std::size_t n = values.size();
  std::sort(values.begin(), values.end());
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// The world vertical a model and its IMU give: the normalised sum of R_k^T g_k / |g_k|.
Eigen::Vector3d ModelVertical(const std::vector<CameraPose>& poses,
                              const std::vector<Eigen::Vector3d>& gravity_in_cam) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < poses.size(); ++k) {
    sum += poses[k].R.transpose() * gravity_in_cam[k].normalized();
  }
  return sum.normalized();
}

// A trajectory to evaluate: poses (cam_from_world) and each image's gravity (the measured one for
// a model, the exact one for the truth); distance along the true trajectory per image.
struct Trajectory {
  std::vector<CameraPose> poses;
  std::vector<Eigen::Vector3d> gravity_in_cam;
};

struct Errors {
  double tilt_deg = 0.0;
  double vertical_drift_m = 0.0;
  double ate_m = 0.0;
  double rpe_rotation_deg = 0.0;
  double rpe_yaw_deg = 0.0;
  double rpe_direction_deg = 0.0;
  std::vector<double> height_error_m;  // per image
  std::vector<double> tilt_error_deg;  // per image
};

Errors Evaluate(const Trajectory& truth, const Trajectory& model) {
  const int n = static_cast<int>(truth.poses.size());
  Errors errors;
  const Eigen::Vector3d g_true = ModelVertical(truth.poses, truth.gravity_in_cam);
  const Eigen::Vector3d g_model = ModelVertical(model.poses, model.gravity_in_cam);
  double sum_tilt = 0.0;
  for (int k = 0; k < n; ++k) {
    const double tilt = AngleDeg(model.poses[k].R * g_model, truth.poses[k].R * g_true);
    errors.tilt_error_deg.push_back(tilt);
    sum_tilt += tilt * tilt;
  }
  errors.tilt_deg = std::sqrt(sum_tilt / n);

  // Sim(3) of the centres (Umeyama), model -> truth.
  std::vector<Eigen::Vector3d> c_model(n), c_true(n);
  Eigen::Vector3d mean_model = Eigen::Vector3d::Zero(), mean_true = Eigen::Vector3d::Zero();
  for (int k = 0; k < n; ++k) {
    c_model[k] = model.poses[k].Center();
    c_true[k] = truth.poses[k].Center();
    mean_model += c_model[k] / n;
    mean_true += c_true[k] / n;
  }
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  double variance_model = 0.0;
  for (int k = 0; k < n; ++k) {
    covariance += (c_true[k] - mean_true) * (c_model[k] - mean_model).transpose() / n;
    variance_model += (c_model[k] - mean_model).squaredNorm() / n;
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(covariance,
                                              Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Vector3d sign(1.0, 1.0, 1.0);
  if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0) sign.z() = -1.0;
  const Eigen::Matrix3d rotation = svd.matrixU() * sign.asDiagonal() * svd.matrixV().transpose();
  const double scale = svd.singularValues().dot(sign) / variance_model;
  double sum_ate = 0.0, max_height = 0.0;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d aligned = scale * rotation * (c_model[k] - mean_model) + mean_true;
    sum_ate += (aligned - c_true[k]).squaredNorm();
    const double height_model = scale * g_model.dot(c_model[k] - c_model[0]);
    const double height_true = g_true.dot(c_true[k] - c_true[0]);
    errors.height_error_m.push_back(height_model - height_true);
    max_height = std::max(max_height, std::abs(height_model - height_true));
  }
  errors.ate_m = std::sqrt(sum_ate / n);
  errors.vertical_drift_m = max_height;

  std::vector<double> rpe_rotation, rpe_yaw, rpe_direction;
  for (int k = 0; k + 1 < n; ++k) {
    const Eigen::Matrix3d rel_model = model.poses[k + 1].R * model.poses[k].R.transpose();
    const Eigen::Matrix3d rel_true = truth.poses[k + 1].R * truth.poses[k].R.transpose();
    rpe_rotation.push_back(RotationAngleDeg(rel_model.transpose() * rel_true));
    rpe_yaw.push_back(TwistAngleDeg(rel_model.transpose() * rel_true, truth.poses[k].R * g_true));
    const Eigen::Vector3d step_model = model.poses[k].R * (c_model[k + 1] - c_model[k]);
    const Eigen::Vector3d step_true = truth.poses[k].R * (c_true[k + 1] - c_true[k]);
    rpe_direction.push_back(AngleDeg(step_model, step_true));
  }
  errors.rpe_rotation_deg = Median(rpe_rotation);
  errors.rpe_yaw_deg = Median(rpe_yaw);
  errors.rpe_direction_deg = Median(rpe_direction);
  return errors;
}

std::vector<CameraPose> Poses(const NViewReconstruction& r) {
  std::vector<CameraPose> poses;
  for (const auto& image : r.images) poses.push_back(image.cam_from_world);
  return poses;
}

std::vector<Eigen::Vector3d> Gravity(const NViewReconstruction& r) {
  std::vector<Eigen::Vector3d> gravity;
  for (const auto& image : r.images) gravity.push_back(image.gravity_in_cam);
  return gravity;
}

// An odometry-like start: image 0 at the truth, each step k-1 -> k the true relative pose with its
// rotation turned by N(0, drift_rotation_deg^2) per axis and its translation moved by
// N(0, (drift_translation |step|)^2) per axis, chained (a random walk in rotation and position,
// as visual odometry drifts); each point carried by the drifted pose of its first image and moved
// by N(0, (1 % of its distance)^2) per axis.
NViewReconstruction DriftedStart(const NViewReconstruction& truth, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  auto random_vector = [&]() { return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)); };
  NViewReconstruction start = truth;
  const int n = static_cast<int>(truth.images.size());
  // world_from_cam as (R, C).
  Eigen::Matrix3d world_from_cam = truth.images[0].cam_from_world.R.transpose();
  Eigen::Vector3d center = truth.images[0].cam_from_world.Center();
  for (int k = 1; k < n; ++k) {
    const CameraPose& previous = truth.images[k - 1].cam_from_world;
    const CameraPose& current = truth.images[k].cam_from_world;
    // The step in camera k-1's frame: rotation prev_from_cur and translation.
    Eigen::Matrix3d rotation_step = previous.R * current.R.transpose();
    Eigen::Vector3d translation_step = previous.R * (current.Center() - previous.Center());
    const Eigen::Vector3d omega = FLAGS_drift_rotation_deg * kDegToRad * random_vector();
    if (omega.norm() > 0.0) {
      rotation_step = Eigen::AngleAxisd(omega.norm(), omega.normalized()) * rotation_step;
    }
    translation_step += FLAGS_drift_translation * translation_step.norm() * random_vector();
    center = center + world_from_cam * translation_step;
    world_from_cam = world_from_cam * rotation_step;
    start.images[k].cam_from_world.R = world_from_cam.transpose();
    start.images[k].cam_from_world.t = -world_from_cam.transpose() * center;
  }
  std::vector<int> first_image(truth.points_in_world.size(), -1);
  for (const auto& o : truth.observations) {
    if (first_image[o.point_index] < 0 || o.image_index < first_image[o.point_index]) {
      first_image[o.point_index] = o.image_index;
    }
  }
  for (std::size_t p = 0; p < truth.points_in_world.size(); ++p) {
    const int k = std::max(first_image[p], 0);
    const Eigen::Vector3d in_cam = truth.images[k].cam_from_world.Apply(truth.points_in_world[p]);
    start.points_in_world[p] = start.images[k].cam_from_world.Inverse().Apply(in_cam) +
                               0.01 * in_cam.norm() * random_vector();
  }
  return start;
}

struct Variant {
  std::string name;
  bool refine = true;
  bool check_gravity = false;
  RotationModel model = RotationModel::kGravityPrior;
  double sigma_deg = 0.0;  // < 0: the IMU's (kExactGravitySigmaDeg for exact gravity)
};

std::vector<Variant> Variants() {
  return {{"start", false},
          {"vision-only", true, false, RotationModel::kGravityPrior,
           NViewBundleAdjustmentOptions::kVerdictGravitySigmaDeg},
          {"prior (IMU sigma)", true, false, RotationModel::kGravityPrior, -1.0},
          {"default (verdict)", true, true, RotationModel::kYawOnly, 0.1},
          {"yaw-only", true, false, RotationModel::kYawOnly, 0.1}};
}

struct Row {
  std::string scenario;
  std::string variant;
  Errors errors;
  double seconds = 0.0;
  std::string note;  // success, model solved, estimated sigma
};

std::string Format(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

// Every variant from `start`, evaluated against `truth` (the truth's exact gravity in its
// images); `imu_noise_deg` is the noise of start's gravity.
std::vector<Row> RunScenario(const std::string& scenario,
                             const Trajectory& truth,
                             const NViewReconstruction& start,
                             double imu_noise_deg) {
  std::vector<Row> rows;
  const Trajectory start_trajectory{Poses(start), Gravity(start)};
  for (const Variant& variant : Variants()) {
    Row row;
    row.scenario = scenario;
    row.variant = variant.name;
    if (!variant.refine) {
      row.errors = Evaluate(truth, start_trajectory);
      rows.push_back(row);
      continue;
    }
    NViewBundleAdjustmentOptions options;
    options.num_threads = FLAGS_threads;
    options.pixel_sigma_px = FLAGS_noise_px;
    options.check_gravity = variant.check_gravity;
    options.rotation_model = variant.model;
    options.gravity_sigma_deg = variant.sigma_deg >= 0.0 ? variant.sigma_deg
                                : imu_noise_deg > 0.0    ? imu_noise_deg
                                                         : kExactGravitySigmaDeg;
    NViewReconstruction refined;
    const auto begin = std::chrono::steady_clock::now();
    const NViewBundleAdjustmentSummary summary = trigrav::RefineWithGravity(
        start, trigrav::NViewBundleAdjustmentConfig{}, options, &refined);
    row.seconds = Seconds(begin);
    if (!summary.success) {
      row.note = "FAILED: " + summary.message.substr(0, 80);
      row.errors = Evaluate(truth, start_trajectory);  // the input is returned
    } else {
      row.errors = Evaluate(truth, {Poses(refined), Gravity(refined)});
      row.note = summary.rotation_model == RotationModel::kYawOnly
                     ? "yaw-only"
                     : "prior " + Format("%.3g", summary.gravity_sigma_deg) + " deg";
      if (variant.check_gravity) {
        int dropped = 0;
        for (const char used : summary.gravity_used) dropped += used ? 0 : 1;
        row.note += ", est. " + Format("%.3g", summary.estimated_gravity_sigma_deg) + " deg";
        if (dropped > 0) row.note += ", " + std::to_string(dropped) + " without gravity";
      }
      row.note += ", " + std::to_string(summary.Iterations()) + " it";
    }
    std::fprintf(stderr, "  %-34s %-18s %7.1f s  %s\n", scenario.c_str(), variant.name.c_str(),
                 row.seconds, row.note.c_str());
    rows.push_back(row);
  }
  return rows;
}

std::vector<Row> SyntheticScenario(const std::string& name,
                                   trigrav::testing_utils::NViewSceneOptions scene_options,
                                   double imu_noise_deg) {
  using trigrav::testing_utils::MakeNViewScene;
  scene_options.pixel_noise_px = FLAGS_noise_px;
  scene_options.gravity_noise_deg = 0.0;
  // The same seed draws the same scene; only the gravity noise's scale differs.
  const NViewReconstruction exact = MakeNViewScene(scene_options, FLAGS_seed).truth;
  scene_options.gravity_noise_deg = imu_noise_deg;
  const NViewReconstruction noisy = MakeNViewScene(scene_options, FLAGS_seed).truth;
  const NViewReconstruction start = DriftedStart(noisy, FLAGS_seed + 1000);
  std::fprintf(stderr, "%s: %zu images, %zu points, %zu observations\n", name.c_str(),
               exact.images.size(), exact.points_in_world.size(), exact.observations.size());
  return RunScenario(name, {Poses(exact), Gravity(exact)}, start, imu_noise_deg);
}

#ifdef TRIGRAV_GRAVITY_PAYS_WITH_COLMAP
// KITTI's cam_from_world of every frame (poses/<seq>.txt holds world_from_cam, 3 x 4 row-major).
std::vector<CameraPose> ReadKittiPoses(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw std::runtime_error("cannot read " + path);
  std::vector<CameraPose> poses;
  std::string line;
  while (std::getline(file, line)) {
    std::stringstream stream(line);
    double v[12];
    int count = 0;
    while (count < 12 && stream >> v[count]) ++count;
    if (count == 0) continue;
    if (count != 12) throw std::runtime_error(path + ": a line without 12 numbers");
    Eigen::Matrix3d r;
    r << v[0], v[1], v[2], v[4], v[5], v[6], v[8], v[9], v[10];
    const Eigen::Vector3d c(v[3], v[7], v[11]);
    CameraPose pose;
    pose.R = r.transpose();
    pose.t = -pose.R * c;
    poses.push_back(pose);
  }
  return poses;
}

int FrameOfName(const std::string& name) {
  const std::size_t slash = name.find_last_of('/');
  const std::string base = slash == std::string::npos ? name : name.substr(slash + 1);
  std::size_t digits = 0;
  while (digits < base.size() && std::isdigit(static_cast<unsigned char>(base[digits]))) ++digits;
  if (digits == 0) throw std::runtime_error("image name without a frame number: " + name);
  return std::stoi(base.substr(0, digits));
}

// How a gravity disagrees with a model's poses: with the world's vertical that fits them best
// (ModelVertical), per image the rotation vector r_k (camera frame) taking R_k g_w to g_k.
// Returns "RMS |r_k|, the mean r_k (camera x, y, z) and the lag-1 autocorrelation of r_k - mean
// along the images": a constant camera-to-IMU misalignment shows as a mean, smooth errors as an
// autocorrelation near 1, independent noise as neither.
std::string GravityAgainstPoses(const std::vector<CameraPose>& cam_from_world,
                                const std::vector<Eigen::Vector3d>& gravity_in_cam) {
  const std::size_t n = cam_from_world.size();
  const Eigen::Vector3d gravity_in_world = ModelVertical(cam_from_world, gravity_in_cam);
  std::vector<Eigen::Vector3d> r(n);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  double squares = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d implied = cam_from_world[k].R * gravity_in_world;
    const Eigen::Vector3d measured = gravity_in_cam[k].normalized();
    const Eigen::Vector3d axis = implied.cross(measured);
    const double angle = std::atan2(axis.norm(), implied.dot(measured));
    r[k] = axis.norm() > 0.0 ? Eigen::Vector3d(kRadToDeg * angle * axis.normalized())
                             : Eigen::Vector3d::Zero();
    mean += r[k] / static_cast<double>(n);
    squares += r[k].squaredNorm();
  }
  double lagged = 0.0, centred = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    centred += (r[k] - mean).squaredNorm();
    if (k + 1 < n) lagged += (r[k] - mean).dot(r[k + 1] - mean);
  }
  char text[160];
  std::snprintf(text, sizeof(text),
                "gravity vs poses: RMS %.3f deg, camera-frame mean (%.3f, %.3f, %.3f) deg, lag-1 "
                "autocorrelation %.2f",
                std::sqrt(squares / static_cast<double>(n)), mean.x(), mean.y(), mean.z(),
                centred > 0.0 ? lagged / centred : 0.0);
  return text;
}

// The gravity of each image as make_gravity_csv emulates an IMU on KITTI: the ground truth
// world's +y seen from the camera, turned by --kitti_gravity_pitch_deg / _roll_deg, tilted by
// Exp(a e1 + b e2), a, b ~ N(0, sigma^2).
std::vector<Row> KittiScenario(const std::string& sequence,
                               const std::string& model_path,
                               double imu_noise_deg) {
  namespace colmap = trigrav::colmap;
  const colmap::Reconstruction model = colmap::ReadModel(model_path);
  const std::vector<CameraPose> ground_truth =
      ReadKittiPoses(FLAGS_kitti_path + "/poses/" + sequence + ".txt");
  std::mt19937_64 rng(FLAGS_seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  colmap::GravityByImageName measured, exact;
  Trajectory truth;
  for (const auto& [id, image] : model.images) {  // increasing id, as ToNView orders them
    const int frame = FrameOfName(image.name);
    if (frame >= static_cast<int>(ground_truth.size())) {
      throw std::runtime_error(image.name + ": no ground-truth pose");
    }
    const Eigen::Vector3d g =
        Eigen::AngleAxisd(FLAGS_kitti_gravity_roll_deg * kDegToRad, Eigen::Vector3d::UnitZ()) *
        Eigen::AngleAxisd(FLAGS_kitti_gravity_pitch_deg * kDegToRad, Eigen::Vector3d::UnitX()) *
        ground_truth[frame].R * Eigen::Vector3d::UnitY();
    const Eigen::Vector3d e1 = g.unitOrthogonal(), e2 = g.cross(e1);
    const Eigen::Vector3d w = imu_noise_deg * kDegToRad * (normal(rng) * e1 + normal(rng) * e2);
    exact[image.name] = g;
    measured[image.name] =
        w.norm() > 0.0 ? Eigen::Vector3d(Eigen::AngleAxisd(w.norm(), w.normalized()) * g) : g;
    truth.poses.push_back(ground_truth[frame]);
    truth.gravity_in_cam.push_back(g);
  }
  const colmap::NViewInput input = colmap::ToNView(model, measured);
  const std::string name = "KITTI " + sequence + " (" + std::to_string(model.images.size()) +
                           " img), " +
                           (imu_noise_deg > 0.0 ? Format("%g", imu_noise_deg) + " deg" : "exact");
  std::fprintf(stderr, "%s: %zu images, %zu points, %zu observations\n", name.c_str(),
               input.reconstruction.images.size(), input.reconstruction.points_in_world.size(),
               input.reconstruction.observations.size());
  std::vector<Row> rows = RunScenario(name, truth, input.reconstruction, imu_noise_deg);
  rows.front().variant = "COLMAP alone";
  rows.front().note =
      GravityAgainstPoses(Poses(input.reconstruction), Gravity(input.reconstruction));
  return rows;
}
#endif

void PrintTable(const std::vector<Row>& rows) {
  std::printf("%-34s %-18s %9s %10s %9s %9s %9s %9s %8s  %s\n", "scenario", "variant", "tilt(deg)",
              "vdrift(m)", "ATE(m)", "RPErot", "RPEyaw", "RPEdir", "time(s)", "solved as");
  std::string last;
  for (const Row& row : rows) {
    if (row.scenario != last && !last.empty()) std::printf("\n");
    last = row.scenario;
    std::printf("%-34s %-18s %9.4f %10.3f %9.3f %9.4f %9.4f %9.3f %8.1f  %s\n",
                row.scenario.c_str(), row.variant.c_str(), row.errors.tilt_deg,
                row.errors.vertical_drift_m, row.errors.ate_m, row.errors.rpe_rotation_deg,
                row.errors.rpe_yaw_deg, row.errors.rpe_direction_deg, row.seconds,
                row.note.c_str());
  }
}

void WriteCsv(const std::vector<Row>& rows, const std::string& path) {
  std::ofstream file(path);
  trigrav::examples::RequireFlag(static_cast<bool>(file), "cannot write --csv " + path);
  file << "scenario,variant,tilt_deg,vertical_drift_m,ate_m,rpe_rotation_deg,rpe_yaw_deg,"
          "rpe_direction_deg,seconds,solved_as\n";
  for (const Row& row : rows) {
    file << '"' << row.scenario << "\"," << row.variant << ',' << row.errors.tilt_deg << ','
         << row.errors.vertical_drift_m << ',' << row.errors.ate_m << ','
         << row.errors.rpe_rotation_deg << ',' << row.errors.rpe_yaw_deg << ','
         << row.errors.rpe_direction_deg << ',' << row.seconds << ",\"" << row.note << "\"\n";
  }
}

void WriteProfileCsv(const std::vector<Row>& rows, const std::string& path) {
  std::ofstream file(path);
  trigrav::examples::RequireFlag(static_cast<bool>(file), "cannot write --profile_csv " + path);
  file << "scenario,variant,image,height_error_m,tilt_error_deg\n";
  for (const Row& row : rows) {
    for (std::size_t k = 0; k < row.errors.height_error_m.size(); ++k) {
      file << '"' << row.scenario << "\"," << row.variant << ',' << k << ','
           << row.errors.height_error_m[k] << ',' << row.errors.tilt_error_deg[k] << '\n';
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  trigrav::examples::ParseToolFlags(
      "Gravity in the N-view bundle adjustment, with and without: long drives, weak geometry, "
      "KITTI models.",
      __FILE__, &argc, &argv);
  using trigrav::examples::RequireFlag;
  if (FLAGS_quick) {
    FLAGS_frames = 60;
    FLAGS_imu_noise_deg = "0.1";
    FLAGS_weak_frames = 60;
  }
  RequireFlag(FLAGS_frames >= 10, "--frames must be >= 10");
  RequireFlag(FLAGS_weak_frames >= 10, "--weak_frames must be >= 10");
  RequireFlag(FLAGS_points_per_image > 0, "--points_per_image must be positive");
  RequireFlag(FLAGS_max_track_length >= 2, "--max_track_length must be >= 2");
  RequireFlag(FLAGS_noise_px > 0.0 && std::isfinite(FLAGS_noise_px),
              "--noise_px must be positive and finite");
  RequireFlag(FLAGS_drift_rotation_deg >= 0.0 && std::isfinite(FLAGS_drift_rotation_deg),
              "--drift_rotation_deg must be finite and >= 0");
  RequireFlag(FLAGS_drift_translation >= 0.0 && std::isfinite(FLAGS_drift_translation),
              "--drift_translation must be finite and >= 0");
  RequireFlag(FLAGS_weak_imu_noise_deg >= 0.0 && std::isfinite(FLAGS_weak_imu_noise_deg),
              "--weak_imu_noise_deg must be finite and >= 0");
  RequireFlag(FLAGS_threads >= 1 && FLAGS_threads <= 256, "--threads must be in [1, 256]");
  const std::vector<double> noise_levels = ParseList(FLAGS_imu_noise_deg, "imu_noise_deg");
  const std::vector<double> kitti_noise_levels =
      ParseList(FLAGS_kitti_imu_noise_deg, "kitti_imu_noise_deg");
  std::vector<std::pair<std::string, std::string>> kitti_models;
  {
    std::stringstream stream(FLAGS_kitti_models);
    std::string item;
    while (std::getline(stream, item, ',')) {
      const std::size_t equals = item.find('=');
      RequireFlag(equals != std::string::npos && equals > 0 && equals + 1 < item.size(),
                  "--kitti_models must list <seq>=<model folder>");
      kitti_models.emplace_back(item.substr(0, equals), item.substr(equals + 1));
    }
  }
  RequireFlag(kitti_models.empty() || !FLAGS_kitti_path.empty(),
              "--kitti_models needs --kitti_path");
  RequireFlag(
      std::isfinite(FLAGS_kitti_gravity_pitch_deg) && std::isfinite(FLAGS_kitti_gravity_roll_deg),
      "--kitti_gravity_pitch_deg and --kitti_gravity_roll_deg must be finite");
#ifndef TRIGRAV_GRAVITY_PAYS_WITH_COLMAP
  RequireFlag(kitti_models.empty(), "--kitti_models: built without trigrav::colmap");
#endif

  const auto begin = std::chrono::steady_clock::now();
  std::vector<Row> rows;
  auto add = [&rows](const std::vector<Row>& more) {
    rows.insert(rows.end(), more.begin(), more.end());
  };
  trigrav::testing_utils::NViewSceneOptions long_drive;
  long_drive.num_images = FLAGS_frames;
  long_drive.num_points = FLAGS_points_per_image * FLAGS_frames;
  long_drive.max_track_length = FLAGS_max_track_length;
  for (const double noise : noise_levels) {
    add(SyntheticScenario(
        std::to_string(FLAGS_frames) + " img, IMU " + Format("%g", noise) + " deg", long_drive,
        noise));
  }
  if (FLAGS_weak) {
    trigrav::testing_utils::NViewSceneOptions short_tracks;
    short_tracks.num_images = FLAGS_weak_frames;
    short_tracks.num_points = 15 * FLAGS_weak_frames;
    short_tracks.max_track_length = 3;
    add(SyntheticScenario(std::to_string(FLAGS_weak_frames) + " img, tracks <= 3, IMU " +
                              Format("%g", FLAGS_weak_imu_noise_deg) + " deg",
                          short_tracks, FLAGS_weak_imu_noise_deg));
    trigrav::testing_utils::NViewSceneOptions short_baseline;
    short_baseline.num_images = FLAGS_weak_frames;
    short_baseline.num_points = FLAGS_points_per_image * FLAGS_weak_frames;
    short_baseline.max_track_length = FLAGS_max_track_length;
    short_baseline.step_m = 0.1;
    add(SyntheticScenario(std::to_string(FLAGS_weak_frames) + " img, 0.1 m steps, IMU " +
                              Format("%g", FLAGS_weak_imu_noise_deg) + " deg",
                          short_baseline, FLAGS_weak_imu_noise_deg));
  }
#ifdef TRIGRAV_GRAVITY_PAYS_WITH_COLMAP
  for (const auto& [sequence, path] : kitti_models) {
    for (const double noise : kitti_noise_levels) add(KittiScenario(sequence, path, noise));
  }
#endif

  std::printf(
      "Gravity in the N-view BA (seed %llu): %.2f px noise; synthetic start drifted by %g deg "
      "and %g of each step per axis (random walk)\n\n",
      static_cast<unsigned long long>(FLAGS_seed), FLAGS_noise_px, FLAGS_drift_rotation_deg,
      FLAGS_drift_translation);
  PrintTable(rows);
  std::printf("\ntotal %.1f s\n", Seconds(begin));
  if (!FLAGS_csv.empty()) WriteCsv(rows, FLAGS_csv);
  if (!FLAGS_profile_csv.empty()) WriteProfileCsv(rows, FLAGS_profile_csv);
  return 0;
}
