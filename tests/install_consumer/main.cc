// An outside project against the installed package: both SolveTrifocal4pt overloads and
// InitializeAndRefine (trigrav::ba, which brings Ceres through find_dependency).
#include <iostream>
#include <random>
#include <vector>

#include <trigrav/ba/initialize_and_refine.h>
#include <trigrav/initializers/pose_metrics.h>
#include <trigrav/initializers/synthetic_scene.h>
#include <trigrav/initializers/trifocal_4pt.h>

int main() {
  std::mt19937_64 rng(42);
  const trigrav::SyntheticScene scene =
      trigrav::GenerateSyntheticScene(trigrav::SyntheticSceneOptions(), &rng);
  std::vector<trigrav::ThreeViewPose> with_gravity, aligned;
  const int n1 = trigrav::SolveTrifocal4pt(scene.rays[0], scene.rays[1], scene.rays[2],
                                           scene.gravity_in_cam_measured[0],
                                           scene.gravity_in_cam_measured[1],
                                           scene.gravity_in_cam_measured[2], &with_gravity);
  const int n2 = trigrav::SolveTrifocal4pt(scene.rays[0], scene.rays[1], scene.rays[2], &aligned);
  if (n1 != 1 || n2 != 1) return 1;
  const trigrav::ThreeViewPoseErrors e =
      trigrav::ComputeThreeViewPoseErrors(scene.ground_truth, with_gravity[0]);

  trigrav::SyntheticSceneOptions options;
  options.num_points = 60;
  options.pixel_noise_px = 0.5;
  options.outlier_ratio = 0.2;
  const trigrav::SyntheticScene noisy = trigrav::GenerateSyntheticScene(options, &rng);
  const trigrav::ThreeViewEstimate estimate = trigrav::InitializeAndRefine(
      trigrav::ToObservations(noisy), trigrav::InitializeAndRefineOptions());
  const trigrav::ThreeViewPoseErrors refined =
      trigrav::ComputeThreeViewPoseErrors(noisy.ground_truth, estimate.refined);
  std::cout << "4pt rotation error " << e.MaxRotationDeg() << " deg; InitializeAndRefine "
            << (estimate.success ? "ok" : estimate.message) << ", refined rotation error "
            << refined.MaxRotationDeg() << " deg\n";
  return e.MaxRotationDeg() < 1e-8 && estimate.success && refined.MaxRotationDeg() < 1.0 ? 0 : 1;
}
