// EliminatedPointReprojectionError: its Jacobian against numeric derivatives where the triplet is
// consistent (there variable projection's Jacobian is the exact derivative), its cost against the
// per-observation factors at their joint minimum over the point, and its failures.
#include "trigrav/factors/eliminated_point_reprojection_error.h"

#include <ceres/loss_function.h>
#include <ceres/manifold.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#include "expect_gradients_match.h"
#include "trigrav/factors/angle_manifold.h"
#include "trigrav/factors/reprojection_factors.h"
#include "trigrav/initializers/gravity.h"
#include "typical_cameras.h"

namespace trigrav {
namespace {

// Three cameras around a point 12 units ahead; camera 1 is the reference.
struct Triplet {
  std::array<Eigen::Matrix3d, 3> alignments = {GravityAlignmentFromPitchRoll(-0.07, 0.12),
                                               GravityAlignmentFromPitchRoll(0.1, -0.05),
                                               GravityAlignmentFromPitchRoll(0.03, 0.08)};
  double yaw[2] = {0.3, -0.2};
  double center[2][3] = {{0.8, -0.1, 0.2}, {-0.5, 0.3, 1.1}};
  Eigen::Vector3d point{1.0, 0.5, 12.0};

  Eigen::Matrix3d Rotation(int k) const {
    if (k == 0) return Eigen::Matrix3d::Identity();
    return alignments[k].transpose() * RotationAboutY(yaw[k - 1]) * alignments[0];
  }
  Eigen::Vector3d Center(int k) const {
    return k == 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(center[k - 1]);
  }
  Eigen::Vector3d PointInCam(int k) const { return Rotation(k) * (point - Center(k)); }
  // Quaternion [w, x, y, z] of camera k (2 or 3).
  std::array<double, 4> Quaternion(int k) const {
    const Eigen::Quaterniond q(Rotation(k));
    return {q.w(), q.x(), q.y(), q.z()};
  }
};

// Runs test(observations) with the pixel observations of every camera model and with bearings,
// each seeing the triplet's point moved by `offset` in every camera frame (zero: consistent).
template <typename Test>
void ForEveryObservationKind(const Triplet& triplet,
                             const Eigen::Vector3d& offset,
                             const Test& test) {
  for (const CameraModel model : kCameraModels) {
    SCOPED_TRACE(CameraModelName(model));
    const Camera camera = TypicalCamera(model);
    std::array<PixelResidual, 3> pixels;
    for (int k = 0; k < 3; ++k) {
      pixels[k] = {camera, camera.Project(Eigen::Vector3d(triplet.PointInCam(k) + offset * k))};
    }
    test(pixels);
  }
  SCOPED_TRACE("bearings");
  std::array<BearingResidual, 3> bearings;
  for (int k = 0; k < 3; ++k) bearings[k] = BearingResidual(triplet.PointInCam(k) + offset * k);
  test(bearings);
}

// Evaluates with Jacobians, which stores the point found in the factor's state.
bool EvaluateWithJacobians(const ceres::CostFunction& cost,
                           const double* const* parameters,
                           double* cost_value = nullptr) {
  Eigen::Matrix<double, 6, 1> residuals;
  std::vector<std::vector<double>> blocks;
  std::vector<double*> jacobians;
  for (const int size : cost.parameter_block_sizes()) blocks.emplace_back(6 * size);
  for (std::vector<double>& block : blocks) jacobians.push_back(block.data());
  const bool ok = cost.Evaluate(parameters, residuals.data(), jacobians.data());
  if (cost_value != nullptr) *cost_value = 0.5 * residuals.squaredNorm();
  return ok;
}

// The numeric derivatives re-find the point at every probe, to the factor's tolerance (a decrement
// of 1e-12 of the cost): the residuals then carry relative errors near 1e-6 of their size, and the
// derivatives agree to about 5e-5. A wrong term (the point held fixed, a sign, a quaternion
// derivative) is off by order 1.
constexpr double kGradientTolerance = 2e-4;

TEST(EliminatedPointReprojectionErrorTest, YawOnlyGradientOfAConsistentTriplet) {
  const Triplet triplet;
  const ceres::HuberLoss loss(2.0);
  ForEveryObservationKind(triplet, Eigen::Vector3d::Zero(), [&](const auto& observations) {
    using Residual = typename std::decay_t<decltype(observations)>::value_type;
    Eigen::Vector3d point = triplet.point + Eigen::Vector3d(0.2, -0.3, 1.5);  // the start
    std::unique_ptr<ceres::CostFunction> cost(
        EliminatedPointReprojectionError<Residual>::CreateYawOnly(observations, triplet.alignments,
                                                                  &loss, point.data()));
    const YawManifold yaw_manifold;
    const double* parameters[4] = {&triplet.yaw[0], triplet.center[0], &triplet.yaw[1],
                                   triplet.center[1]};
    ASSERT_TRUE(EvaluateWithJacobians(*cost, parameters));
    EXPECT_LT((point - triplet.point).norm(), 1e-9);  // found from a start 1.5 units off
    ExpectGradientsMatch(*cost, {&yaw_manifold, nullptr, &yaw_manifold, nullptr},
                         {parameters[0], parameters[1], parameters[2], parameters[3]},
                         kGradientTolerance);
  });
}

TEST(EliminatedPointReprojectionErrorTest, QuaternionGradientOfAConsistentTriplet) {
  const Triplet triplet;
  const std::array<double, 4> q2 = triplet.Quaternion(1), q3 = triplet.Quaternion(2);
  ForEveryObservationKind(triplet, Eigen::Vector3d::Zero(), [&](const auto& observations) {
    using Residual = typename std::decay_t<decltype(observations)>::value_type;
    Eigen::Vector3d point = triplet.point + Eigen::Vector3d(-0.4, 0.1, -2.0);
    std::unique_ptr<ceres::CostFunction> cost(
        EliminatedPointReprojectionError<Residual>::CreateWithQuaternions(observations, nullptr,
                                                                          point.data()));
    const ceres::QuaternionManifold quaternion;
    const double* parameters[4] = {q2.data(), triplet.center[0], q3.data(), triplet.center[1]};
    ASSERT_TRUE(EvaluateWithJacobians(*cost, parameters));
    EXPECT_LT((point - triplet.point).norm(), 1e-9);
    ExpectGradientsMatch(*cost, {&quaternion, nullptr, &quaternion, nullptr},
                         {parameters[0], parameters[1], parameters[2], parameters[3]},
                         kGradientTolerance);
  });
}

// With noisy observations (one of them beyond the Huber scale): the six residuals' cost is the
// per-observation factors' robust cost at the point the factor found, and no nearby point has a
// lower one.
TEST(EliminatedPointReprojectionErrorTest, CostIsTheMinimumOverThePoint) {
  const Triplet triplet;
  ForEveryObservationKind(
      triplet, Eigen::Vector3d(0.02, -0.015, 0.0), [&](const auto& observations) {
        using Residual = typename std::decay_t<decltype(observations)>::value_type;
        // The offsets are about a pixel, or 0.1 deg.
        const double huber_scale = std::is_same_v<Residual, BearingResidual> ? 0.05 : 0.5;
        const ceres::HuberLoss loss(huber_scale);
        Eigen::Vector3d point = triplet.point;
        std::unique_ptr<ceres::CostFunction> cost(
            EliminatedPointReprojectionError<Residual>::CreateYawOnly(
                observations, triplet.alignments, &loss, point.data()));
        const double* parameters[4] = {&triplet.yaw[0], triplet.center[0], &triplet.yaw[1],
                                       triplet.center[1]};
        Eigen::Matrix<double, 6, 1> residuals;
        ASSERT_TRUE(cost->Evaluate(parameters, residuals.data(), nullptr));
        const double eliminated_cost = 0.5 * residuals.squaredNorm();
        EXPECT_EQ(point, triplet.point);  // a cost-only evaluation keeps the stored point
        ASSERT_TRUE(EvaluateWithJacobians(*cost, parameters));

        // The joint cost of the per-observation factors at a point x.
        auto joint_cost = [&](const Eigen::Vector3d& x) {
          double sum = 0.0, largest = 0.0;
          for (int k = 0; k < 3; ++k) {
            Eigen::Vector2d r;
            const Eigen::Vector3d x_cam = triplet.Rotation(k) * (x - triplet.Center(k));
            EXPECT_TRUE(observations[k](x_cam.data(), r.data()));
            double rho[3];
            loss.Evaluate(r.squaredNorm(), rho);
            sum += 0.5 * rho[0];
            largest = std::max(largest, r.norm());
          }
          return std::make_pair(sum, largest);
        };
        const auto [at_point, largest_residual] = joint_cost(point);
        EXPECT_GT(largest_residual, huber_scale);  // the loss is not quadratic here
        // The evaluation with Jacobians at the same cameras went on from the cost-only one's point
        // (JacobiansAtTheLastTrialGoOnFromItsPoint).
        EXPECT_NEAR(eliminated_cost, at_point, 1e-9 * at_point);
        for (int axis = 0; axis < 3; ++axis) {
          for (const double step : {-1e-4, 1e-4}) {
            EXPECT_GE(joint_cost(point + step * Eigen::Vector3d::Unit(axis)).first,
                      at_point * (1.0 - 1e-12));
          }
        }
      });
}

// Ceres evaluates a trial step's cost, then, once it accepts the step, the Jacobians at the same
// parameters: those start from the trial's point (section 15.1), and only at the same parameters.
// With pixel offsets of about 1 px beyond a 0.5 px Huber scale, the reweighted steps converge
// linearly, and one evaluation's 20 steps stop short of the point's minimum (by about 2e-10 of
// the cost), so where the second evaluation starts shows in its cost.
TEST(EliminatedPointReprojectionErrorTest, JacobiansAtTheLastTrialGoOnFromItsPoint) {
  const Triplet triplet;
  const Camera camera = TypicalCamera(CameraModel::kPinhole);
  std::array<PixelResidual, 3> pixels;
  const Eigen::Vector3d offset(0.02, -0.015, 0.0);  // as CostIsTheMinimumOverThePoint's
  for (int k = 0; k < 3; ++k) {
    pixels[k] = {camera, camera.Project(Eigen::Vector3d(triplet.PointInCam(k) + offset * k))};
  }
  const ceres::HuberLoss loss(0.5);
  const double other_yaw = triplet.yaw[0] + 0.01;
  const double* parameters[4] = {&triplet.yaw[0], triplet.center[0], &triplet.yaw[1],
                                 triplet.center[1]};
  const double* other[4] = {&other_yaw, triplet.center[0], &triplet.yaw[1], triplet.center[1]};
  auto make = [&](Eigen::Vector3d* point) {
    *point = triplet.point;
    return std::unique_ptr<ceres::CostFunction>(
        EliminatedPointReprojectionError<PixelResidual>::CreateYawOnly(pixels, triplet.alignments,
                                                                       &loss, point->data()));
  };
  auto cost_only = [](const ceres::CostFunction& cost, const double* const* at) {
    Eigen::Matrix<double, 6, 1> residuals;
    EXPECT_TRUE(cost.Evaluate(at, residuals.data(), nullptr));
    return 0.5 * residuals.squaredNorm();
  };
  Eigen::Vector3d direct_point, trial_point, other_point;
  double direct, after_trial, after_other;
  ASSERT_TRUE(EvaluateWithJacobians(*make(&direct_point), parameters, &direct));

  const auto with_trial = make(&trial_point);
  EXPECT_EQ(cost_only(*with_trial, parameters), direct);  // the same minimisation
  ASSERT_TRUE(EvaluateWithJacobians(*with_trial, parameters, &after_trial));
  EXPECT_LT(after_trial, direct);
  EXPECT_NE(trial_point, direct_point);

  const auto with_other = make(&other_point);
  cost_only(*with_other, other);
  ASSERT_TRUE(EvaluateWithJacobians(*with_other, parameters, &after_other));
  EXPECT_EQ(after_other, direct);
  EXPECT_EQ(other_point, direct_point);
}

TEST(EliminatedPointReprojectionErrorTest, FailsWhenAnObservationCannotSeeThePoint) {
  const Triplet triplet;
  std::array<BearingResidual, 3> bearings;
  for (int k = 0; k < 3; ++k) bearings[k] = BearingResidual(triplet.PointInCam(k));
  bearings[2] = BearingResidual(-triplet.PointInCam(2));  // behind camera 3
  Eigen::Vector3d point = triplet.point;
  std::unique_ptr<ceres::CostFunction> cost(
      EliminatedPointReprojectionError<BearingResidual>::CreateYawOnly(bearings, triplet.alignments,
                                                                       nullptr, point.data()));
  const double* parameters[4] = {&triplet.yaw[0], triplet.center[0], &triplet.yaw[1],
                                 triplet.center[1]};
  double residuals[6];
  EXPECT_FALSE(cost->Evaluate(parameters, residuals, nullptr));
}

}  // namespace
}  // namespace trigrav
