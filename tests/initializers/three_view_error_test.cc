#include "trigrav/initializers/three_view_error.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "trigrav/evaluation/synthetic_scene.h"

namespace trigrav {
namespace {

ThreeViewObservations ObservationsOf(const SyntheticScene& scene, double focal_px) {
  ThreeViewObservations observations;
  for (int k = 0; k < 3; ++k) {
    observations.cameras[k] = PinholeCamera{focal_px, focal_px, 320.0, 240.0};
    observations.gravity_in_cam[k] = scene.gravity_in_cam_measured[k];
    observations.pixels[k] = scene.pixels[k];
  }
  return observations;
}

TEST(ThreeViewReprojectionError, ZeroForExactTripletsAndNoiseSized) {
  std::mt19937_64 rng(1);
  SyntheticSceneOptions options;
  options.num_points = 50;
  const SyntheticScene exact = GenerateSyntheticScene(options, &rng);
  const ThreeViewReprojectionError error(ObservationsOf(exact, 500.0));
  const auto pose = ThreeViewReprojectionError::Prepare(exact.ground_truth);
  for (std::size_t n = 0; n < error.size(); ++n) EXPECT_LT(error(pose, n), 1e-8);

  options.pixel_noise_px = 1.0;
  options.num_points = 2000;
  const SyntheticScene noisy = GenerateSyntheticScene(options, &rng);
  const ThreeViewReprojectionError noisy_error(ObservationsOf(noisy, 500.0));
  const auto noisy_pose = ThreeViewReprojectionError::Prepare(noisy.ground_truth);
  std::vector<double> errors;
  for (std::size_t n = 0; n < noisy_error.size(); ++n) errors.push_back(noisy_error(noisy_pose, n));
  std::sort(errors.begin(), errors.end());
  // derivations.md section 7: median 1.18 px, p95 2.2 px with ground-truth poses at 1 px.
  EXPECT_NEAR(errors[errors.size() / 2], 1.18, 0.15);
  EXPECT_NEAR(errors[errors.size() * 95 / 100], 2.2, 0.3);
}

TEST(ThreeViewReprojectionError, InfiniteBehindACamera) {
  ThreeViewObservations observations;
  for (int k = 0; k < 3; ++k) {
    observations.cameras[k] = PinholeCamera{500.0, 500.0, 320.0, 240.0};
    observations.gravity_in_cam[k] = Eigen::Vector3d::UnitY();
    observations.pixels[k] = {Eigen::Vector2d(320.0, 240.0)};
  }
  // Camera 3 turned around: the point on the common optical axis is behind it.
  ThreeViewPose pose;
  pose.cam2_from_cam1.t = Eigen::Vector3d(-1.0, 0.0, 0.0);
  pose.cam3_from_cam1.R = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY()).toRotationMatrix();
  pose.cam3_from_cam1.t = Eigen::Vector3d(0.0, 0.0, 2.0);
  const ThreeViewReprojectionError error(observations);
  EXPECT_EQ(error(ThreeViewReprojectionError::Prepare(pose), 0),
            std::numeric_limits<double>::infinity());
}

// Straight driving: collinear centres make the three epipolar constraints coincide. A view-3
// outlier that slides 20 px along its epipolar line keeps every pairwise epipolar error at zero,
// but its triangulation disagrees with views 1 and 2 (derivations.md section 7).
TEST(ThreeViewReprojectionError, SeesAnOutlierSlidingAlongItsEpipolarLine) {
  const double f = 500.0;
  ThreeViewPose pose;  // cameras at z = 0, 1, 2 m, same orientation: forward motion
  pose.cam2_from_cam1.t = Eigen::Vector3d(0.0, 0.0, -1.0);
  pose.cam3_from_cam1.t = Eigen::Vector3d(0.0, 0.0, -2.0);
  const Eigen::Vector3d point(3.0, -1.5, 20.0);
  ThreeViewObservations observations;
  for (int k = 0; k < 3; ++k) {
    observations.cameras[k] = PinholeCamera{f, f, 320.0, 240.0};
    observations.gravity_in_cam[k] = Eigen::Vector3d::UnitY();
    const Eigen::Vector3d p = point - Eigen::Vector3d(0.0, 0.0, k);
    observations.pixels[k] = {
        Eigen::Vector2d(f * p.x() / p.z() + 320.0, f * p.y() / p.z() + 240.0)};
  }
  const auto prepared = ThreeViewReprojectionError::Prepare(pose);
  EXPECT_LT(ThreeViewReprojectionError(observations)(prepared, 0), 1e-9);
  // The epipole of every pair is the principal point; slide view 3's pixel away from it by 20 px.
  const Eigen::Vector2d radial =
      (observations.pixels[2][0] - Eigen::Vector2d(320.0, 240.0)).normalized();
  observations.pixels[2][0] += 20.0 * radial;
  EXPECT_GT(ThreeViewReprojectionError(observations)(prepared, 0), 3.0);
}

// The error as derivations.md section 7.2 writes it, in Eigen expressions: the midpoint of the
// rays d_k = R_k^T x_k / |x_k|, projected by Camera::Project, the largest residual norm.
double ReferenceError(const ThreeViewObservations& observations,
                      const ThreeViewPose& pose,
                      std::size_t n) {
  const std::array<Eigen::Matrix3d, 3> rotation = {Eigen::Matrix3d::Identity(),
                                                   pose.cam2_from_cam1.R, pose.cam3_from_cam1.R};
  const std::array<Eigen::Vector3d, 3> center = {
      Eigen::Vector3d::Zero(), pose.cam2_from_cam1.Center(), pose.cam3_from_cam1.Center()};
  std::array<Eigen::Vector3d, 3> directions;
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d ray;
    if (!observations.cameras[k].Unproject(observations.pixels[k][n], &ray)) {
      return std::numeric_limits<double>::infinity();
    }
    directions[k] = rotation[k].transpose() * ray.normalized();
  }
  Eigen::Vector3d point;
  if (!TriangulateMidpoint(center, directions, &point)) {
    return std::numeric_limits<double>::infinity();
  }
  double largest = 0.0;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d p = k == 0 ? point : Eigen::Vector3d(rotation[k] * (point - center[k]));
    Eigen::Vector2d pixel;
    if (!observations.cameras[k].Project(p.data(), pixel.data())) {
      return std::numeric_limits<double>::infinity();
    }
    const double norm = (pixel - observations.pixels[k][n]).norm();
    largest =
        std::max(largest, std::isfinite(norm) ? norm : std::numeric_limits<double>::infinity());
  }
  return largest;
}

