// Gravity-aware three-view initialisation of a COLMAP project: reads the database (cameras,
// images, keypoints, verified matches), chains three-view tracks, picks triplets, runs trigrav's
// InitializeAndRefine on each with the images' gravity, writes one CSV row per triplet and the
// COLMAP sparse model of the best trusted triplet, which `colmap mapper --input_path` continues
// from.
//
//   triplet_initializer --database_path=db.db --gravity_csv=g.csv --output_csv=triplets.csv
//       --output_model_path=seed
//
// README.md describes the flags, the CSV and the walkthrough from images to a refined model.

#include <gflags/gflags.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "../common/thread_note.h"
#include "common/output_paths.h"
#include "common/require_flag.h"
#include "common/tool_flags.h"
#include "staged_file.h"
#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/ba/three_view_bundle_adjustment.h"
#include "trigrav/colmap/database.h"
#include "trigrav/colmap/gravity_csv.h"
#include "trigrav/colmap/match_graph.h"
#include "trigrav/colmap/model_io.h"
#include "trigrav/colmap/triplet_csv.h"
#include "trigrav/colmap/triplet_model.h"
#include "trigrav/initializers/initial_solver.h"
#include "trigrav/initializers/parallel_for.h"

DEFINE_string(database_path, "", "COLMAP database (required).");
DEFINE_string(gravity_csv,
              "",
              "Gravity per image (trigrav/colmap/gravity_csv.h; make_gravity_csv); every image of "
              "a chosen triplet needs one (required).");
DEFINE_string(output_csv, "", "Per-triplet CSV to write (required).");
DEFINE_string(output_model_path,
              "",
              "Folder (created, or replaced as a whole when it holds a model only) for the binary "
              "COLMAP model of the best trusted triplet (required).");
DEFINE_string(triplets,
              "consecutive",
              "consecutive: (i, i+1, i+2) of the images sorted by name (a sequence); connected: "
              "the best-connected triplets, greedily, until every matched image is in one.");
DEFINE_int32(max_triplets, 0, "At most this many triplets (the first ones); 0 = no limit.");
DEFINE_int32(min_tracks, 20, "Triplets with fewer three-view tracks are not estimated.");
DEFINE_string(solver,
              "3pt",
              "Minimal solver of the RANSAC (InitialSolverName: 3pt, 4pt, 5pt, ...).");
DEFINE_double(threshold_px,
              2.0,
              "Inlier threshold (px): largest reprojection error over the three views "
              "(RansacOptions::max_error).");
DEFINE_string(rotation_model,
              "gravity_prior",
              "Refinement's rotation model: yaw_only (gravity exact) or gravity_prior.");
DEFINE_double(gravity_sigma_deg, 0.1, "IMU gravity sigma (deg) of the gravity-prior model.");
DEFINE_string(
    engine,
    trigrav::EngineName(trigrav::ThreeViewBundleAdjustmentOptions().engine),
    "Bundle-adjustment engine (ThreeViewBundleAdjustmentOptions::Engine, the same optimum): "
    "ceres_points_eliminated (the library's default) or ceres (a block per point).");
DEFINE_bool(check_gravity,
            true,
            "Compare with a gravity-free estimate also after a success "
            "(RobustThreeViewOptions::check_gravity_after_success, the library's default).");
DEFINE_uint64(seed, 1, "RANSAC seed (triplet i uses seed + i).");
DEFINE_int32(threads, 2, "Worker threads (one triplet each).");

