#ifndef TRIGRAV_INITIALIZERS_TRIFOCAL_LINEAR_H_
#define TRIGRAV_INITIALIZERS_TRIFOCAL_LINEAR_H_

#include <Eigen/Core>
#include <vector>

#include "trigrav/initializers/camera_pose.h"

namespace trigrav {

// Normalised linear trifocal tensor for calibrated views with general rotations, no gravity
// ("7pt-Hartley-3view" baseline of the experiments). References: Hartley & Zisserman, "Multiple
// View Geometry", 2nd ed., algorithm 16.1 (normalised linear tensor), chapter 15 and algorithm 15.1
// (epipoles, fundamental matrices and cameras from the tensor), section 9.6 (E to R, t); Julia &
// Monasse 2018, "A critical review of the trifocal tensor estimation", which evaluates this linear
// method among the trifocal estimators.
//
// With P_1 = [I | 0], P_2 = [A | a_4], P_3 = [B | b_4] the tensor is T_i = a_i b_4^T - a_4 b_i^T
// and a triplet x1 <-> x2 <-> x3 satisfies the point-point-point incidence
//   [x2]_x (sum_i x1_i T_i) [x3]_x = 0_{3x3},
// 4 independent equations linear in the 27 entries of T: p_a^T (sum_i x1_i T_i) r_b = 0, a, b in
// {1, 2}, with orthonormal bases (p_a) of x2^perp and (r_b) of x3^perp (derivations.md section 3).
//   1. Hartley normalisation per view: dehomogenise (x_1 / x_3, x_2 / x_3), move the centroid to
//      the origin and scale the mean distance to sqrt(2): x^ = H_k x / x_3. The incidence is
//      homogeneous in each ray, so dividing by a negative x_3 (a ray pointing backwards) does not
//      change the tensor; cheirality below uses the caller's rays with their own sign. A view with
//      a ray whose x_3 is 0 (or below 1e-12 |x|) is not dehomogenised: its rays are only scaled to
//      unit length.
//   2. T^ = least-squares null vector (|T^| = 1) of the stacked 4N x 27 system, N >= 7; then
//      T_i = sum_r (H_1)_{ri} H_2^-1 T^_r H_3^-T.
//   3. Epipoles e', e'' (unit): left null vector of the left null vectors of T_1, T_2, T_3, and the
//      same for the right null vectors; cameras (H&Z algorithm 15.1)
//        P_2 = [[T_1, T_2, T_3] e'' | e'],  P_3 = [(e'' e''^T - I) [T_1^T, T_2^T, T_3^T] e' | e''],
//      and since the rays are calibrated, the essential matrices E_21 = [e']_x M_2 and
//      E_31 = [e'']_x M_3 (P_k = [M_k | m_k]; H&Z's F_21 and F_31 up to sign).
//   4. Each E_k1 = U diag(s1, s2, 0) V^T gives two rotations U W V^T and U W^T V^T (the twisted
//      pair).
//   5. For each of the 2 x 2 rotation pairs the centres (c_2; c_3) are re-solved linearly from all
//      triplets with the rotations fixed (the incidence rows of derivations.md section 3.4, valid
//      for any R_2, R_3: least-squares null vector of 4N x 6). This gives both directions and the
//      relative scale from the incidence itself rather than from the entries of the unconstrained
//      tensor.
//   6. Cheirality: for each pair, the sign of (c_2; c_3) that puts the most triplets in front of
//      all three cameras (view-1 depths from pairs (1,2) and (1,3), and the depths of those points
//      in cameras 2 and 3) is kept. The pair with the most such triplets wins (ties: smaller
//      residual of step 5); a strict majority of the triplets is required, otherwise there is no
//      solution. The pair of two-view choices (per view pair, the rotation with more triplets in
//      front of both cameras for the centre direction of E_k1, H&Z section 9.6) is tried first,
//      and the search stops at the first pair with every triplet in front. Taking the two-view
//      choices alone returns no solution about 1.5x as often (measured at 1 px, f = 500 px:
//      20 triplets 1.5 % against 0.8 % of the scenes, 7 triplets 27 % against 18 %).
//      Scale |c_2| = 1, t_k = -R_k c_k.
// Rays are K^-1 [u v 1]^T (any non-zero length and sign). At most one solution, scaled so that
// |cam2_from_cam1.Center()| = 1; returns the number written. Degenerate input gives 0 solutions
// (coincident points in a view, a repeated triplet or any other input whose 4N x 27 system has a
// null space of dimension 2 or more, no cheirality-consistent pose) or, when the tensor is not
// defined (zero baseline in both pairs: pure rotations), possibly a finite pose with meaningless
// translations; never a non-finite pose. Throws std::invalid_argument on misuse: sizes differ,
// fewer than 7 triplets, non-finite numbers, zero-length rays, null output.
int SolveTrifocalLinear(const std::vector<Eigen::Vector3d>& x1,
                        const std::vector<Eigen::Vector3d>& x2,
                        const std::vector<Eigen::Vector3d>& x3,
                        std::vector<ThreeViewPose>* solutions);

}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_TRIFOCAL_LINEAR_H_
