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
                          return std::vector<MethodPose>{{kRawStage, result.success, result.pose,
                                                          result.num_inliers, result.time_s,
                                                          result.relative_scale_known}};
                        }});
  }
}

}  // namespace trigrav::kitti
