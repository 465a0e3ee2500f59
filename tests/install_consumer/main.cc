// An outside project against the installed package: both SolveTrifocal4pt overloads here, and
// InitializeAndRefine (trigrav::ba, which brings Ceres through find_dependency) through the
// consumer's own shared library (plugin.cc).
#include <trigrav/evaluation/pose_errors.h>
#include <trigrav/evaluation/synthetic_scene.h>
#include <trigrav/initializers/trifocal_4pt.h>

#include <iostream>
#include <random>
#include <vector>

#include "plugin.h"

int main() {
  std::mt19937_64 rng(42);
  const trigrav::SyntheticScene scene =
      trigrav::GenerateSyntheticScene(trigrav::SyntheticSceneOptions(), &rng);
  std::vector<trigrav::ThreeViewPose> with_gravity, aligned;
  const int n1 = trigrav::SolveTrifocal4pt(
      scene.rays[0], scene.rays[1], scene.rays[2], scene.gravity_in_cam_measured[0],
      scene.gravity_in_cam_measured[1], scene.gravity_in_cam_measured[2], &with_gravity);
  const int n2 = trigrav::SolveTrifocal4pt(scene.rays[0], scene.rays[1], scene.rays[2], &aligned);
  if (n1 != 1 || n2 != 1) return 1;
  const trigrav::ThreeViewPoseErrors e =
      trigrav::ComputeThreeViewPoseErrors(scene.ground_truth, with_gravity[0]);

  const double refined_rotation_deg = RefinedRotationErrorDeg(43);
  std::cout << "4pt rotation error " << e.MaxRotationDeg() << " deg; InitializeAndRefine in a "
            << "shared object: refined rotation error " << refined_rotation_deg << " deg\n";
  return e.MaxRotationDeg() < 1e-8 && refined_rotation_deg < 1.0 ? 0 : 1;
}
