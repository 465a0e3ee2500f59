// The Ceres engine with the points eliminated (ThreeViewBundleAdjustmentOptions::Engine::
// kCeresPointsEliminated) against the plain Ceres engine (kCeres) on the same problems: same final
// cost, pose and covariance; the same failures; warm-started second refinements
// (RefineThreeViewPose with a previous refinement); problem() solved as kCeres, and said so, once
// a caller asked for it.
#include <ceres/autodiff_cost_function.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/ba/refine_three_view_pose.h"
#include "trigrav/ba/three_view_bundle_adjustment.h"
#include "trigrav/ba/three_view_covariance.h"
#include "trigrav/evaluation/synthetic_scene.h"
#include "typical_cameras.h"

namespace trigrav {
namespace {

using Options = ThreeViewBundleAdjustmentOptions;
using Engine = Options::Engine;
using LossType = Options::LossType;
using RotationModel = Options::RotationModel;

double RotationAngle(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(Eigen::Matrix3d(a * b.transpose())).angle();
}

// Largest rotation angle (rad) and centre distance (units of |C2|) between two poses.
double PoseDistance(const ThreeViewPose& a, const ThreeViewPose& b) {
  return std::max({RotationAngle(a.cam2_from_cam1.R, b.cam2_from_cam1.R),
                   RotationAngle(a.cam3_from_cam1.R, b.cam3_from_cam1.R),
                   (a.cam2_from_cam1.Center() - b.cam2_from_cam1.Center()).norm(),
                   (a.cam3_from_cam1.Center() - b.cam3_from_cam1.Center()).norm()});
}

// The truth of a scene moved by about a degree and 5 % of the baseline.
ThreeViewPose Perturbed(const ThreeViewPose& truth, std::mt19937_64* rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  auto rotation = [&]() {
    const Eigen::Vector3d w(normal(*rng), normal(*rng), normal(*rng));
    return Eigen::AngleAxisd(0.02 * w.norm(), w.normalized()).toRotationMatrix();
  };
  ThreeViewPose pose = truth;
  const double baseline = truth.cam2_from_cam1.Center().norm();
  for (CameraPose* p : {&pose.cam2_from_cam1, &pose.cam3_from_cam1}) {
    const Eigen::Vector3d center =
        p->Center() + 0.05 * baseline * Eigen::Vector3d(normal(*rng), normal(*rng), normal(*rng));
    p->R = rotation() * p->R;
    p->t = -p->R * center;
  }
  return pose;
}

// A scene with 10 % outliers and IMU tilt noise, observed through `camera` (pixels re-projected
// with 1 px noise) or as bearings.
ThreeViewObservations SceneObservations(CameraModel camera,
                                        bool bearings,
                                        std::mt19937_64* rng,
                                        SyntheticScene* scene) {
  SyntheticSceneOptions options;
  options.num_points = 80;
  options.pixel_noise_px = 1.0;
  options.imu_pitch_noise_deg = 0.2;
  options.imu_roll_noise_deg = 0.2;
  options.outlier_ratio = 0.1;
  *scene = GenerateSyntheticScene(options, rng);
  if (bearings) return ToBearingObservations(*scene);
  ThreeViewObservations observations = ToObservations(*scene);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (int k = 0; k < 3; ++k) {
    observations.cameras[k] = TypicalCamera(camera);
    for (std::size_t i = 0; i < scene->points_in_world.size(); ++i) {
      if (!scene->is_inlier[i]) continue;  // outliers keep their (wrong) pixels
      const Eigen::Vector3d x =
          scene->cam_from_world[k] * (scene->points_in_world[i] - scene->center_in_world[k]);
      observations.pixels[k][i] =
          observations.cameras[k].Project(x) + Eigen::Vector2d(noise(*rng), noise(*rng));
    }
  }
  return observations;
}

struct Solved {
  ThreeViewBundleAdjustmentSummary summary;
  ThreeViewPose pose;
  std::vector<Eigen::Vector3d> points;
};

Solved BuildAndSolve(const ThreeViewObservations& observations,
                     const ThreeViewPose& initial,
                     const Options& options,
                     const ThreeViewBundleAdjustmentConfig& config = {}) {
  ThreeViewBundleAdjuster adjuster(observations, config, options);
  Solved out;
  EXPECT_TRUE(adjuster.Build(initial)) << adjuster.message();
  out.summary = adjuster.Solve();
  out.pose = adjuster.CurrentPose();
  out.points = adjuster.points();
  return out;
}

std::string CaseName(RotationModel model, bool bearings, CameraModel camera, LossType loss) {
  const char* losses[] = {"none", "huber", "cauchy"};
  return std::string(model == RotationModel::kYawOnly ? "yaw-only" : "gravity-prior") + " " +
         (bearings ? "bearings" : CameraModelName(camera)) + " " + losses[static_cast<int>(loss)];
}

// The kCeres engine's options of the random problems (gravity sigma 0.2 deg, the scenes' IMU
// noise).
Options CeresOptions(RotationModel model, LossType loss) {
  Options options;
  options.engine = Engine::kCeres;
  options.rotation_model = model;
  options.loss = loss;
  options.gravity_sigma_deg = 0.2;
  return options;
}

// Calls test(model, bearings, camera, loss) for every rotation model, camera model (and bearings,
// with the camera unused) and loss.
template <typename Test>
void ForEveryProblemKind(const Test& test) {
  for (const RotationModel model : {RotationModel::kYawOnly, RotationModel::kGravityPrior}) {
    for (int observation = 0; observation <= static_cast<int>(kCameraModels.size());
         ++observation) {
      const bool bearings = observation == static_cast<int>(kCameraModels.size());
      const CameraModel camera = bearings ? CameraModel::kPinhole : kCameraModels[observation];
      for (const LossType loss : {LossType::kNone, LossType::kHuber, LossType::kCauchy}) {
        test(model, bearings, camera, loss);
      }
    }
  }
}

// Engine::kCeresPointsEliminated (variable projection) against Engine::kCeres, on every rotation
// model, camera model (and bearings) and loss, on the inliers: the same optimum, poses to 1e-6 and
// points to 1e-6 of their distance.
TEST(EngineAgreementTest, PointsEliminatedEngineReachesTheCeresOptimum) {
  std::mt19937_64 rng(29);
  int cases = 0;
  ForEveryProblemKind([&](RotationModel model, bool bearings, CameraModel camera, LossType loss) {
    SCOPED_TRACE(CaseName(model, bearings, camera, loss));
    SyntheticScene scene;
    const ThreeViewObservations observations = SceneObservations(camera, bearings, &rng, &scene);
    const ThreeViewPose initial = Perturbed(scene.ground_truth, &rng);
    Options options = CeresOptions(model, loss);
    options.function_tolerance = 1e-12;
    options.max_num_iterations = 500;  // the joint problem crawls with Cauchy's loss
    // The inliers: an outlier's robust cost (Cauchy's most) can have several minima over its
    // point, and the two formulations, which move the points differently, may settle in
    // different ones.
    const ThreeViewBundleAdjustmentConfig config =
        ThreeViewBundleAdjustmentConfig::FromInlierMask(scene.is_inlier);
    const Solved ceres = BuildAndSolve(observations, initial, options, config);
    options.engine = Engine::kCeresPointsEliminated;
    const Solved eliminated = BuildAndSolve(observations, initial, options, config);
    ASSERT_TRUE(ceres.summary.success) << ceres.summary.message;
    ASSERT_TRUE(eliminated.summary.success) << eliminated.summary.message;
    EXPECT_EQ(eliminated.summary.num_residual_blocks, ceres.summary.num_residual_blocks);
    ++cases;
    if (loss == LossType::kCauchy) {
      // Cauchy's cost is not convex where the imposed tilt leaves residuals of several
      // pixels: the two formulations can stop in different minima. Never in a worse one here.
      EXPECT_LE(eliminated.summary.FinalCost(), ceres.summary.FinalCost() * (1.0 + 1e-8))
          << eliminated.summary.BriefReport() << "\n"
          << ceres.summary.BriefReport();
      if (eliminated.summary.FinalCost() < ceres.summary.FinalCost() * (1.0 - 1e-8)) return;
    }
    EXPECT_NEAR(eliminated.summary.FinalCost(), ceres.summary.FinalCost(),
                1e-8 * ceres.summary.FinalCost())
        << eliminated.summary.BriefReport() << "\n"
        << ceres.summary.BriefReport();
    EXPECT_LT(PoseDistance(eliminated.pose, ceres.pose), 1e-6);
    ASSERT_EQ(eliminated.points.size(), ceres.points.size());
    for (std::size_t p = 0; p < ceres.points.size(); ++p) {
      EXPECT_LT((eliminated.points[p] - ceres.points[p]).norm(), 1e-6 * ceres.points[p].norm());
    }
  });
  EXPECT_EQ(cases, 2 * 7 * 3);
}

// Residual 1e4 C (3) of a centre: a strong prior towards the origin.
struct CenterPrior {
  template <typename T>
  bool operator()(const T* center, T* residual) const {
    for (int i = 0; i < 3; ++i) residual[i] = T(1e4) * center[i];
    return true;
  }
};

// kCeresPointsEliminated solves problem() as kCeres when there is nothing to eliminate (constant
// points) and when a caller asked for problem() (their factors would be ignored otherwise): a
// caller's prior on C3 moves the result as it does with kCeres.
TEST(EngineAgreementTest, PointsEliminatedEngineSolvesProblemWhenAskedForIt) {
  std::mt19937_64 rng(31);
  SyntheticScene scene;
  const ThreeViewObservations observations =
      SceneObservations(CameraModel::kPinhole, false, &rng, &scene);
  const ThreeViewPose initial = Perturbed(scene.ground_truth, &rng);
  ThreeViewBundleAdjustmentConfig constant;
  constant.constant_points = true;
  Options options;
  options.engine = Engine::kCeres;
  const Solved ceres = BuildAndSolve(observations, initial, options, constant);
  options.engine = Engine::kCeresPointsEliminated;
  const Solved eliminated = BuildAndSolve(observations, initial, options, constant);
  ASSERT_TRUE(eliminated.summary.success) << eliminated.summary.message;
  EXPECT_EQ(eliminated.summary.engine, Engine::kCeres);  // nothing to eliminate: said so
  EXPECT_EQ(eliminated.summary.FinalCost(), ceres.summary.FinalCost());
  EXPECT_EQ(eliminated.points, ceres.points);

  // A prior pulling C3 to the origin, added through problem() with either engine.
  std::vector<ThreeViewPose> with_prior;
  for (const Engine engine : {Engine::kCeres, Engine::kCeresPointsEliminated}) {
    options.engine = engine;
    ThreeViewBundleAdjuster adjuster(observations, {}, options);
    ASSERT_TRUE(adjuster.Build(initial));
    adjuster.problem()->AddResidualBlock(
        new ceres::AutoDiffCostFunction<CenterPrior, 3, 3>(new CenterPrior), nullptr,
        adjuster.CenterBlock(3));
    const ThreeViewBundleAdjustmentSummary summary = adjuster.Solve();
    ASSERT_TRUE(summary.success);
    EXPECT_EQ(summary.engine, Engine::kCeres);  // the caller's factors take part: said so
    with_prior.push_back(adjuster.CurrentPose());
  }
  EXPECT_LT(PoseDistance(with_prior[0], with_prior[1]), 1e-12);
  EXPECT_LT(with_prior[1].cam3_from_cam1.Center().norm(),
            0.5 * scene.ground_truth.cam3_from_cam1.Center().norm() /
                scene.ground_truth.cam2_from_cam1.Center().norm());
}

// Tight tolerances and iterations enough for both (kCeres takes more than 50 on the yaw-only
// problem): both engines go to the same point, to the precision of the eliminated engine's inner
// point minimisation: poses to 1e-7 (measured 4e-9), points to 1e-4 of their distance (measured
// up to 1.3e-5: a distant point's depth is weakly determined, and moves far for a tiny cost).
TEST(EngineAgreementTest, ConvergesToTheSamePointAtTightTolerances) {
  std::mt19937_64 rng(23);
  for (const RotationModel model : {RotationModel::kYawOnly, RotationModel::kGravityPrior}) {
    SyntheticScene scene;
    const ThreeViewObservations observations =
        SceneObservations(CameraModel::kOpenCV, false, &rng, &scene);
    const ThreeViewPose initial = Perturbed(scene.ground_truth, &rng);
    Options options;
    options.engine = Engine::kCeres;
    options.rotation_model = model;
    options.function_tolerance = 1e-15;
    options.parameter_tolerance = 1e-15;
    options.gradient_tolerance = 1e-15;
    options.max_num_iterations = 1000;
    const Solved ceres = BuildAndSolve(observations, initial, options);
    options.engine = Engine::kCeresPointsEliminated;
    const Solved eliminated = BuildAndSolve(observations, initial, options);
    ASSERT_TRUE(ceres.summary.success && eliminated.summary.success);
    EXPECT_LT(PoseDistance(eliminated.pose, ceres.pose), 1e-7);
    ASSERT_EQ(eliminated.points.size(), ceres.points.size());
    for (std::size_t p = 0; p < ceres.points.size(); ++p) {
      EXPECT_LT((eliminated.points[p] - ceres.points[p]).norm(), 1e-4 * ceres.points[p].norm());
    }
  }
}

// The covariance after the points-eliminated engine's solve equals the one after kCeres', with
// either rotation model and constant points (Huber's loss: Cauchy's cost can have several minima,
// and the engines may stop in different ones).
TEST(EngineAgreementTest, CovarianceEqualsTheCeresEngines) {
  std::mt19937_64 rng(29);
  for (const RotationModel model : {RotationModel::kYawOnly, RotationModel::kGravityPrior}) {
    for (const bool constant_points : {false, true}) {
      SyntheticScene scene;
      const ThreeViewObservations observations =
          SceneObservations(CameraModel::kPinhole, false, &rng, &scene);
      Options options;
      options.rotation_model = model;
      options.loss = LossType::kHuber;
      options.loss_scale_px = 1.0;
      options.compute_covariance = true;
      // Both engines at the same optimum (as in ConvergesToTheSamePointAtTightTolerances).
      options.function_tolerance = options.gradient_tolerance = options.parameter_tolerance = 1e-15;
      options.max_num_iterations = 1000;
      std::vector<char> all(observations.size(), 1);
      ThreeViewBundleAdjustmentConfig config;
      config.constant_points = constant_points;
      Eigen::MatrixXd covariance[2];
      for (const Engine engine : {Engine::kCeres, Engine::kCeresPointsEliminated}) {
        options.engine = engine;
        if (!constant_points) {
          const ThreeViewRefinement refinement =
              RefineThreeViewPose(observations, scene.ground_truth, all, options);
          ASSERT_TRUE(refinement.summary.success) << refinement.summary.message;
          covariance[static_cast<int>(engine)] = refinement.covariance;
          EXPECT_TRUE(refinement.summary.message.empty()) << refinement.summary.message;
          continue;
        }
        ThreeViewBundleAdjuster adjuster(observations, config, options);
        ASSERT_TRUE(adjuster.Build(scene.ground_truth));
        ASSERT_TRUE(adjuster.Solve().success);
        std::string message;
        ASSERT_TRUE(ComputeThreeViewPoseCovariance(&adjuster, 1.0,
                                                   &covariance[static_cast<int>(engine)], &message))
            << message;
      }
      ASSERT_GT(covariance[0].size(), 0);
      ASSERT_EQ(covariance[1].rows(), covariance[0].rows());
      EXPECT_LT((covariance[1] - covariance[0]).norm(), 1e-6 * covariance[0].norm())
          << "ceres\n"
          << covariance[0] << "\neliminated\n"
          << covariance[1];
    }
  }
}

// Constant points (motion-only): the same optimum and fixed cost as Ceres.
TEST(EngineAgreementTest, ConstantPointsMatchCeres) {
  std::mt19937_64 rng(31);
  SyntheticScene scene;
  const ThreeViewObservations observations =
      SceneObservations(CameraModel::kPinhole, false, &rng, &scene);
  ThreeViewBundleAdjustmentConfig config;
  config.constant_points = true;
  Options options;
  const ThreeViewPose initial = Perturbed(scene.ground_truth, &rng);
  ThreeViewBundleAdjustmentSummary summary[2];
  ThreeViewPose pose[2];
  for (const Engine engine : {Engine::kCeres, Engine::kCeresPointsEliminated}) {
    options.engine = engine;
    ThreeViewBundleAdjuster adjuster(observations, config, options);
    ASSERT_TRUE(adjuster.Build(initial));
    summary[static_cast<int>(engine)] = adjuster.Solve();
    pose[static_cast<int>(engine)] = adjuster.CurrentPose();
    ASSERT_TRUE(summary[static_cast<int>(engine)].success);
  }
  EXPECT_NEAR(summary[1].FinalCost(), summary[0].FinalCost(), 1e-8 * summary[0].FinalCost());
  EXPECT_LT(PoseDistance(pose[1], pose[0]), 1e-6);
  EXPECT_GT(summary[1].ceres_summary.fixed_cost, 0.0);
  EXPECT_NEAR(summary[1].ceres_summary.fixed_cost, summary[0].ceres_summary.fixed_cost,
              1e-9 * summary[0].ceres_summary.fixed_cost);
}

// Zero iterations: both stop at once (NO_CONVERGENCE, a usable solution), cost unchanged.
TEST(EngineAgreementTest, ZeroIterationsLikeCeres) {
  std::mt19937_64 rng(37);
  SyntheticScene scene;
  const ThreeViewObservations observations =
      SceneObservations(CameraModel::kPinhole, false, &rng, &scene);
  Options options;
  options.engine = Engine::kCeresPointsEliminated;
  options.max_num_iterations = 0;
  const Solved solved = BuildAndSolve(observations, Perturbed(scene.ground_truth, &rng), options);
  EXPECT_TRUE(solved.summary.success);
  EXPECT_EQ(solved.summary.Iterations(), 1);  // iteration 0, counted as Ceres counts it
  EXPECT_EQ(solved.summary.ceres_summary.termination_type, ceres::NO_CONVERGENCE);
  EXPECT_EQ(solved.summary.FinalCost(), solved.summary.InitialCost());
  EXPECT_NE(solved.summary.BriefReport().find("NO_CONVERGENCE"), std::string::npos);
}

// Failures: success false with a message, never a NaN pose.
TEST(EngineAgreementTest, FailuresGiveAMessage) {
  std::mt19937_64 rng(41);
  SyntheticScene scene;
  const ThreeViewObservations observations =
      SceneObservations(CameraModel::kPinhole, false, &rng, &scene);
  Options options;
  options.engine = Engine::kCeresPointsEliminated;
  std::vector<char> two(observations.size(), 0);
  two[0] = two[1] = 1;
  const ThreeViewRefinement few =
      RefineThreeViewPose(observations, scene.ground_truth, two, options);
  EXPECT_FALSE(few.summary.success);
  EXPECT_NE(few.summary.message.find("fewer than 3"), std::string::npos) << few.summary.message;

  ThreeViewPose nan_pose = scene.ground_truth;
  nan_pose.cam3_from_cam1.t.x() = std::numeric_limits<double>::quiet_NaN();
  const ThreeViewRefinement nan = RefineThreeViewPose(
      observations, nan_pose, std::vector<char>(observations.size(), 1), options);
  EXPECT_FALSE(nan.summary.success);
  EXPECT_FALSE(nan.summary.message.empty());

  ThreeViewBundleAdjuster unbuilt(observations, {}, options);
  EXPECT_FALSE(unbuilt.Solve().success);
  EXPECT_EQ(unbuilt.problem(), nullptr);

  options.engine = static_cast<Engine>(7);
  EXPECT_THROW(options.Check(), std::invalid_argument);
}

// A second refinement from the first one's pose and points: the known points are where it starts
// (zero iterations return them), on the same inliers it has nothing left to do, and new inliers
// are triangulated.
TEST(EngineAgreementTest, SecondRefinementStartsFromThePreviousPoints) {
  std::mt19937_64 rng(43);
  SyntheticScene scene;
  const ThreeViewObservations observations =
      SceneObservations(CameraModel::kPinhole, false, &rng, &scene);
  for (const Engine engine : {Engine::kCeres, Engine::kCeresPointsEliminated}) {
    Options options;
    options.engine = engine;
    std::vector<char> first = scene.is_inlier;
    for (std::size_t i = 0; i < first.size(); i += 5) first[i] = 0;  // leave some inliers out
    const ThreeViewRefinement refinement =
        RefineThreeViewPose(observations, Perturbed(scene.ground_truth, &rng), first, options);
    ASSERT_TRUE(refinement.summary.success) << refinement.summary.message;

    const ThreeViewRefinement again =
        RefineThreeViewPose(observations, refinement.pose, first, options, refinement);
    ASSERT_TRUE(again.summary.success);
    EXPECT_NEAR(again.summary.InitialCost(), refinement.summary.FinalCost(),
                1e-12 * refinement.summary.FinalCost());
    EXPECT_LE(again.summary.Iterations(), 2);

    Options frozen = options;
    frozen.max_num_iterations = 0;
    const ThreeViewRefinement grown =
        RefineThreeViewPose(observations, refinement.pose, scene.is_inlier, frozen, refinement);
    ASSERT_TRUE(grown.summary.success);
    ASSERT_GT(grown.triplets.size(), refinement.triplets.size());
    std::size_t known = 0;
    for (std::size_t p = 0; p < grown.triplets.size(); ++p) {
      for (std::size_t q = 0; q < refinement.triplets.size(); ++q) {
        if (refinement.triplets[q] != grown.triplets[p]) continue;
        // The same point, rescaled by 1 / |C2| of the refined pose (1 to round-off).
        EXPECT_LT((grown.points_in_cam1[p] - refinement.points_in_cam1[q]).norm(),
                  1e-14 * refinement.points_in_cam1[q].norm());
        ++known;
      }
    }
    EXPECT_EQ(known, refinement.triplets.size());
  }
}

// InitializeAndRefine with either engine: the same inliers and refined pose, and the stages'
// times add up within the refinement's.
TEST(EngineAgreementTest, InitializeAndRefineAgreesWithTheCeresEngine) {
  std::mt19937_64 rng(47);
  for (int trial = 0; trial < 5; ++trial) {
    SyntheticSceneOptions scene_options;
    scene_options.num_points = 200;
    scene_options.pixel_noise_px = 1.0;
    scene_options.outlier_ratio = 0.2;
    const SyntheticScene scene = GenerateSyntheticScene(scene_options, &rng);
    const ThreeViewObservations observations = ToObservations(scene);
    InitializeAndRefineOptions options;
    options.robust.ransac.seed = 3;
    options.bundle_adjustment.engine = Engine::kCeres;
    // kCeresPointsEliminated takes other steps to the optimum: at the default tolerance (1e-8)
    // its pose stops up to 6e-6 from the others..
    options.bundle_adjustment.function_tolerance = 1e-12;
    const ThreeViewEstimate ceres = InitializeAndRefine(observations, options);
    for (const Engine engine : {Engine::kCeresPointsEliminated, Engine::kCeresPointsEliminated}) {
      SCOPED_TRACE(EngineName(engine));
      options.bundle_adjustment.engine = engine;
      const ThreeViewEstimate other = InitializeAndRefine(observations, options);
      ASSERT_TRUE(ceres.success && other.success);
      ASSERT_TRUE(other.refinement.summary.success) << other.message;
      EXPECT_EQ(other.inliers, ceres.inliers);
      EXPECT_EQ(other.refinement_runs, ceres.refinement_runs);
      EXPECT_LT(PoseDistance(other.refined, ceres.refined), 1e-6);
      EXPECT_NEAR(other.refinement.summary.FinalCost(), ceres.refinement.summary.FinalCost(),
                  1e-8 * ceres.refinement.summary.FinalCost());
      const ThreeViewEstimateTimings& t = other.timings;
      EXPECT_GT(t.build_s, 0.0);
      EXPECT_GT(t.solve_s, 0.0);
      EXPECT_GT(t.reclassification_s, 0.0);
      EXPECT_LE(t.build_s + t.solve_s + t.covariance_s + t.reclassification_s, t.refinement_s);
      EXPECT_LE(t.ransac_s + t.refinement_s, t.total_s);
    }
  }
}

}  // namespace
}  // namespace trigrav
