#include "trigrav/initializers/two_view_to_three_view.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "input_checks.h"
#include "two_view_geometry.h"

namespace trigrav {

void CombineTwoViewPairs(const std::vector<Eigen::Vector3d>& x1,
                         const std::vector<Eigen::Vector3d>& x2,
                         const std::vector<Eigen::Vector3d>& x3,
                         const std::vector<CameraPose>& pair12,
                         const std::vector<CameraPose>& pair13,
                         std::vector<ThreeViewPose>* poses,
                         std::vector<double>* residuals) {
  constexpr const char* kName = "CombineTwoViewPairs";
  if (poses == nullptr) throw std::invalid_argument("trigrav: CombineTwoViewPairs: poses is null");
  internal::CheckTriplets(kName, 0, std::numeric_limits<std::size_t>::max(), x1, x2, x3, poses);
  internal::CheckPoses(kName, "pair12", pair12);
  internal::CheckPoses(kName, "pair13", pair13);
  const std::size_t n_points = x1.size();
  for (const CameraPose& cam2 : pair12) {
    const Eigen::Vector3d center2 = cam2.Center();
    for (const CameraPose& cam3 : pair13) {
      const Eigen::Vector3d center3 = cam3.Center();
      double cross = 0.0, squared = 0.0, squared2 = 0.0;
      for (std::size_t n = 0; n < n_points; ++n) {
        const double depth2 = internal::ViewOneDepth(x1[n], x2[n], cam2.R, center2);
        const double depth3 = internal::ViewOneDepth(x1[n], x3[n], cam3.R, center3);
        cross += depth2 * depth3;
        squared += depth3 * depth3;
        squared2 += depth2 * depth2;
      }
      const double kappa = cross / squared;
      if (!(kappa > 0.0) || !std::isfinite(kappa)) continue;
      ThreeViewPose pose;
      pose.cam2_from_cam1 = cam2;
      pose.cam3_from_cam1.R = cam3.R;
      pose.cam3_from_cam1.t = kappa * cam3.t;
      poses->push_back(pose);
      if (residuals != nullptr) {
        // A second pass: |l2|^2 - kappa <l2, l3> would lose half the digits to cancellation.
        double remainder = 0.0;
        for (std::size_t n = 0; n < n_points; ++n) {
          const double depth2 = internal::ViewOneDepth(x1[n], x2[n], cam2.R, center2);
          const double depth3 = internal::ViewOneDepth(x1[n], x3[n], cam3.R, center3);
          remainder += (depth2 - kappa * depth3) * (depth2 - kappa * depth3);
        }
        residuals->push_back(squared2 > 0.0 ? std::sqrt(remainder / squared2)
                                            : std::numeric_limits<double>::infinity());
      }
    }
  }
}

}  // namespace trigrav
