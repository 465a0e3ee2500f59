#ifndef TRIGRAV_INITIALIZERS_SRC_OBSERVATION_RAYS_H_
#define TRIGRAV_INITIALIZERS_SRC_OBSERVATION_RAYS_H_

// ThreeViewObservations::Check() and the rays of the observations in one pass, so that whoever
// needs both (ThreeViewReprojectionError) unprojects each pixel once.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "trigrav/initializers/three_view_observations.h"

namespace trigrav {
namespace internal {

// Throws as ThreeViewObservations::Check(); when rays is not null, (*rays)[k][n] is then the ray of
// triplet n in view k: the unprojected pixel (z = 1) or the unit bearing.
void CheckAndUnproject(const ThreeViewObservations& observations,
                       std::array<std::vector<Eigen::Vector3d>, 3>* rays);

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_OBSERVATION_RAYS_H_