// Errors() of pinhole cameras (the vectorised loop) and of distorted ones (triplet by triplet) are
// the reference error to the last bit, outliers, points behind a camera and parallel rays (a pose
// without baseline) included; above the cap they are only known to be above it.
TEST(ThreeViewReprojectionError, ErrorsAreTheReferenceToTheLastBit) {
  std::mt19937_64 rng(5);
  for (const bool distorted : {false, true}) {
    SyntheticSceneOptions options;
    options.num_points = 301;  // not a multiple of any block
    options.pixel_noise_px = 1.0;
    options.outlier_ratio = 0.3;
    if (distorted) options.opencv_distortion = {-0.2, 0.05, 0.001, -0.001};
    const SyntheticScene scene = GenerateSyntheticScene(options, &rng);
    const ThreeViewObservations observations = ToObservations(scene);
    const ThreeViewReprojectionError error(observations);
    ThreeViewPose behind = scene.ground_truth;  // camera 3 turned around
    behind.cam3_from_cam1.R = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY()).toRotationMatrix() *
                              behind.cam3_from_cam1.R;
    ThreeViewPose no_baseline = scene.ground_truth;
    no_baseline.cam2_from_cam1.t.setZero();
    no_baseline.cam3_from_cam1.t.setZero();
    ThreeViewPose perturbed = scene.ground_truth;
    perturbed.cam2_from_cam1.t += Eigen::Vector3d(0.05, -0.02, 0.01);
    int finite = 0, infinite = 0;
    for (const ThreeViewPose& pose : {scene.ground_truth, perturbed, behind, no_baseline}) {
      const auto prepared = ThreeViewReprojectionError::Prepare(pose);
      std::vector<double> exact(error.size()), capped(error.size() - 7);
      error.Errors(prepared, 0, error.size(), std::numeric_limits<double>::infinity(),
                   exact.data());
      error.Errors(prepared, 7, error.size(), 3.0, capped.data());
      for (std::size_t n = 0; n < error.size(); ++n) {
        const double reference = ReferenceError(observations, pose, n);
        EXPECT_EQ(exact[n], reference) << "triplet " << n << (distorted ? " distorted" : "");
        EXPECT_EQ(error(prepared, n), reference);
        if (n >= 7) {
          if (reference <= 3.0) {
            EXPECT_EQ(capped[n - 7], reference);
          } else {
            EXPECT_GT(capped[n - 7], 3.0);
          }
        }
        finite += std::isfinite(reference);
        infinite += !std::isfinite(reference);
      }
    }
    EXPECT_GT(finite, 300);
    EXPECT_GT(infinite, 300);  // behind camera 3, and no baseline
  }
}

