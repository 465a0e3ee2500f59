#ifndef TRIGRAV_INITIALIZERS_SRC_TILT_CORRECTING_REFINEMENT_H_
#define TRIGRAV_INITIALIZERS_SRC_TILT_CORRECTING_REFINEMENT_H_

// Local optimisation that corrects the relative tilt of IMU gravity (derivations.md section 2.4).

#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <vector>

#include "robust_triplet_data.h"
#include "trifocal_common.h"
#include "trigrav/initializers/gravity.h"
#include "trigrav/initializers/trifocal_4pt.h"
#include "trigrav/initializers/trifocal_linear.h"

namespace trigrav {
namespace internal {

// Local optimisation of a gravity-aware method that may correct the given relative tilt
// (RobustThreeViewOptions::max_tilt_correction_deg): the linear trifocal tensor of the inliers'
// aligned rays gives camera 1's vertical as seen by cameras 2 and 3, R_k1 e_y; if it is within the
// bound of e_y, view k's aligned rays are turned by the tilt S_k taking R_k1 e_y to e_y. The
// upright 4-point solver then re-estimates yaw and translation on the corrected rays, and the pose
// is unaligned with the corrected alignments S_k A_k. The tensor, whose 26 unknowns make it noisy,
// contributes only the tilt (2 numbers per camera); yaw and translation come from the 4-point
// solver, as with exact gravity. Below the tensor's 7 triplets, or when it has no solution, the
// refinement is the upright one of M. (trigrav's own design; the paper assumes exact gravity.)
template <typename M>
struct TiltCorrectingRefinement : M {
  static_assert(M::kAligned, "only gravity-aware methods have a tilt to correct");
  static void Refine(const TripletData& data,
                     const ViewRays& aligned,
                     Workspace* work,
                     std::vector<ThreeViewPose>* poses) {
    std::array<Eigen::Matrix3d, 3> alignment = data.alignment;
    std::array<const Rays*, 3> rays = {&aligned[0], &aligned[1], &aligned[2]};
    work->three_view.clear();
    if (aligned[0].size() >= kTrifocalLinearMinTriplets) {
      SolveTrifocalLinear(aligned[0], aligned[1], aligned[2], &work->three_view);
    }
    if (!work->three_view.empty()) {
      const ThreeViewPose& tensor = work->three_view.front();
      const std::array<const Eigen::Matrix3d*, 2> rotation = {&tensor.cam2_from_cam1.R,
                                                              &tensor.cam3_from_cam1.R};
      for (int k = 1; k < 3; ++k) {
        const Eigen::Vector3d vertical = *rotation[k - 1] * Eigen::Vector3d::UnitY();
        if (!(vertical.y() >= data.min_cos_tilt_correction)) continue;  // beyond the bound
        const Eigen::Matrix3d tilt =
            Eigen::Quaterniond::FromTwoVectors(vertical, Eigen::Vector3d::UnitY())
                .toRotationMatrix();
        work->corrected[k].resize(aligned[k].size());
        for (std::size_t i = 0; i < aligned[k].size(); ++i) {
          work->corrected[k][i] = tilt * aligned[k][i];
        }
        rays[k] = &work->corrected[k];
        alignment[k] = tilt * alignment[k];
      }
    }
    SolveTrifocal4pt(*rays[0], *rays[1], *rays[2], &work->three_view);
    for (const ThreeViewPose& pose : work->three_view) {
      poses->push_back(UnalignThreeViewPose(pose, alignment[0], alignment[1], alignment[2]));
    }
  }
};

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_TILT_CORRECTING_REFINEMENT_H_
