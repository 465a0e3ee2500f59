// Internal: essential matrix -> relative pose with the cheirality test, shared by the two-view
// solvers (essential_5pt.cc, essential_8pt.cc). Not installed; not part of the public API.
#ifndef TRIGRAV_INITIALIZERS_SRC_ESSENTIAL_DECOMPOSITION_H_
#define TRIGRAV_INITIALIZERS_SRC_ESSENTIAL_DECOMPOSITION_H_

#include <Eigen/Core>
#include <vector>

#include "trigrav/initializers/camera_pose.h"

namespace trigrav {
namespace internal {

// Of the four poses (R_a, +-t), (R_b, +-t), the one with the most correspondences in front of both
// cameras (both depths of the two-ray triangulation > 0; rays within 1e-10 rad of parallel after
// rotation count as not in front, so under a pure rotation, whose translation is unobservable, the
// true rotation gets no votes). Returns that number and writes the pose, or returns 0 and leaves
// *pose untouched if no correspondence is in front for any candidate (or no candidate is finite).
int ChoosePoseByCheirality(const Eigen::Matrix3d& R_a,
                           const Eigen::Matrix3d& R_b,
                           const Eigen::Vector3d& t,
                           const std::vector<Eigen::Vector3d>& x1,
                           const std::vector<Eigen::Vector3d>& x2,
                           CameraPose* pose);

// Pose (R, t) with |t| = 1 and E ~ [t]_x R (so x2^T E x1 = 0 for x2 ~ R x1 + t), chosen among the
// four decompositions of E (Hartley & Zisserman, "Multiple View Geometry", 2nd ed., result 9.19):
// with E = U diag(s1, s2, s3) V^T, det U = det V = 1, the rotations U W V^T, U W^T V^T
// (W = R_z(90 deg)) and the translations +-u_3. This first projects E to the essential manifold,
// i.e. s1, s2, s3 are replaced by (1, 1, 0) (the nearest essential matrix in the Frobenius norm, up
// to scale), so E may be any estimate of rank about 2: what the 8-point solver needs. Then
// ChoosePoseByCheirality. Returns 0 (pose untouched) also if E is zero or not finite.
int PoseFromEssential(const Eigen::Matrix3d& E,
                      const std::vector<Eigen::Vector3d>& x1,
                      const std::vector<Eigen::Vector3d>& x2,
                      CameraPose* pose);

// The same for an E that already satisfies the essential constraints up to rounding (as the
// five-point solver's do), without an SVD: scaled to |E|_F = sqrt(2) (singular values 1, 1, 0),
// t = the unit left null vector of E, and since cof(E) = t t^T R and [t]_x E = (t t^T - I) R for
// E = [t]_x R, the two rotations are cof(E) -+ [t]_x E (the second is the "twisted pair" rotation
// (2 t t^T - I) R, which is also what -E gives). Two Newton-Schulz steps R <- R (3 I - R^T R) / 2
// remove the residual non-orthogonality of a slightly inexact E; if R^T R is more than 1e-6 from I,
// E is not essential enough for that and PoseFromEssential (SVD projection) is used instead. Then
// ChoosePoseByCheirality.
int PoseFromExactEssential(const Eigen::Matrix3d& E,
                           const std::vector<Eigen::Vector3d>& x1,
                           const std::vector<Eigen::Vector3d>& x2,
                           CameraPose* pose);

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_ESSENTIAL_DECOMPOSITION_H_
