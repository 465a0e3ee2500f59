#include "peer_estimators.h"

#include "peer_backends.h"

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

std::vector<NamedMinimalSolver> PeerMinimalSolvers() {
#ifdef TRIGRAV_PEERS_HAVE_OPENGV
  return OpenGvMinimalSolvers();
#else
  return {};
#endif
}

}  // namespace trigrav::peers
