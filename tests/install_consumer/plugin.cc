// A user's shared object built against the installed trigrav (static or shared): it links only if
// the installed libraries are position independent.
#include "plugin.h"

#include <trigrav/trigrav.h>

#include <random>

double RefinedRotationErrorDeg(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  trigrav::SyntheticSceneOptions options;
  options.num_points = 60;
  options.pixel_noise_px = 0.5;
  options.outlier_ratio = 0.2;
  const trigrav::SyntheticScene scene = trigrav::GenerateSyntheticScene(options, &rng);
  const trigrav::ThreeViewEstimate estimate = trigrav::InitializeAndRefine(
      trigrav::ToObservations(scene), trigrav::InitializeAndRefineOptions());
  if (!estimate.success) return 180.0;
  return trigrav::ComputeThreeViewPoseErrors(scene.ground_truth, estimate.refined).MaxRotationDeg();
}