TEST(ThreeViewReprojectionError, ErrorsRejectABadRange) {
  ThreeViewObservations observations;
  for (int k = 0; k < 3; ++k) {
    observations.cameras[k] = PinholeCamera{500.0, 500.0, 320.0, 240.0};
    observations.gravity_in_cam[k] = Eigen::Vector3d::UnitY();
    observations.pixels[k] = {Eigen::Vector2d(320.0, 240.0)};
  }
  const ThreeViewReprojectionError error(observations);
  const auto pose = ThreeViewReprojectionError::Prepare(ThreeViewPose{});
  double value;
  EXPECT_THROW(error.Errors(pose, 0, 2, 1.0, &value), std::invalid_argument);
  EXPECT_THROW(error.Errors(pose, 1, 0, 1.0, &value), std::invalid_argument);
  EXPECT_THROW(error.Errors(pose, 0, 1, 1.0, nullptr), std::invalid_argument);
}

TEST(TriangulateMidpoint, ParallelRaysFail) {
  Eigen::Vector3d point(7, 7, 7);
  const std::array<Eigen::Vector3d, 3> centers = {Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(),
                                                  Eigen::Vector3d(2, 0, 0)};
  const std::array<Eigen::Vector3d, 3> same = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ(),
                                               Eigen::Vector3d::UnitZ()};
  EXPECT_FALSE(TriangulateMidpoint(centers, same, &point));
  EXPECT_EQ(point, Eigen::Vector3d(7, 7, 7));
}

