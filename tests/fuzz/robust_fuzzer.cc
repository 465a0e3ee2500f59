// Fuzz harness over the robust estimator EstimateThreeViewPoseRobust (robust_three_view.h), every
// InitialSolver, with bounded RANSAC iterations (at most 64) and at most 40 triplets so one input
// runs in milliseconds.
//
// Input: the solver (one value in 8 is not a valid enumerator), the RANSAC options (mostly sane,
// some decoded freely), then either a synthetic scene with outliers and edits (fuzz_scene.h) or raw
// intrinsics, gravity and pixels, then edits of the intrinsics, and last max_tilt_correction_deg
// (0 past the end of the input, so shorter inputs keep their meaning). Checked:
//   - the only exception is std::invalid_argument, and only when the observations or the options
//     fail their own Check(), the tilt bound is outside [0, 90) or the solver is not an enumerator;
//   - success: a finite pose, one inlier flag per triplet, num_inliers = the flags set (at least a
//     minimal sample), iterations <= max_iterations; failure: a message.
// Built as a libFuzzer target with Clang, and into a replay driver (replay_main.cc) for ctest.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <initializer_list>
#include <stdexcept>

#include "fuzz_check.h"
#include "fuzz_input.h"
#include "fuzz_scene.h"
#include "trigrav/initializers/robust_three_view.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav {
namespace fuzz {
namespace {

constexpr int kNumSolvers = static_cast<int>(kInitialSolvers.size());
constexpr int kMaxIterations = 64;
constexpr int kMaxTriplets = 40;

// One of the listed values, or (the last choice) any decoded double.
double Choose(FuzzInput* input, std::initializer_list<double> values) {
  const int which = input->Index(static_cast<int>(values.size()) + 1);
  return which < static_cast<int>(values.size()) ? values.begin()[which] : input->Double();
}

RobustThreeViewOptions DecodeOptions(FuzzInput* input) {
  RobustThreeViewOptions options;
  options.solver = static_cast<InitialSolver>(input->Index(kNumSolvers + 2));
  RansacOptions& ransac = options.ransac;
  ransac.max_error = Choose(input, {0.5, 2.0, 20.0, 1e6});
  ransac.confidence = Choose(input, {0.99, 0.9999});
  ransac.min_iterations = input->Index(24) - 2;
  ransac.max_iterations = input->Index(kMaxIterations + 2) - 1;
  ransac.seed = input->Uint32();
  ransac.local_optimization = input->Byte() % 4 != 0;
  ransac.local_optimization_rounds = input->Index(6) - 1;
  ransac.local_optimization_threshold_multiplier = Choose(input, {1.0, 3.0});
  ransac.min_inlier_ratio = Choose(input, {0.25, 0.0, 0.9});
  options.max_bearing_error_deg = Choose(input, {0.1, 1.0, 1e-6});
  options.check_gravity_after_success = input->Byte() % 4 != 0;
  return options;
}

// A synthetic scene as pixels, as bearings, or as pixels read through a camera of any model with
// fuzzed distortion; or cameras, gravity and pixels from raw doubles. Then edits of every kind.
ThreeViewObservations DecodeObservations(FuzzInput* input) {
  ThreeViewObservations observations;
  const int mode = input->Index(4);
  if (mode != 1) {
    if (auto scene = DecodeSyntheticScene(input, 1, kMaxTriplets)) {
      observations = mode == 2 ? ToBearingObservations(*scene) : ToObservations(*scene);
    }
  } else {
    for (Camera& camera : observations.cameras) {
      camera = PinholeCamera{input->Double(), input->Double(), input->Double(), input->Double()};
    }
    for (Eigen::Vector3d& gravity : observations.gravity_in_cam) gravity = input->Vector3();
    const int size = input->Index(kMaxTriplets + 1);
    for (auto& view : observations.pixels) {
      view.resize(size);
      for (Eigen::Vector2d& pixel : view) pixel = {input->Double(), input->Double()};
    }
  }
  if (mode == 3) {
    for (Camera& camera : observations.cameras) {
      const CameraModel model = kCameraModels[input->Index(static_cast<int>(kCameraModels.size()))];
      const internal::CameraParamLayout layout = internal::ParamLayout(model);
      std::array<double, kMaxCameraParams> params{};
      params[layout.fx] = camera.FocalX();
      params[layout.fy] = camera.FocalY();
      params[layout.cx] = camera.params[2];
      params[layout.cy] = camera.params[3];
      for (int i = layout.distortion; i < NumCameraParams(model); ++i) {
        params[i] = Choose(input, {0.0, -0.3, 0.1, 1e-3, input->Double()});
      }
      camera = Camera(model, params);
    }
  }
  if (observations.HasBearings()) {
    ApplyEdits<3>(input, &observations.bearings, &observations.gravity_in_cam);
  } else {
    ApplyEdits<2>(input, &observations.pixels, &observations.gravity_in_cam);
  }
  for (int edit = input->Index(3); edit > 0; --edit) {
    observations.cameras[input->Index(3)].params[input->Index(kMaxCameraParams)] = input->Double();
  }
  // Edits may add triplets; the harness stays small.
  for (auto& view : observations.pixels) {
    view.resize(std::min<std::size_t>(view.size(), kMaxTriplets));
  }
  for (auto& view : observations.bearings) {
    view.resize(std::min<std::size_t>(view.size(), kMaxTriplets));
  }
  return observations;
}

bool IsValid(const ThreeViewObservations& observations, const RobustThreeViewOptions& options) {
  if (static_cast<int>(options.solver) >= kNumSolvers) return false;
  try {
    observations.Check();
    options.Check();
  } catch (const std::invalid_argument&) {
    return false;
  }
  return true;
}

}  // namespace
}  // namespace fuzz
}  // namespace trigrav

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace trigrav;  // NOLINT: the harness entry point must stay outside namespaces
  fuzz::FuzzInput input(data, size);
  RobustThreeViewOptions options = fuzz::DecodeOptions(&input);
  const ThreeViewObservations observations = fuzz::DecodeObservations(&input);
  options.max_tilt_correction_deg = fuzz::Choose(&input, {0.0, 0.5, 5.0, 45.0});
  const bool valid = fuzz::IsValid(observations, options);
  RobustThreeViewEstimate estimate;
  try {
    estimate = EstimateThreeViewPoseRobust(observations, options);
  } catch (const std::invalid_argument& error) {
    if (valid) std::fprintf(stderr, "thrown: %s\n", error.what());
    TRIGRAV_FUZZ_CHECK(!valid,
                       "std::invalid_argument for observations and options that pass Check()");
    return 0;
  }
  TRIGRAV_FUZZ_CHECK(valid, "invalid observations or options were accepted");
  if (!estimate.success) {
    TRIGRAV_FUZZ_CHECK(!estimate.message.empty(), "a failure without a message");
    return 0;
  }
  TRIGRAV_FUZZ_CHECK(estimate.pose.IsFinite(), "non-finite pose");
  TRIGRAV_FUZZ_CHECK(estimate.inliers.size() == observations.size(), "one inlier flag per triplet");
  TRIGRAV_FUZZ_CHECK(
      estimate.ransac.num_inliers == std::count_if(estimate.inliers.begin(), estimate.inliers.end(),
                                                   [](char flag) { return flag != 0; }),
      "num_inliers differs from the flags set");
  TRIGRAV_FUZZ_CHECK(estimate.ransac.num_inliers >= MinimalSampleSize(options.solver),
                     "fewer inliers than a minimal sample");
  TRIGRAV_FUZZ_CHECK(estimate.ransac.iterations <= options.ransac.max_iterations,
                     "too many iterations");
  return 0;
}
