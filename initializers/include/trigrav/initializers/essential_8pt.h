#ifndef TRIGRAV_INITIALIZERS_ESSENTIAL_8PT_H_
#define TRIGRAV_INITIALIZERS_ESSENTIAL_8PT_H_

#include <Eigen/Core>
#include <vector>

#include "trigrav/initializers/camera_pose.h"

namespace trigrav {

// Normalised eight-point relative pose of two calibrated views ("8pt-Hartley-2view"):
// H. C. Longuet-Higgins, "A Computer Algorithm for Reconstructing a Scene from Two Projections",
// Nature 293, 1981, with the normalisation of R. Hartley, "In Defense of the Eight-Point
// Algorithm", IEEE TPAMI 19(6), 1997.
//
// Solves x2_n^T E x1_n = 0 (n = 1..N, N >= 8) for E = [t]_x R in least squares:
//   1. normalisation: if every ray points forward (z > 0.1 |x|, i.e. within 84 deg of the optical
//      axis) the rays are dehomogenised to (x/z, y/z) and each view is translated to zero centroid
//      and scaled isotropically to mean distance sqrt(2) from it (Hartley's T1, T2); otherwise the
//      rays are used as they are, scaled to unit length (T = I);
//   2. e = unit vector minimising |A e| over the N x 9 system A of rows kron(T2 x2, T1 x1)^T, by an
//      allocation-free Householder triangularisation streamed over the rows, then inverse
//      iteration; a rank deficiency of 2 or more (E not determined) returns 0;
//   3. E = T2^T E_hat T1, projected to the essential manifold (singular values (1, 1, 0));
//   4. decomposition into the four (R, t) candidates; the one with the most correspondences in
//      front of both cameras is kept if that is more than half of them.
// At most 1 solution. Conventions: x2 ~ R x1 + t, rays K^-1 [u v 1]^T (any non-zero length),
// |t| = |Center()| = 1.
//
// Clears *solutions, appends the pose and returns 1, or returns 0 for degenerate input (fewer than
// 8 distinct points, exactly zero translation, no majority in front); near-degenerate input gives a
// finite pose of little meaning, never NaN. Throws std::invalid_argument on misuse: sizes differ,
// fewer than 8 correspondences, non-finite numbers, zero-length rays, null output.
int SolveEssential8pt(const std::vector<Eigen::Vector3d>& x1,
                      const std::vector<Eigen::Vector3d>& x2,
                      std::vector<CameraPose>* solutions);

}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_ESSENTIAL_8PT_H_
