// Camera models: COLMAP names and parameter counts, projection against hand-computed values, and
// the round trip pixel -> ray -> pixel to 1e-10 px for every model over the whole image.
#include "trigrav/initializers/camera_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "typical_cameras.h"

namespace trigrav {
namespace {

TEST(CameraModel, NamesRoundTripAndParameterCounts) {
  const std::vector<int> counts = {3, 4, 4, 5, 8, 8};
  for (std::size_t i = 0; i < kCameraModels.size(); ++i) {
    CameraModel parsed = CameraModel::kPinhole;
    ASSERT_TRUE(ParseCameraModel(CameraModelName(kCameraModels[i]), &parsed));
    EXPECT_EQ(parsed, kCameraModels[i]);
    EXPECT_EQ(NumCameraParams(kCameraModels[i]), counts[i]);
  }
  CameraModel untouched = CameraModel::kRadial;
  EXPECT_FALSE(ParseCameraModel("FULL_OPENCV", &untouched));
  EXPECT_EQ(untouched, CameraModel::kRadial);
}

TEST(CameraModel, FromColmapRejectsBadInput) {
  EXPECT_THROW(Camera::FromColmap("FOV", {500.0, 320.0, 240.0, 0.1}), std::invalid_argument);
  EXPECT_THROW(Camera::FromColmap("PINHOLE", {500.0, 320.0, 240.0}), std::invalid_argument);
  EXPECT_THROW(Camera::FromColmap("SIMPLE_PINHOLE", {0.0, 320.0, 240.0}), std::invalid_argument);
  EXPECT_THROW(Camera::FromColmap("SIMPLE_PINHOLE", {500.0, std::nan(""), 240.0}),
               std::invalid_argument);
  Camera out_of_range;
  out_of_range.model = static_cast<CameraModel>(42);
  EXPECT_THROW(out_of_range.Check(), std::invalid_argument);
}

TEST(CameraModel, ProjectionMatchesTheFormulas) {
  const Eigen::Vector3d point(0.3, -0.2, 2.0);
  const double u = 0.15, v = -0.1, r2 = u * u + v * v;
  const Camera opencv = TypicalCamera(CameraModel::kOpenCV);
  const double radial = -0.3 * r2 + 0.1 * r2 * r2;
  const double u_d = u + u * radial + 2 * 1e-3 * u * v + -5e-4 * (r2 + 2 * u * u);
  const double v_d = v + v * radial + 2 * -5e-4 * u * v + 1e-3 * (r2 + 2 * v * v);
  EXPECT_NEAR(opencv.Project(point).x(), 1000.0 * u_d + 640.0, 1e-9);
  EXPECT_NEAR(opencv.Project(point).y(), 1010.0 * v_d + 480.0, 1e-9);
  const Camera fisheye = TypicalCamera(CameraModel::kOpenCVFisheye);
  const double r = std::sqrt(r2), theta = std::atan(r), t2 = theta * theta;
  const double theta_d =
      theta * (1 + 0.05 * t2 - 0.01 * t2 * t2 + 0.002 * t2 * t2 * t2 - 0.0005 * t2 * t2 * t2 * t2);
  EXPECT_NEAR(fisheye.Project(point).x(), 600.0 * u * theta_d / r + 640.0, 1e-9);
  const Camera pinhole = Camera::FromPinhole(PinholeCamera{500.0, 510.0, 320.0, 240.0});
  const PinholeCamera reference{500.0, 510.0, 320.0, 240.0};
  EXPECT_NEAR((pinhole.Project(point) - reference.Project(point)).norm(), 0.0, 1e-12);
  Eigen::Vector2d pixel(-1.0, -1.0);
  const Eigen::Vector3d behind(0.1, 0.1, -1.0);
  EXPECT_FALSE(opencv.Project(behind.data(), pixel.data()));
  EXPECT_EQ(pixel, Eigen::Vector2d(-1.0, -1.0));
}

TEST(CameraModel, UnprojectRoundTripsEveryPixelOfTheImage) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> x(0.0, 1280.0), y(0.0, 960.0);
  for (const CameraModel model : kCameraModels) {
    const Camera camera = TypicalCamera(model);
    double worst_px = 0.0;
    for (int n = 0; n < 2000; ++n) {
      // The corners first, then random pixels.
      const Eigen::Vector2d pixel = n < 4
                                        ? Eigen::Vector2d(n % 2 ? 1280.0 : 0.0, n / 2 ? 960.0 : 0.0)
                                        : Eigen::Vector2d(x(rng), y(rng));
      Eigen::Vector3d ray;
      ASSERT_TRUE(camera.Unproject(pixel, &ray))
          << CameraModelName(model) << " " << pixel.transpose();
      EXPECT_EQ(ray.z(), 1.0);
      worst_px = std::max(worst_px, (camera.Project(ray) - pixel).norm());
    }
    EXPECT_LT(worst_px, 1e-10) << CameraModelName(model);
  }
}

TEST(CameraModel, UnprojectRefusesPixelsNoRayExplains) {
  // Strong barrel distortion folds back at r^2 = 1 / (3 |k|): pixels beyond the fold's image.
  const Camera folded = Camera::FromColmap("SIMPLE_RADIAL", {100.0, 0.0, 0.0, -1.0});
  Eigen::Vector3d ray;
  EXPECT_FALSE(folded.Unproject(Eigen::Vector2d(100.0, 0.0), &ray));
  EXPECT_TRUE(folded.Unproject(Eigen::Vector2d(20.0, 0.0), &ray));
  EXPECT_FALSE(folded.Unproject(Eigen::Vector2d(std::nan(""), 0.0), &ray));
}

}  // namespace
}  // namespace trigrav