void ExpectThrowNaming(const ThreeViewObservations& observations, const char* fragment) {
  try {
    observations.Check();
    ADD_FAILURE() << "no throw for " << fragment;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(ThreeViewObservations, CheckNamesTheProblem) {
  ThreeViewObservations observations;
  for (int k = 0; k < 3; ++k) {
    observations.cameras[k] = PinholeCamera{500.0, 500.0, 320.0, 240.0};
    observations.gravity_in_cam[k] = Eigen::Vector3d::UnitY();
    observations.pixels[k] = {Eigen::Vector2d(1, 2)};
  }
  EXPECT_NO_THROW(observations.Check());
  ThreeViewObservations bad = observations;
  bad.cameras[1].params[0] = 0.0;
  ExpectThrowNaming(bad, "camera 2 needs positive");
  bad = observations;
  bad.cameras[2].params[1] = NAN;
  ExpectThrowNaming(bad, "camera 3");
  bad = observations;
  bad.pixels[2].push_back(Eigen::Vector2d(1, 1));
  ExpectThrowNaming(bad, "differ in size");
  bad = observations;
  bad.pixels[0][0].x() = INFINITY;
  ExpectThrowNaming(bad, "pixels[0][0]");
  bad = observations;
  bad.gravity_in_cam[1] = Eigen::Vector3d(NAN, 1.0, 0.0);
  ExpectThrowNaming(bad, "gravity_in_cam[1] is not finite");
  // A pixel beyond the fold of a strong barrel distortion (r^2 > 1 / (3 |k|)).
  bad = observations;
  bad.cameras[1] = Camera::FromColmap("SIMPLE_RADIAL", {500.0, 320.0, 240.0, -0.5});
  bad.pixels[1][0] = Eigen::Vector2d(320.0 + 500.0, 240.0);
  ExpectThrowNaming(bad, "pixels[1][0] cannot be unprojected by the SIMPLE_RADIAL camera");
}

// Nothing has a usable default: a default camera or gravity is rejected, naming what to set.
TEST(ThreeViewObservations, CheckRejectsUnsetCamerasAndGravity) {
  ThreeViewObservations observations;
  for (int k = 0; k < 3; ++k) {
    observations.cameras[k] = PinholeCamera{500.0, 500.0, 320.0, 240.0};
    observations.gravity_in_cam[k] = Eigen::Vector3d::UnitY();
    observations.pixels[k] = {Eigen::Vector2d(1, 2)};
  }
  ThreeViewObservations bad = observations;
  bad.cameras[2] = Camera();
  ExpectThrowNaming(bad, "camera 3 is not set");
  bad = observations;
  bad.cameras[0] = PinholeCamera();
  ExpectThrowNaming(bad, "camera 1 is not set");
  bad = observations;
  bad.gravity_in_cam[1] = Eigen::Vector3d::Zero();
  ExpectThrowNaming(bad, "gravity_in_cam[1] is not set");
  ExpectThrowNaming(ThreeViewObservations(), "gravity_in_cam[0] is not set");
  // Non-zero but beyond what a double's squared length holds: named, not called unset.
  bad = observations;
  bad.gravity_in_cam[1] *= 1e-300;
  ExpectThrowNaming(bad,
                    "gravity_in_cam[1] is too short to normalise (length 1e-300: its squared "
                    "length underflows to 0)");
  bad = observations;
  bad.gravity_in_cam[2] *= 1e300;
  ExpectThrowNaming(bad,
                    "gravity_in_cam[2] is too long to normalise (length 1e+300: its squared "
                    "length overflows)");
}

TEST(ThreeViewObservations, BearingsNeedNoCamerasAndAreChecked) {
  ThreeViewObservations observations;
  for (int k = 0; k < 3; ++k) {
    observations.gravity_in_cam[k] = Eigen::Vector3d::UnitY();
    observations.bearings[k] = {Eigen::Vector3d(0.1, 0.2, 1.0), Eigen::Vector3d(0.0, 0.0, -2.0)};
  }
  EXPECT_NO_THROW(observations.Check());
  EXPECT_TRUE(observations.HasBearings());
  EXPECT_EQ(observations.size(), 2u);
  EXPECT_EQ(observations.Ray(1, 1), Eigen::Vector3d(0.0, 0.0, -2.0));
  ThreeViewObservations bad = observations;
  bad.bearings[2][1].setZero();
  ExpectThrowNaming(bad, "bearings[2][1] is zero");
  bad = observations;
  bad.bearings[2][1] = Eigen::Vector3d(0.0, 0.0, 1e-300);
  ExpectThrowNaming(bad, "bearings[2][1] is too short to normalise (length 1e-300");
  bad = observations;
  bad.bearings[0].pop_back();
  ExpectThrowNaming(bad, "bearings of the three views differ in size");
  bad = observations;
  bad.pixels[1] = {Eigen::Vector2d(1, 2), Eigen::Vector2d(3, 4)};
  ExpectThrowNaming(bad, "both pixels and bearings");
}

// The error is in degrees for bearings: a point 0.5 deg off a bearing in view 3 gives 0.5.
TEST(ThreeViewReprojectionError, BearingErrorIsAnAngleInDegrees) {
  ThreeViewPose pose;  // cameras at x = 0, 1, 2 m, same orientation
  pose.cam2_from_cam1.t = Eigen::Vector3d(-1.0, 0.0, 0.0);
  pose.cam3_from_cam1.t = Eigen::Vector3d(-2.0, 0.0, 0.0);
  const Eigen::Vector3d point(0.5, -0.3, 10.0);
  ThreeViewObservations observations;
  for (int k = 0; k < 3; ++k) {
    observations.gravity_in_cam[k] = Eigen::Vector3d::UnitY();
    observations.bearings[k] = {point - Eigen::Vector3d(k, 0.0, 0.0)};
  }
  const auto prepared = ThreeViewReprojectionError::Prepare(pose);
  EXPECT_LT(ThreeViewReprojectionError(observations)(prepared, 0), 1e-12);
  const ThreeViewReprojectionError error(observations);
  const Eigen::Vector3d& bearing = observations.bearings[2][0];
  const Eigen::Vector3d axis = bearing.cross(Eigen::Vector3d::UnitY()).normalized();
  const Eigen::Vector3d off = Eigen::AngleAxisd(0.5 * M_PI / 180.0, axis) * bearing;
  EXPECT_NEAR(error.ObservationError(2, 0, off), std::tan(0.5 * M_PI / 180.0) * 180.0 / M_PI,
              1e-12);
}

}  // namespace
}  // namespace trigrav
