#ifndef TRIGRAV_TESTS_SCENES_INPUT_MISTAKES_H_
#define TRIGRAV_TESTS_SCENES_INPUT_MISTAKES_H_

// Common mistakes in preparing three-view input, applied to a synthetic scene: what the mistakes
// matrix (tests/ba/mistakes_matrix_test.cc) and the verdict tool (examples/experiments/
// verdict_matrix, which has tests/scenes on its include path) feed to InitializeAndRefine. Each
// gives the observations a user making the mistake would pass; the scene's ground truth stays the
// right answer.

#include <Eigen/Core>
#include <array>
#include <stdexcept>
#include <utility>

#include "trigrav/evaluation/synthetic_scene.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav {

enum class InputMistake {
  kNone,
  kGravitySignCamera2,         // camera 2's gravity points up (-g)
  kWorldVerticalEveryCamera,   // the world's vertical e_y given as every camera's gravity
  kTransposedRotation,         // gravity mapped with W_k^T instead of W_k (world-to-camera W_k)
  kHalfResolutionPixels,       // pixels of a half-resolution image, full-resolution intrinsics
  kRowColumnPixels,            // pixels given as (row, column)
  kViews2And3PixelsSwapped,    // the pixels of views 2 and 3 swapped (gravity in order)
  kReadmeExampleIntrinsics,    // every camera given the README example's intrinsics (KITTI's)
  kFocalLength20PercentShort,  // every camera's focal length 0.8 of the true one
};

inline constexpr std::array<InputMistake, 9> kInputMistakes = {
    InputMistake::kNone,
    InputMistake::kGravitySignCamera2,
    InputMistake::kWorldVerticalEveryCamera,
    InputMistake::kTransposedRotation,
    InputMistake::kHalfResolutionPixels,
    InputMistake::kRowColumnPixels,
    InputMistake::kViews2And3PixelsSwapped,
    InputMistake::kReadmeExampleIntrinsics,
    InputMistake::kFocalLength20PercentShort};

inline const char* InputMistakeName(InputMistake mistake) {
  switch (mistake) {
    case InputMistake::kNone:
      return "none";
    case InputMistake::kGravitySignCamera2:
      return "gravity-sign-camera-2";
    case InputMistake::kWorldVerticalEveryCamera:
      return "world-vertical-every-camera";
    case InputMistake::kTransposedRotation:
      return "transposed-rotation";
    case InputMistake::kHalfResolutionPixels:
      return "half-resolution-pixels";
    case InputMistake::kRowColumnPixels:
      return "row-column-pixels";
    case InputMistake::kViews2And3PixelsSwapped:
      return "views-2-3-pixels-swapped";
    case InputMistake::kReadmeExampleIntrinsics:
      return "readme-example-intrinsics";
    case InputMistake::kFocalLength20PercentShort:
      return "focal-length-20-percent-short";
  }
  throw std::invalid_argument("trigrav: unknown InputMistake value");
}

// The observations of `scene` (ToObservations) with the mistake made. The gravity mistakes start
// from the true gravity W_k e_y (the scene's IMU noise is dropped for them).
inline ThreeViewObservations WithMistake(const SyntheticScene& scene, InputMistake mistake) {
  ThreeViewObservations observations = ToObservations(scene);
  const Eigen::Vector3d down = Eigen::Vector3d::UnitY();
  switch (mistake) {
    case InputMistake::kNone:
      break;
    case InputMistake::kGravitySignCamera2:
      observations.gravity_in_cam[1] = -(scene.cam_from_world[1] * down);
      break;
    case InputMistake::kWorldVerticalEveryCamera:
      for (Eigen::Vector3d& gravity : observations.gravity_in_cam) gravity = down;
      break;
    case InputMistake::kTransposedRotation:
      for (int k = 0; k < 3; ++k) {
        observations.gravity_in_cam[k] = scene.cam_from_world[k].transpose() * down;
      }
      break;
    case InputMistake::kHalfResolutionPixels:
      for (auto& pixels : observations.pixels) {
        for (Eigen::Vector2d& pixel : pixels) pixel *= 0.5;
      }
      break;
    case InputMistake::kRowColumnPixels:
      for (auto& pixels : observations.pixels) {
        for (Eigen::Vector2d& pixel : pixels) pixel = Eigen::Vector2d(pixel.y(), pixel.x());
      }
      break;
    case InputMistake::kViews2And3PixelsSwapped:
      std::swap(observations.pixels[1], observations.pixels[2]);
      break;
    case InputMistake::kReadmeExampleIntrinsics:
      for (Camera& camera : observations.cameras) {
        camera = PinholeCamera{718.856, 718.856, 607.193, 185.216};
      }
      break;
    case InputMistake::kFocalLength20PercentShort:
      for (Camera& camera : observations.cameras) {
        const internal::CameraParamLayout layout = internal::ParamLayout(camera.model);
        camera.params[layout.fx] *= 0.8;
        if (layout.fy != layout.fx) camera.params[layout.fy] *= 0.8;
      }
      break;
  }
  return observations;
}

}  // namespace trigrav

#endif  // TRIGRAV_TESTS_SCENES_INPUT_MISTAKES_H_