namespace {

namespace fs = std::filesystem;
namespace colmap = trigrav::colmap;
namespace tools = trigrav::colmap_tools;
using trigrav::examples::RequireFlag;
using RotationModel = trigrav::ThreeViewBundleAdjustmentOptions::RotationModel;

trigrav::InitializeAndRefineOptions EstimatorOptions() {
  trigrav::InitializeAndRefineOptions options;
  RequireFlag(
      trigrav::ParseInitialSolver(FLAGS_solver, &options.robust.solver),
      "unknown --solver=" + FLAGS_solver + " (one of " + trigrav::InitialSolverNames() + ")");
  options.robust.ransac.max_error = FLAGS_threshold_px;
  options.robust.check_gravity_after_success = FLAGS_check_gravity;
  auto& ba = options.bundle_adjustment;
  ba.rotation_model =
      FLAGS_rotation_model == "yaw_only" ? RotationModel::kYawOnly : RotationModel::kGravityPrior;
  ba.gravity_sigma_deg = FLAGS_gravity_sigma_deg;
  ba.loss_scale_px = FLAGS_threshold_px;
  trigrav::ParseEngine(FLAGS_engine, &ba.engine);  // checked by CheckFlags()
  ba.compute_covariance = true;
  options.Check();
  return options;
}

void CheckFlags() {
  RequireFlag(!FLAGS_database_path.empty(), "--database_path is required");
  RequireFlag(fs::is_regular_file(FLAGS_database_path),
              "--database_path=" + FLAGS_database_path + " is not a file");
  RequireFlag(!FLAGS_gravity_csv.empty(), "--gravity_csv is required");
  RequireFlag(!FLAGS_output_csv.empty(), "--output_csv is required");
  RequireFlag(!FLAGS_output_model_path.empty(), "--output_model_path is required");
  RequireFlag(FLAGS_triplets == "consecutive" || FLAGS_triplets == "connected",
              "--triplets must be consecutive or connected");
  RequireFlag(FLAGS_max_triplets >= 0, "--max_triplets must be >= 0");
  RequireFlag(FLAGS_min_tracks >= 3, "--min_tracks must be >= 3");
  RequireFlag(FLAGS_threshold_px > 0.0 && std::isfinite(FLAGS_threshold_px),
              "--threshold_px must be positive and finite");
  RequireFlag(FLAGS_rotation_model == "yaw_only" || FLAGS_rotation_model == "gravity_prior",
              "--rotation_model must be yaw_only or gravity_prior");
  RequireFlag(FLAGS_gravity_sigma_deg > 0.0 && std::isfinite(FLAGS_gravity_sigma_deg),
              "--gravity_sigma_deg must be positive and finite");
  trigrav::ThreeViewBundleAdjustmentOptions::Engine engine;
  RequireFlag(trigrav::ParseEngine(FLAGS_engine, &engine),
              "--engine must be " + trigrav::EngineNames());
  RequireFlag(FLAGS_threads >= 1 && FLAGS_threads <= 256, "--threads must be in [1, 256]");
  using trigrav::examples::ToolPath;
  trigrav::examples::RequireOutputsApartFromInputs(
      {{"--database_path", FLAGS_database_path}, {"--gravity_csv", FLAGS_gravity_csv}},
      {{"--output_csv", FLAGS_output_csv},
       {"--output_model_path", FLAGS_output_model_path, ToolPath::kFolder}});
}

// The database's images sorted by name.
std::vector<colmap::DatabaseImage> ImagesByName(const colmap::Database& database) {
  std::vector<colmap::DatabaseImage> images = database.ReadImages();
  std::sort(images.begin(), images.end(),
            [](const colmap::DatabaseImage& a, const colmap::DatabaseImage& b) {
              return a.name < b.name;
            });
  return images;
}

int Run() {
  const trigrav::InitializeAndRefineOptions options = EstimatorOptions();
  const auto start = std::chrono::steady_clock::now();
  const colmap::GravityByImageName gravity = colmap::ReadGravityCsv(FLAGS_gravity_csv);
  const colmap::Database database(FLAGS_database_path);
  const std::vector<colmap::ColmapCamera> cameras = database.ReadCameras();
  std::map<colmap::CameraId, trigrav::Camera> camera_of_id;
  for (const colmap::ColmapCamera& camera : cameras) camera_of_id[camera.camera_id] = camera.camera;
  const std::vector<colmap::DatabaseImage> images = ImagesByName(database);
  std::map<colmap::ImageId, colmap::DatabaseImage> image_of_id;
  std::vector<colmap::ImageId> ids_by_name;
  for (const colmap::DatabaseImage& image : images) {
    image_of_id[image.image_id] = image;
    ids_by_name.push_back(image.image_id);
  }
  const colmap::MatchGraph graph(database.ReadTwoViewGeometries());
  const int max_triplets = FLAGS_max_triplets > 0 ? FLAGS_max_triplets : int(images.size());
  std::vector<std::array<colmap::ImageId, 3>> triplets =
      FLAGS_triplets == "consecutive" ? colmap::ConsecutiveTriplets(ids_by_name)
                                      : colmap::ConnectedTriplets(graph, ids_by_name, max_triplets);
  if (triplets.size() > std::size_t(max_triplets)) triplets.resize(max_triplets);
  if (triplets.empty()) throw std::runtime_error("no triplet of images in " + FLAGS_database_path);

  // The images of the triplets: gravity (every one needs one), keypoints.
  std::map<colmap::ImageId, std::vector<Eigen::Vector2d>> keypoints;
  for (const auto& triplet : triplets) {
    for (const colmap::ImageId id : triplet) keypoints[id];
  }
  std::vector<std::string> names;
  for (auto& [id, points] : keypoints) {
    names.push_back(image_of_id.at(id).name);
    points = database.ReadKeypoints(id);
  }
  const std::vector<Eigen::Vector3d> gravity_of_name = colmap::GravityOfImages(gravity, names);
  std::map<std::string, Eigen::Vector3d> gravity_of_image;
  for (std::size_t i = 0; i < names.size(); ++i) gravity_of_image[names[i]] = gravity_of_name[i];

  // Every triplet image's camera, before the workers (Database::ReadImages checks that each
  // image's camera row exists; this keeps the lookups below from throwing).
  for (const auto& [id, points] : keypoints) {
    const colmap::DatabaseImage& image = image_of_id.at(id);
    if (camera_of_id.count(image.camera_id) == 0) {
      throw std::runtime_error(FLAGS_database_path + ": image " + image.name + " has camera_id " +
                               std::to_string(image.camera_id) + ", not among the cameras");
    }
  }

  std::vector<colmap::TripletResult> results(triplets.size());
  std::vector<std::vector<colmap::ThreeViewTrack>> tracks(triplets.size());
  const auto estimate_triplet = [&](std::size_t i) {
    colmap::TripletResult& result = results[i];
    trigrav::ThreeViewObservations observations;
    for (int k = 0; k < 3; ++k) {
      result.images[k] = image_of_id.at(triplets[i][k]);
      observations.cameras[k] = camera_of_id.at(result.images[k].camera_id);
      observations.gravity_in_cam[k] = gravity_of_image.at(result.images[k].name);
    }
    tracks[i] = colmap::ThreeViewTracks(graph, triplets[i]);
    result.num_tracks = static_cast<int>(tracks[i].size());
    if (result.num_tracks < FLAGS_min_tracks) return;
    for (const colmap::ThreeViewTrack& track : tracks[i]) {
      for (int k = 0; k < 3; ++k) {
        observations.pixels[k].push_back(keypoints.at(triplets[i][k])[track[k]]);
      }
    }
    trigrav::InitializeAndRefineOptions triplet_options = options;
    triplet_options.robust.ransac.seed = FLAGS_seed + i;
    result.estimate = trigrav::InitializeAndRefine(observations, triplet_options);
    result.estimated = true;
  };
  // The pool rethrows a worker's exception after joining every thread.
  trigrav::examples::NoteFewerThreads(
      trigrav::ParallelFor(triplets.size(), FLAGS_threads, estimate_triplet));
  // Committed after the model (or alone when there is none): a failure leaves no CSV.
  tools::StagedFile csv(FLAGS_output_csv, colmap::FormatTripletCsv(
                                              results, options.bundle_adjustment.rotation_model));

  int best = -1, num_success = 0, num_trusted = 0;
  for (std::size_t i = 0; i < results.size(); ++i) {
    num_success += results[i].estimate.success;
    if (colmap::TripletVerdict(results[i]) != "trusted") continue;
    ++num_trusted;
    if (best < 0 || results[i].estimate.num_inliers > results[best].estimate.num_inliers) {
      best = static_cast<int>(i);
    }
  }
  std::cout << triplets.size() << " triplets (" << FLAGS_triplets << "): " << num_success
            << " estimated, " << num_trusted << " trusted; CSV " << FLAGS_output_csv << "\n";
  if (best < 0) {
    csv.Commit();
    std::cerr << "error: no trusted triplet; no model written (reasons in " << FLAGS_output_csv
              << ")" << std::endl;
    return 1;
  }
  const colmap::TripletResult& seed = results[best];
  std::array<std::vector<Eigen::Vector2d>, 3> seed_keypoints;
  for (int k = 0; k < 3; ++k) seed_keypoints[k] = keypoints.at(seed.images[k].image_id);
  const colmap::Reconstruction model =
      colmap::TripletModel(cameras, seed.images, seed_keypoints, tracks[best], seed.estimate);
  colmap::WriteModelCreatingParents(model, FLAGS_output_model_path, colmap::ModelFormat::kBinary);
  csv.Commit();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "seed triplet " << seed.images[0].name << " " << seed.images[1].name << " "
            << seed.images[2].name << ": " << seed.estimate.num_inliers << " inliers of "
            << seed.num_tracks << " tracks, " << model.points3D.size() << " points, RMS "
            << seed.estimate.refinement.residual_rms << " px; model " << FLAGS_output_model_path
            << "\ntotal " << seconds << " s\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  trigrav::examples::ParseToolFlags(
      "triplet_initializer --database_path=db.db --gravity_csv=g.csv --output_csv=triplets.csv "
      "--output_model_path=seed",
      __FILE__, &argc, &argv);
  CheckFlags();
  try {
    return Run();
  } catch (const std::exception& error) {
    std::cerr << "error: " << error.what() << std::endl;
    return 1;
  }
}
