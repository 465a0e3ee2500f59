// The C++ side of tests/python/test_bit_identical.py: runs the library's calls on observations read
// from a file and prints every result number as a hexadecimal float (%a), so that the test can
// compare the Python module's results with ==.
//   trigrav_python_cpp_reference <input>
// Input (whitespace-separated; doubles in any strtod format, the test writes float.hex()):
//   camera <COLMAP model> <count> <params...>
//   gravity <9 numbers: gravity_in_cam of cameras 1, 2, 3>
//   seed <RANSAC seed>
//   triplets <N>, then N lines of u1 v1 u2 v2 u3 v3
// Output lines "<name> <values...>" (see Print* below); the calls and their options are those the
// test makes from Python.

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "trigrav/trigrav.h"

namespace {

double ReadDouble(std::ifstream& in) {
  std::string token;
  in >> token;
  return std::strtod(token.c_str(), nullptr);
}

void Expect(std::ifstream& in, const char* keyword) {
  std::string token;
  in >> token;
  if (token != keyword) {
    std::fprintf(stderr, "expected '%s', read '%s'\n", keyword, token.c_str());
    std::exit(2);
  }
}

trigrav::ThreeViewObservations ReadObservations(const char* path, std::uint64_t* seed) {
  std::ifstream in(path);
  trigrav::ThreeViewObservations observations;
  Expect(in, "camera");
  std::string model;
  int count = 0;
  in >> model >> count;
  std::vector<double> params(count);
  for (double& p : params) p = ReadDouble(in);
  observations.cameras.fill(trigrav::Camera::FromColmap(model, params));
  Expect(in, "gravity");
  for (Eigen::Vector3d& g : observations.gravity_in_cam) {
    for (int i = 0; i < 3; ++i) g[i] = ReadDouble(in);
  }
  Expect(in, "seed");
  in >> *seed;
  Expect(in, "triplets");
  int n = 0;
  in >> n;
  for (int t = 0; t < n; ++t) {
    for (int k = 0; k < 3; ++k) {
      const double u = ReadDouble(in);
      observations.pixels[k].emplace_back(u, ReadDouble(in));
    }
  }
  if (!in) {
    std::fprintf(stderr, "cannot read %s\n", path);
    std::exit(2);
  }
  return observations;
}

void PrintValues(const char* name, const double* values, int count) {
  std::printf("%s", name);
  for (int i = 0; i < count; ++i) std::printf(" %a", values[i]);
  std::printf("\n");
}

// R row by row, then t, for cameras 2 and 3: 24 numbers.
void PrintPose(const char* name, const trigrav::ThreeViewPose& pose) {
  std::printf("%s", name);
  for (const trigrav::CameraPose* camera : {&pose.cam2_from_cam1, &pose.cam3_from_cam1}) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) std::printf(" %a", camera->R(r, c));
    }
    for (int r = 0; r < 3; ++r) std::printf(" %a", camera->t(r));
  }
  std::printf("\n");
}

void PrintMask(const char* name, const std::vector<char>& mask) {
  std::printf("%s ", name);
  for (const char m : mask) std::printf("%d", m ? 1 : 0);
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s <input>\n", argv[0]);
    return 2;
  }
  std::uint64_t seed = 0;
  const trigrav::ThreeViewObservations observations = ReadObservations(argv[1], &seed);

  // initialize_and_refine: gravity-prior model with covariance, 1.5 px.
  trigrav::InitializeAndRefineOptions options;
  options.robust.ransac.max_error = 1.5;
  options.robust.ransac.seed = seed;
  options.bundle_adjustment.rotation_model =
      trigrav::ThreeViewBundleAdjustmentOptions::RotationModel::kGravityPrior;
  options.bundle_adjustment.compute_covariance = true;
  const trigrav::ThreeViewEstimate estimate = trigrav::InitializeAndRefine(observations, options);
  std::printf("ir_success %d\nir_num_inliers %d\n", estimate.success ? 1 : 0, estimate.num_inliers);
  PrintPose("ir_initial", estimate.robust.pose);
  PrintPose("ir_refined", estimate.refined);
  PrintMask("ir_inliers", estimate.inliers);
  PrintValues("ir_covariance", estimate.refinement.covariance.data(),
              static_cast<int>(estimate.refinement.covariance.size()));  // column-major

  // estimate_three_view_pose_robust with the default options and the seed, then the refine-only
  // call with the default bundle adjustment options on its inliers.
  trigrav::RobustThreeViewOptions robust_options;
  robust_options.ransac.seed = seed;
  const trigrav::RobustThreeViewEstimate robust =
      trigrav::EstimateThreeViewPoseRobust(observations, robust_options);
  std::printf("robust_success %d\n", robust.success ? 1 : 0);
  PrintPose("robust_pose", robust.pose);
  PrintMask("robust_inliers", robust.inliers);
  const trigrav::ThreeViewRefinement refinement = trigrav::RefineThreeViewPose(
      observations, robust.pose, robust.inliers, trigrav::ThreeViewBundleAdjustmentOptions());
  PrintPose("refine_pose", refinement.pose);
  PrintValues("refine_rms", &refinement.residual_rms, 1);

  // solve_trifocal_3pt on the rays of the first three triplets, with gravity.
  std::vector<Eigen::Vector3d> rays[3];
  for (int k = 0; k < 3; ++k) {
    for (std::size_t n = 0; n < 3; ++n) rays[k].push_back(observations.Ray(k, n));
  }
  std::vector<trigrav::ThreeViewPose> solutions;
  trigrav::SolveTrifocal3pt(rays[0], rays[1], rays[2], observations.gravity_in_cam[0],
                            observations.gravity_in_cam[1], observations.gravity_in_cam[2],
                            &solutions);
  std::printf("solver_3pt_count %zu\n", solutions.size());
  for (const trigrav::ThreeViewPose& pose : solutions) PrintPose("solver_3pt", pose);
  PrintValues("rays_3pt", rays[0][0].data(), 3);
  return 0;
}
