#ifndef TRIGRAV_EXAMPLES_KITTI_PEER_METHODS_H_
#define TRIGRAV_EXAMPLES_KITTI_PEER_METHODS_H_

// The peers of examples/peers/ (OpenCV's and OpenGV's five-point RANSAC on pairs (1,2), (1,3)) as
// KITTI methods, for kitti_triplets --peers. Compiled only when a peer library was found
// (TRIGRAV_PEER_SOURCES, examples/peers/README.md).

#include <vector>

#include "kitti_methods.h"

namespace trigrav::kitti {

// Appends every peer found at build time, each with its one stage "raw" at the evaluation's inlier
// threshold (pixels; what it means for each peer is in examples/peers/peer_estimators.h). Peers run
// single-threaded (OpenCV's pool off) and ignore the seed: they are deterministic.
void AppendPeerMethods(double threshold_px, std::vector<Method>* methods);

}  // namespace trigrav::kitti

#endif  // TRIGRAV_EXAMPLES_KITTI_PEER_METHODS_H_
