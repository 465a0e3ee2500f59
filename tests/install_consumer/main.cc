#include <iostream>
#include <random>
#include <vector>

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
  if (n1 != 1) return 1;
  const trigrav::ThreeViewPoseErrors e =
      trigrav::ComputeThreeViewPoseErrors(scene.ground_truth, with_gravity[0]);
  std::cout << "solutions " << n1 << " " << n2 << " rotation error " << e.MaxRotationDeg()
            << " deg\n";
  return e.MaxRotationDeg() < 1e-8 ? 0 : 1;
}
