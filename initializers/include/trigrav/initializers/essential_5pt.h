#ifndef TRIGRAV_INITIALIZERS_ESSENTIAL_5PT_H_
#define TRIGRAV_INITIALIZERS_ESSENTIAL_5PT_H_

#include <vector>

#include <Eigen/Core>

#include "trigrav/initializers/camera_pose.h"

namespace trigrav {

// Five-point relative pose of two calibrated views ("5pt-Nister-2view"): D. Nister, "An Efficient
// Solution to the Five-Point Relative Pose Problem", IEEE TPAMI 26(6), 2004, in the Groebner-basis
// formulation of H. Stewenius, C. Engels and D. Nister, "Recent Developments on Direct Relative
// Orientation", ISPRS J. Photogrammetry and Remote Sensing 60(4), 2006.
//
// Solves x2_n^T E x1_n = 0 (n = 1..5) with E = [t]_x R essential, i.e.
//   det(E) = 0  and  2 E E^T E - tr(E E^T) E = 0   (Nister eqs. 3 and 4):
//   1. E = x X + y Y + z Z + W from an orthonormal basis of the null space of the 5 x 9 epipolar system;
//   2. the 10 cubic constraints in (x, y, z), 20 monomials; Gauss-Jordan elimination of the 10 cubic
//      monomials leaves the quotient-ring basis (x^2, xy, xz, y^2, yz, z^2, x, y, z, 1);
//   3. the 10 x 10 action matrix of multiplication by x; its real eigenvectors are that basis
//      evaluated at the solutions (Eigen::EigenSolver on a fixed 10 x 10 matrix);
//   4. each real E is decomposed into (R, t) and kept only if all 5 points triangulate in front of
//      both cameras (positive depths in both views).
// Up to 10 solutions (the real roots of Nister's degree-10 polynomial); typically 1 to 4 survive the
// cheirality test. Conventions: x2 ~ R x1 + t, rays K^-1 [u v 1]^T (any non-zero length, any sign
// of z), each solution scaled to |t| = |Center()| = 1.
//
// Exactly 5 correspondences. Clears *solutions, appends every real, cheirality-consistent pose and
// returns the count (0 for degenerate input, e.g. coincident points or, without translation, no
// observable epipolar geometry). Throws std::invalid_argument on misuse: sizes differ, not exactly 5
// correspondences, non-finite numbers, zero-length rays, null output.
int SolveEssential5pt(const std::vector<Eigen::Vector3d>& x1, const std::vector<Eigen::Vector3d>& x2,
                      std::vector<CameraPose>* solutions);

}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_ESSENTIAL_5PT_H_
