#include "peer_methods.h"

#include "peer_estimators.h"

namespace trigrav::kitti {

void AppendPeerMethods(double threshold_px, std::vector<Method>* methods) {
  peers::RunPeersSingleThreaded();
  for (const peers::NamedEstimator& peer : peers::PeerEstimators()) {
    methods->push_back({peer.name, [peer, threshold_px](const ThreeViewObservations& observations,
                                                        std::uint64_t /*seed*/) {
                          const peers::EstimatorResult result =
                              peer.estimate(observations, threshold_px);
                          MethodPose pose;
                          static_cast<RobustThreeViewEstimate&>(pose) = result;
                          pose.stage = peer.stage;
                          pose.time_s = result.time_s;
                          pose.relative_scale_known = result.relative_scale_known;
                          return std::vector<MethodPose>{pose};
                        }});
  }
}

}  // namespace trigrav::kitti
