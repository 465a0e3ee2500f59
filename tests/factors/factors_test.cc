// Tests of trigrav::factors: analytic against numeric derivatives, agreement with the pose
// projection, the gravity prior, the yaw manifold.
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
#include <type_traits>
#include <vector>

#include "expect_gradients_match.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/statistics.h"
#include "trigrav/evaluation/synthetic_scene.h"
#include "trigrav/factors/angle_manifold.h"
#include "trigrav/factors/reprojection_factors.h"
#include "trigrav/initializers/gravity.h"
#include "typical_cameras.h"

namespace trigrav {
namespace {

// The factors' analytic derivatives agree with numeric ones to 1e-7.
constexpr double kGradientTolerance = 1e-7;

// Runs `test` with the pixel residual of every camera model and with a bearing residual, each
// observing `observed_in_cam` (pixel = its projection, bearing = its direction) shifted by a small
// offset so that the residual is not zero.
template <typename Test>
void ForEveryResidual(const Eigen::Vector3d& observed_in_cam, const Test& test) {
  const Eigen::Vector3d shifted = observed_in_cam + Eigen::Vector3d(0.03, -0.02, 0.0);
  for (const CameraModel model : kCameraModels) {
    const Camera camera = TypicalCamera(model);
    SCOPED_TRACE(CameraModelName(camera.model));
    test(PixelResidual{camera, camera.Project(shifted)});
  }
  SCOPED_TRACE("bearing");
  test(BearingResidual(shifted));
}

TEST(FactorsTest, YawOnlyReprojectionGradient) {
  const Eigen::Matrix3d a_cam = GravityAlignmentFromPitchRoll(0.1, -0.05);
  const Eigen::Matrix3d a_ref = GravityAlignmentFromPitchRoll(-0.07, 0.12);
  const double yaw = 0.3;
  const double center[3] = {0.5, -0.2, 0.1};
  const double point[3] = {1.0, 0.5, 12.0};
  const Eigen::Vector3d x = a_cam.transpose() * RotationAboutY(yaw) * a_ref *
                            (Eigen::Vector3d(point) - Eigen::Vector3d(center));
  ForEveryResidual(x, [&](const auto& residual) {
    using Residual = std::decay_t<decltype(residual)>;
    std::unique_ptr<ceres::CostFunction> cost(
        YawOnlyReprojectionError<Residual>::Create(residual, a_cam, a_ref));
    YawManifold yaw_manifold;
    ExpectGradientsMatch(*cost, {&yaw_manifold, nullptr, nullptr}, {&yaw, center, point},
                         kGradientTolerance);
  });
}

TEST(FactorsTest, YawOnlyReprojectionMatchesPoseProjection) {
  const Eigen::Matrix3d a_cam = GravityAlignmentFromPitchRoll(0.1, -0.05);
  const Eigen::Matrix3d a_ref = GravityAlignmentFromPitchRoll(-0.07, 0.12);
  const double yaw = 0.3;
  const Eigen::Vector3d center(0.5, -0.2, 0.1), point(1.0, 0.5, 12.0);
  const Eigen::Matrix3d R = a_cam.transpose() * RotationAboutY(yaw) * a_ref;
  const Eigen::Vector3d x = R * (point - center);
  for (const CameraModel model : kCameraModels) {
    const Camera camera = TypicalCamera(model);
    const YawOnlyReprojectionError<PixelResidual> functor({camera, camera.Project(x)}, a_cam,
                                                          a_ref);
    double residuals[2];
    ASSERT_TRUE(functor(&yaw, center.data(), point.data(), residuals));
    EXPECT_NEAR(residuals[0], 0.0, 1e-9) << CameraModelName(camera.model);
    EXPECT_NEAR(residuals[1], 0.0, 1e-9) << CameraModelName(camera.model);
  }
  const YawOnlyReprojectionError<BearingResidual> bearing(BearingResidual(3.0 * x), a_cam, a_ref);
  double residuals[2];
  ASSERT_TRUE(bearing(&yaw, center.data(), point.data(), residuals));
  EXPECT_NEAR(residuals[0], 0.0, 1e-12);
  EXPECT_NEAR(residuals[1], 0.0, 1e-12);
}

TEST(FactorsTest, BearingResidualIsTheAngleInDegrees) {
  const Eigen::Vector3d b = Eigen::Vector3d(0.2, -0.4, 1.0).normalized();
  const BearingResidual residual(5.0 * b);
  EXPECT_NEAR(
      (residual.frame() * residual.frame().transpose() - Eigen::Matrix3d::Identity()).norm(), 0.0,
      1e-15);
  const Eigen::Vector3d axis = b.cross(Eigen::Vector3d::UnitX()).normalized();
  for (const double angle_deg : {0.01, 0.5, 10.0}) {
    const Eigen::Vector3d x = 7.0 * (Eigen::AngleAxisd(angle_deg * M_PI / 180.0, axis) * b);
    double r[2];
    ASSERT_TRUE(residual(x.data(), r));
    EXPECT_NEAR(std::hypot(r[0], r[1]), std::tan(angle_deg * M_PI / 180.0) * 180.0 / M_PI,
                1e-12 * angle_deg);
  }
  const Eigen::Vector3d behind = -b;
  double r[2];
  EXPECT_FALSE(residual(behind.data(), r));
}

TEST(FactorsTest, ReprojectionGradient) {
  Eigen::Quaterniond q(Eigen::AngleAxisd(0.2, Eigen::Vector3d(0.3, 1.0, -0.2).normalized()));
  const double quaternion[4] = {q.w(), q.x(), q.y(), q.z()};
  const double center[3] = {-0.4, 0.3, 0.2};
  const double point[3] = {-1.0, 0.8, 15.0};
  const Eigen::Vector3d x = q * (Eigen::Vector3d(point) - Eigen::Vector3d(center));
  ForEveryResidual(x, [&](const auto& residual) {
    using Residual = std::decay_t<decltype(residual)>;
    std::unique_ptr<ceres::CostFunction> cost(ReprojectionError<Residual>::Create(residual));
    ceres::QuaternionManifold quaternion_manifold;
    ExpectGradientsMatch(*cost, {&quaternion_manifold, nullptr, nullptr},
                         {quaternion, center, point}, kGradientTolerance);
    ExpectGradientsMatch(*cost, {nullptr, nullptr, nullptr}, {quaternion, center, point},
                         kGradientTolerance);
  });
}

TEST(FactorsTest, ReferenceReprojectionGradient) {
  const double point[3] = {-1.0, 0.8, 15.0};
  ForEveryResidual(Eigen::Vector3d(point), [&](const auto& residual) {
    using Residual = std::decay_t<decltype(residual)>;
    std::unique_ptr<ceres::CostFunction> cost(
        ReferenceReprojectionError<Residual>::Create(residual));
    ExpectGradientsMatch(*cost, {nullptr}, {point}, kGradientTolerance);
  });
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
  ExpectGradientsMatch(*cost, {&quaternion_manifold}, {quaternion}, kGradientTolerance);
  ExpectGradientsMatch(*cost, {nullptr}, {quaternion}, kGradientTolerance);

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
  ExpectGradientsMatch(*exact_cost, {&quaternion_manifold}, {quaternion}, kGradientTolerance);
  // A flipped sign: exactly opposite directions are pi apart, not a match.
  const GravityPriorError flipped(g_ref, -predicted);
  ASSERT_TRUE(flipped(quaternion, residuals));
  EXPECT_NEAR(std::hypot(residuals[0], residuals[1]), M_PI, 1e-12);
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
