// Tests of the refined pose's covariance (trigrav/ba/three_view_covariance.h) and of what
// RefineThreeViewPose returns beside the pose: residuals, their RMS, the relative scale.
#include <ceres/covariance.h>
#include <ceres/manifold.h>
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>
#include <vector>

#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/ba/refine_three_view_pose.h"
#include "trigrav/ba/three_view_bundle_adjustment.h"
#include "trigrav/ba/three_view_covariance.h"
#include "trigrav/evaluation/synthetic_scene.h"

namespace trigrav {
namespace {

using RotationModel = ThreeViewBundleAdjustmentOptions::RotationModel;

SyntheticSceneOptions InlierScene(int num_points, double imu_noise_deg) {
  SyntheticSceneOptions options;
  options.num_points = num_points;
  options.pixel_noise_px = 1.0;
  options.imu_pitch_noise_deg = imu_noise_deg;
  options.imu_roll_noise_deg = imu_noise_deg;
  return options;
}

ThreeViewBundleAdjustmentOptions Options(RotationModel model, bool covariance) {
  ThreeViewBundleAdjustmentOptions options;
  options.rotation_model = model;
  options.compute_covariance = covariance;
  return options;
}

// Refines the truth of a scene on its inliers.
ThreeViewRefinement RefineScene(const SyntheticScene& scene,
                                const ThreeViewBundleAdjustmentOptions& options) {
  return RefineThreeViewPose(ToObservations(scene), scene.ground_truth, scene.is_inlier, options);
}

class CovarianceModelTest : public ::testing::TestWithParam<RotationModel> {};

// The Schur-complement covariance equals ceres::Covariance (SPARSE_QR, all point blocks) on the
// same problem, mapped to Ceres' ambient coordinates: d yaw = d yaw, d q = P omega / 2 (P the
// QuaternionManifold's Plus Jacobian), d C2 = B u2, d C3 = d C3.
TEST_P(CovarianceModelTest, EqualsCeresCovarianceInAmbientCoordinates) {
  const RotationModel model = GetParam();
  std::mt19937_64 rng(3);
  const SyntheticScene scene = GenerateSyntheticScene(InlierScene(60, 0.2), &rng);
  const ThreeViewObservations observations = ToObservations(scene);
  ThreeViewBundleAdjustmentOptions options = Options(model, false);
  options.gravity_sigma_deg = 0.2;
  ThreeViewBundleAdjuster adjuster(observations, {}, options);
  ASSERT_TRUE(adjuster.Build(scene.ground_truth));
  ASSERT_TRUE(adjuster.Solve().success);
  Eigen::MatrixXd covariance;
  std::string message;
  ASSERT_TRUE(ComputeThreeViewPoseCovariance(&adjuster, 1.0, &covariance, &message)) << message;
  EXPECT_TRUE(message.empty());

  const std::vector<const double*> blocks = {adjuster.RotationBlock(2), adjuster.RotationBlock(3),
                                             adjuster.CenterBlock(2), adjuster.CenterBlock(3)};
  ceres::Covariance::Options ceres_options;
  ceres_options.algorithm_type = ceres::SPARSE_QR;
  ceres::Covariance ceres_covariance(ceres_options);
  ASSERT_TRUE(ceres_covariance.Compute(blocks, adjuster.problem()));
  const ThreeViewCovarianceLayout layout = ThreeViewCovarianceLayout::For(model);
  const int r = layout.rotation_size == 1 ? 1 : 4;  // ambient size of a rotation block
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> ambient(2 * r + 6,
                                                                                 2 * r + 6);
  ASSERT_TRUE(ceres_covariance.GetCovarianceMatrix(blocks, ambient.data()));

  Eigen::MatrixXd to_ambient = Eigen::MatrixXd::Zero(2 * r + 6, layout.Size());
  for (int view = 2; view <= 3; ++view) {
    if (r == 1) {
      to_ambient(view - 2, layout.Rotation(view)) = 1.0;
    } else {
      Eigen::Matrix<double, 4, 3, Eigen::RowMajor> plus_jacobian;
      ceres::QuaternionManifold().PlusJacobian(adjuster.RotationBlock(view), plus_jacobian.data());
      to_ambient.block<4, 3>(4 * (view - 2), layout.Rotation(view)) = 0.5 * plus_jacobian;
    }
  }
  to_ambient.block<3, 2>(2 * r, layout.Center2()) =
      CenterTangentBasis(Eigen::Map<const Eigen::Vector3d>(adjuster.CenterBlock(2)));
  to_ambient.block<3, 3>(2 * r + 3, layout.Center3()).setIdentity();
  const Eigen::MatrixXd ours = to_ambient * covariance * to_ambient.transpose();
  EXPECT_LT((ours - ambient).norm(), 1e-6 * ambient.norm()) << "ours\n"
                                                            << ours << "\nceres\n"
                                                            << ambient;
}

// Symmetric, positive definite, of full rank in the documented layout (7 or 11), and scaled by the
// assumed sigmas squared.
TEST_P(CovarianceModelTest, SymmetricFullRankAndScaledBySigmaSquared) {
  const RotationModel model = GetParam();
  std::mt19937_64 rng(5);
  const SyntheticScene scene = GenerateSyntheticScene(InlierScene(80, 0.0), &rng);
  ThreeViewBundleAdjustmentOptions options = Options(model, true);
  const ThreeViewRefinement refinement = RefineScene(scene, options);
  ASSERT_TRUE(refinement.summary.success) << refinement.summary.message;
  const Eigen::MatrixXd& covariance = refinement.covariance;
  const int size = ThreeViewCovarianceLayout::For(model).Size();
  ASSERT_EQ(covariance.rows(), size);
  ASSERT_EQ(covariance.cols(), size);
  EXPECT_EQ((covariance - covariance.transpose()).norm(), 0.0);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(covariance);
  EXPECT_GT(eigen.eigenvalues().minCoeff(), 1e-10 * eigen.eigenvalues().maxCoeff());

  // Doubling the pixel sigma (and the gravity sigma, so that the prior's relative weight and the
  // optimum stay) quadruples the covariance.
  options.pixel_sigma_px *= 2.0;
  options.gravity_sigma_deg *= 2.0;
  const ThreeViewRefinement doubled = RefineScene(scene, options);
  ASSERT_EQ(doubled.covariance.rows(), size);
  EXPECT_LT((doubled.covariance - 4.0 * covariance).norm(), 1e-6 * covariance.norm());
}

INSTANTIATE_TEST_SUITE_P(Models,
                         CovarianceModelTest,
                         ::testing::Values(RotationModel::kYawOnly, RotationModel::kGravityPrior));

TEST(CovarianceTest, NotComputedUnlessAskedFor) {
  std::mt19937_64 rng(7);
  const SyntheticScene scene = GenerateSyntheticScene(InlierScene(30, 0.0), &rng);
  const ThreeViewRefinement refinement =
      RefineScene(scene, Options(RotationModel::kYawOnly, false));
  ASSERT_TRUE(refinement.summary.success);
  EXPECT_EQ(refinement.covariance.size(), 0);
}

TEST(CovarianceTest, UnbuiltAdjusterGivesNoCovarianceAndAReason) {
  std::mt19937_64 rng(7);
  const SyntheticScene scene = GenerateSyntheticScene(InlierScene(30, 0.0), &rng);
  const ThreeViewObservations observations = ToObservations(scene);
  ThreeViewBundleAdjuster adjuster(observations, {}, Options(RotationModel::kYawOnly, false));
  Eigen::MatrixXd covariance = Eigen::MatrixXd::Identity(7, 7);
  std::string message;
  EXPECT_FALSE(ComputeThreeViewPoseCovariance(&adjuster, 1.0, &covariance, &message));
  EXPECT_EQ(covariance.size(), 0);
  EXPECT_FALSE(message.empty());
  EXPECT_THROW(ComputeThreeViewPoseCovariance(&adjuster, 0.0, &covariance, &message),
               std::invalid_argument);
  EXPECT_THROW(adjuster.RotationBlock(1), std::invalid_argument);
  EXPECT_THROW(adjuster.CenterBlock(4), std::invalid_argument);
}

// A camera with no observations (its residual blocks removed through problem()) has no
// information: the covariance is empty with a reason, never NaN.
TEST(CovarianceTest, RankDeficientGivesAnEmptyCovarianceAndAReason) {
  std::mt19937_64 rng(11);
  const SyntheticScene scene = GenerateSyntheticScene(InlierScene(40, 0.0), &rng);
  const ThreeViewObservations observations = ToObservations(scene);
  ThreeViewBundleAdjuster adjuster(observations, {}, Options(RotationModel::kYawOnly, false));
  ASSERT_TRUE(adjuster.Build(scene.ground_truth));
  ASSERT_TRUE(adjuster.Solve().success);
  std::vector<ceres::ResidualBlockId> camera3;
  adjuster.problem()->GetResidualBlocksForParameterBlock(adjuster.CenterBlock(3), &camera3);
  for (const ceres::ResidualBlockId id : camera3) adjuster.problem()->RemoveResidualBlock(id);
  Eigen::MatrixXd covariance;
  std::string message;
  EXPECT_FALSE(ComputeThreeViewPoseCovariance(&adjuster, 1.0, &covariance, &message));
  EXPECT_EQ(covariance.size(), 0);
  EXPECT_NE(message.find("rank-deficient"), std::string::npos) << message;
}

// The residual norms and their RMS at the refined pose, and the relative scale, on exact inliers
// with 1 px noise: RMS near sigma sqrt(1 - (3 n + 7) / (6 n)); scale near the truth.
TEST(CovarianceTest, ResidualsAndRelativeScaleAgainstTheTruth) {
  std::mt19937_64 rng(13);
  const SyntheticScene scene = GenerateSyntheticScene(InlierScene(300, 0.0), &rng);
  const ThreeViewRefinement refinement =
      RefineScene(scene, Options(RotationModel::kYawOnly, false));
  ASSERT_TRUE(refinement.summary.success);
  const double n = static_cast<double>(refinement.triplets.size());
  ASSERT_EQ(refinement.residual_norms.size(), refinement.triplets.size());
  const double expected_rms = std::sqrt(1.0 - (3.0 * n + 7.0) / (6.0 * n));
  EXPECT_NEAR(refinement.residual_rms, expected_rms, 0.05 * expected_rms);
  // Each residual norm is that of a 2-vector of about 0.7 px per component.
  for (const Eigen::Vector3d& norms : refinement.residual_norms) {
    EXPECT_TRUE(norms.allFinite());
    EXPECT_LT(norms.maxCoeff(), 6.0);
  }
  const double true_scale = scene.ground_truth.cam3_from_cam1.Center().norm() /
                            scene.ground_truth.cam2_from_cam1.Center().norm();
  EXPECT_NEAR(refinement.relative_scale, true_scale, 0.02 * true_scale);
  EXPECT_NEAR(refinement.relative_scale, refinement.pose.cam3_from_cam1.Center().norm(), 1e-12);
}

// Calibration over 150 scenes through InitializeAndRefine (1 px, 20 % outliers, a 4 px inlier
// threshold: at the default 2 px the selection of inliers by their noise makes the errors 5-25 %
// larger than predicted, examples/experiments/README.md): per parameter, the RMS over scenes of
// error / predicted sigma within 25 % of 1, and the mean normalised error e^T Sigma^-1 e within
// 30 % of the dimension.
void ExpectCalibrated(RotationModel model, double imu_noise_deg, double gravity_sigma_deg) {
  const ThreeViewCovarianceLayout layout = ThreeViewCovarianceLayout::For(model);
  const int n = layout.Size();
  InitializeAndRefineOptions options;
  options.robust.ransac.max_error = 4.0;
  options.bundle_adjustment.rotation_model = model;
  options.bundle_adjustment.gravity_sigma_deg = gravity_sigma_deg;
  options.bundle_adjustment.compute_covariance = true;
  SyntheticSceneOptions scene_options = InlierScene(100, imu_noise_deg);
  scene_options.outlier_ratio = 0.2;
  std::mt19937_64 rng(17);
  Eigen::VectorXd squared_z = Eigen::VectorXd::Zero(n);
  double normalised = 0.0;
  constexpr int kScenes = 150;
  int used = 0;
  for (int s = 0; s < kScenes; ++s) {
    const SyntheticScene scene = GenerateSyntheticScene(scene_options, &rng);
    const ThreeViewObservations observations = ToObservations(scene);
    options.robust.ransac.seed = static_cast<std::uint64_t>(s);
    const ThreeViewEstimate estimate = InitializeAndRefine(observations, options);
    // The verdict refuses a few (of these 150: two RANSAC poses 13-20 deg off, and one whose
    // RANSAC pose was 1.9 deg off, which the refinement would have mended).
    if (!estimate.success) continue;
    ++used;
    const Eigen::MatrixXd& covariance = estimate.refinement.covariance;
    ASSERT_EQ(covariance.rows(), n) << estimate.refinement.summary.message;
    const Eigen::VectorXd error = ThreeViewPoseDifference(
        model, estimate.refined, scene.ground_truth, observations.gravity_in_cam);
    squared_z += error.cwiseAbs2().cwiseQuotient(covariance.diagonal());
    normalised += error.dot(covariance.ldlt().solve(error));
  }
  ASSERT_GE(used, kScenes - 4);
  for (int i = 0; i < n; ++i) {
    const double rms_z = std::sqrt(squared_z[i] / used);
    EXPECT_GT(rms_z, 0.75) << "parameter " << i;
    EXPECT_LT(rms_z, 1.25) << "parameter " << i;
  }
  EXPECT_NEAR(normalised / used, n, 0.3 * n);
}

TEST(CovarianceCalibrationTest, YawOnly) { ExpectCalibrated(RotationModel::kYawOnly, 0.0, 0.5); }

TEST(CovarianceCalibrationTest, GravityPriorWithImuNoise) {
  ExpectCalibrated(RotationModel::kGravityPrior, 0.5, 0.5);
}

}  // namespace
}  // namespace trigrav
