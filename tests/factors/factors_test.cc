// Tests of trigrav::factors: analytic against numeric derivatives, agreement with the pose
// projection, the gravity prior, the yaw manifold.
#include <ceres/gradient_checker.h>
#include <ceres/manifold.h>
#include <ceres/manifold_test_utils.h>
#include <ceres/sphere_manifold.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/statistics.h"
#include "trigrav/evaluation/synthetic_scene.h"
#include "trigrav/factors/angle_manifold.h"
#include "trigrav/factors/reprojection_factors.h"
#include "trigrav/initializers/gravity.h"

namespace trigrav {
namespace {

PinholeCamera TestCamera() {
  PinholeCamera camera;
  camera.fx = 500.0;
  camera.fy = 510.0;
  camera.cx = 320.0;
  camera.cy = 240.0;
  return camera;
}

// Probes a cost function at the given parameters; expects analytic == numeric derivatives.
void ExpectGradientsMatch(const ceres::CostFunction& cost,
                          const std::vector<const ceres::Manifold*>& manifolds,
                          const std::vector<const double*>& parameters) {
  ceres::NumericDiffOptions numeric_options;
  ceres::GradientChecker checker(&cost, &manifolds, numeric_options);
  ceres::GradientChecker::ProbeResults results;
  EXPECT_TRUE(checker.Probe(parameters.data(), 1e-7, &results)) << results.error_log;
  EXPECT_TRUE(results.return_value);
  EXPECT_LT(results.maximum_relative_error, 1e-7);
}

TEST(FactorsTest, YawOnlyReprojectionGradient) {
  const Eigen::Matrix3d a_cam = GravityAlignmentFromPitchRoll(0.1, -0.05);
  const Eigen::Matrix3d a_ref = GravityAlignmentFromPitchRoll(-0.07, 0.12);
  std::unique_ptr<ceres::CostFunction> cost(
      YawOnlyReprojectionError::Create(TestCamera(), a_cam, a_ref, Eigen::Vector2d(300.0, 250.0)));
  const double yaw = 0.3;
  const double center[3] = {0.5, -0.2, 0.1};
  const double point[3] = {1.0, 0.5, 12.0};
  YawManifold yaw_manifold;
  ExpectGradientsMatch(*cost, {&yaw_manifold, nullptr, nullptr}, {&yaw, center, point});
}

TEST(FactorsTest, YawOnlyReprojectionMatchesPoseProjection) {
  const Eigen::Matrix3d a_cam = GravityAlignmentFromPitchRoll(0.1, -0.05);
  const Eigen::Matrix3d a_ref = GravityAlignmentFromPitchRoll(-0.07, 0.12);
  const double yaw = 0.3;
  const Eigen::Vector3d center(0.5, -0.2, 0.1), point(1.0, 0.5, 12.0);
  const Eigen::Matrix3d R = a_cam.transpose() * RotationAboutY(yaw) * a_ref;
  const Eigen::Vector3d x = R * (point - center);
  const PinholeCamera camera = TestCamera();
  const Eigen::Vector2d pixel(camera.fx * x.x() / x.z() + camera.cx,
                              camera.fy * x.y() / x.z() + camera.cy);
  const YawOnlyReprojectionError functor(camera, a_cam, a_ref, pixel);
  double residuals[2];
  ASSERT_TRUE(functor(&yaw, center.data(), point.data(), residuals));
  EXPECT_NEAR(residuals[0], 0.0, 1e-9);
  EXPECT_NEAR(residuals[1], 0.0, 1e-9);
}

TEST(FactorsTest, ReprojectionGradient) {
  std::unique_ptr<ceres::CostFunction> cost(
      ReprojectionError::Create(TestCamera(), Eigen::Vector2d(310.0, 230.0)));
  Eigen::Quaterniond q(Eigen::AngleAxisd(0.2, Eigen::Vector3d(0.3, 1.0, -0.2).normalized()));
  const double quaternion[4] = {q.w(), q.x(), q.y(), q.z()};
  const double center[3] = {-0.4, 0.3, 0.2};
  const double point[3] = {-1.0, 0.8, 15.0};
  ceres::QuaternionManifold quaternion_manifold;
  ExpectGradientsMatch(*cost, {&quaternion_manifold, nullptr, nullptr},
                       {quaternion, center, point});
  ExpectGradientsMatch(*cost, {nullptr, nullptr, nullptr}, {quaternion, center, point});
}

TEST(FactorsTest, ReferenceReprojectionGradient) {
  std::unique_ptr<ceres::CostFunction> cost(
      ReferenceReprojectionError::Create(TestCamera(), Eigen::Vector2d(310.0, 230.0)));
  const double point[3] = {-1.0, 0.8, 15.0};
  ExpectGradientsMatch(*cost, {nullptr}, {point});
}

TEST(FactorsTest, GravityPriorGradientAndValue) {
  const Eigen::Vector3d g_ref = Eigen::Vector3d(0.05, 1.0, -0.1);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, 1.0, 0.4).normalized()));
  // Measured gravity 2 degrees away from the predicted one.
  const Eigen::Vector3d predicted = q * g_ref.normalized();
  const Eigen::Vector3d axis = predicted.cross(Eigen::Vector3d(0.3, -0.5, 0.8)).normalized();
  const double angle = 2.0 * M_PI / 180.0;
  const Eigen::Vector3d g_cam = 3.0 * (Eigen::AngleAxisd(angle, axis) * predicted);
  std::unique_ptr<ceres::CostFunction> cost(GravityPriorError::Create(g_ref, g_cam));
  const double quaternion[4] = {q.w(), q.x(), q.y(), q.z()};
  ceres::QuaternionManifold quaternion_manifold;
  ExpectGradientsMatch(*cost, {&quaternion_manifold}, {quaternion});
  ExpectGradientsMatch(*cost, {nullptr}, {quaternion});

  const GravityPriorError functor(g_ref, g_cam);
  double residuals[2];
  ASSERT_TRUE(functor(quaternion, residuals));
  EXPECT_NEAR(std::hypot(residuals[0], residuals[1]), angle, 1e-12);
  // Zero at an exact match, with finite derivatives there.
  const GravityPriorError exact(g_ref, predicted);
  ASSERT_TRUE(exact(quaternion, residuals));
  EXPECT_NEAR(residuals[0], 0.0, 1e-15);
  EXPECT_NEAR(residuals[1], 0.0, 1e-15);
  std::unique_ptr<ceres::CostFunction> exact_cost(GravityPriorError::Create(g_ref, predicted));
  ExpectGradientsMatch(*exact_cost, {&quaternion_manifold}, {quaternion});
  EXPECT_THROW(GravityPriorError(Eigen::Vector3d::Zero(), g_cam), std::invalid_argument);
}

TEST(FactorsTest, YawManifoldInvariants) {
  using Vector = Eigen::VectorXd;
  using namespace ceres;  // the matchers of manifold_test_utils.h
  const YawManifold manifold;
  const double values[][3] = {
      {0.3, 0.2, -2.0}, {3.0, 0.3, -3.0}, {-3.1, -0.2, 2.9}, {0.0, 1.5, 1.0}, {-1.0, -2.5, 3.1}};
  for (const auto& v : values) {
    const Vector x = Vector::Constant(1, v[0]);
    const Vector delta = Vector::Constant(1, v[1]);
    const Vector y = Vector::Constant(1, v[2]);
    EXPECT_THAT_MANIFOLD_INVARIANTS_HOLD(manifold, x, delta, y, 1e-9);
  }
  double wrapped = 0.0;
  const double x = 3.0, delta = 0.5;
  ASSERT_TRUE(manifold.Plus(&x, &delta, &wrapped));
  EXPECT_NEAR(wrapped, 3.5 - 2.0 * M_PI, 1e-15);
  EXPECT_GE(NormalizeAngle(M_PI), -M_PI);
  EXPECT_LT(NormalizeAngle(M_PI), M_PI);
}

}  // namespace
}  // namespace trigrav
