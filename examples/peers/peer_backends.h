#ifndef TRIGRAV_EXAMPLES_PEERS_PEER_BACKENDS_H_
#define TRIGRAV_EXAMPLES_PEERS_PEER_BACKENDS_H_

// The entries of each peer library; declared only when the library was found at build time
// (TRIGRAV_PEERS_HAVE_OPENCV, TRIGRAV_PEERS_HAVE_OPENGV). Callers use peer_estimators.h.

#include <vector>

#include "peer_estimators.h"

namespace trigrav::peers {

// RANSAC and USAC shared settings, the values of trigrav's RansacOptions where the API takes them.
inline constexpr double kPeerConfidence = 0.9999;
inline constexpr int kPeerMaxIterations = 10000;

#ifdef TRIGRAV_PEERS_HAVE_OPENCV
std::vector<NamedEstimator> OpenCvEstimators();
// cv::setNumThreads.
void SetOpenCvThreads(int threads);
#endif

#ifdef TRIGRAV_PEERS_HAVE_OPENGV
std::vector<NamedEstimator> OpenGvEstimators();
std::vector<NamedMinimalSolver> OpenGvMinimalSolvers();
#endif

}  // namespace trigrav::peers

#endif  // TRIGRAV_EXAMPLES_PEERS_PEER_BACKENDS_H_
