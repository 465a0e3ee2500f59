#include "peer_estimators.h"

#include <random>

#include "peer_backends.h"
#include "trigrav/evaluation/synthetic_scene.h"

namespace trigrav::peers {

void RunPeersSingleThreaded() {
#ifdef TRIGRAV_PEERS_HAVE_OPENCV
  SetOpenCvThreads(1);
#endif
}

std::vector<NamedEstimator> PeerEstimators() {
  std::vector<NamedEstimator> estimators;
#ifdef TRIGRAV_PEERS_HAVE_OPENCV
  for (NamedEstimator& entry : OpenCvEstimators()) estimators.push_back(std::move(entry));
#endif
#ifdef TRIGRAV_PEERS_HAVE_OPENGV
  for (NamedEstimator& entry : OpenGvEstimators()) estimators.push_back(std::move(entry));
#endif
  return estimators;
}

std::vector<MinimalProblem> MakeMinimalProblems(int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  SyntheticSceneOptions options;
  options.num_points = 5;
  std::vector<MinimalProblem> problems;
  for (int i = 0; i < count; ++i) {
    const SyntheticScene scene = GenerateSyntheticScene(options, &rng);
    problems.push_back({scene.rays[0], scene.rays[1], scene.rays[2],
                        scene.gravity_in_cam_measured[0], scene.gravity_in_cam_measured[1],
                        scene.gravity_in_cam_measured[2], scene.ground_truth});
  }
  return problems;
}

std::vector<NamedMinimalSolver> PeerMinimalSolvers() {
#ifdef TRIGRAV_PEERS_HAVE_OPENGV
  return OpenGvMinimalSolvers();
#else
  return {};
#endif
}

}  // namespace trigrav::peers
