#ifndef TRIGRAV_INITIALIZERS_SRC_CONSENSUS_EVIDENCE_H_
#define TRIGRAV_INITIALIZERS_SRC_CONSENSUS_EVIDENCE_H_

// How much a RANSAC winner's consensus says (derivations.md section 7.7): the number of false
// alarms of its inlier count against triplets that fit by chance, and the precision its inliers
// give the pose.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "robust_triplet_data.h"
#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav {
namespace internal {

// The bounding box of a view's pixels (non-empty): corners low and high.
struct PixelBox {
  Eigen::Vector2d low, high;
};
PixelBox PixelBoundingBox(const std::vector<Eigen::Vector2d>& pixels);

// Per view: the scale that turns a tangent-plane offset (radians) into the threshold's unit (the
// mean focal length in pixels; 180 / pi for bearings, whose threshold is in degrees).
std::array<double, 3> ThresholdUnitsPerRadian(const ThreeViewObservations& observations);

// Probability that a triplet drawn uniformly from the observed domain of each view fits a fixed
// pose within `threshold` (section 7.7): a band of half-width 2 threshold around an epipolar
// segment in one view times a disc of radius 2 threshold in the other, the domains being the
// bounding boxes of the pixels (the cap of the bearings around their mean, in degrees). In (0, 1].
double ChanceFitProbability(const ThreeViewObservations& observations, double threshold);

// log10 of the number of false alarms of k inliers among n triplets (Moisan and Stival's ORSA):
// max_models (n - s) C(n, k) C(k, s) alpha^(k - s), s the minimal sample and max_models the most
// models a sample gives. Below 0: fewer than one such consensus is expected by chance. +infinity
// for k < s.
double Log10NumberOfFalseAlarms(int n, int k, int sample_size, int max_models, double alpha);

// Standard deviations of the pose that `inliers` of `data` give at pose `pose` with isotropic
// observation noise `sigma` (in the threshold's unit, scaled per view by `units_per_radian`),
// from the Gauss-Newton information with every point eliminated (section 7.7), and the size of the
// Gauss-Newton step from `pose` to the inliers' optimum. Rotations vary about camera 1's vertical
// when `yaw_only`, freely otherwise; |C_2| = 1 fixes the scale.
struct PosePrecision {
  bool determined = false;         // the information is positive definite
  double rotation_sigma_deg = 0;   // largest over views 2 and 3 and directions
  double direction_sigma_deg = 0;  // of the centres' directions C_2 / |C_2|, C_3 / |C_3|
  // The Gauss-Newton step from `pose` to the inliers' least-squares optimum, measured as above.
  double rotation_offset_deg = 0;
  double direction_offset_deg = 0;
};
PosePrecision PredictPosePrecision(const TripletData& data,
                                   const ThreeViewPose& pose,
                                   const std::vector<char>& inliers,
                                   const std::array<double, 3>& units_per_radian,
                                   double sigma,
                                   bool yaw_only);

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_CONSENSUS_EVIDENCE_H_
