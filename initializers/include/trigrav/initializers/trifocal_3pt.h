#ifndef TRIGRAV_INITIALIZERS_TRIFOCAL_3PT_H_
#define TRIGRAV_INITIALIZERS_TRIFOCAL_3PT_H_

#include <Eigen/Core>
#include <vector>

#include "trigrav/initializers/camera_pose.h"

namespace trigrav {

// 3-point trifocal solvers with known vertical direction ("3pt-Our-3view" of Li, Yu, Guan et al.,
// "Trifocal Tensor and Relative Pose Estimation with Known Vertical Direction", Section III-C).
//
// In gravity-aligned frames (camera y axis = gravity, down) the cameras are P_1 = [I | 0] and
// P_k = [R_y(theta_k) | -R_y(theta_k) c_k], with
//   R_y(theta) = [[cos, 0, sin], [0, 1, 0], [-sin, 0, cos]]
// and c_k the centre of camera k in view-1 coordinates. There are 7 unknowns (theta_2, theta_3 and
// c_2, c_3 up to one scale), while 3 triplets give 9 independent trifocal constraints (3 per
// triplet, eq. d5): the problem is over-determined by 2 (derivations.md section 5.1). An exact
// solver uses 7 of the 9 constraints and the other 2 can only rank the candidates, so both solvers
// return every candidate that passes cheirality (all three points in front of all three cameras),
// best first. Scale convention: |cam2_from_cam1.Center()| = 1; |cam3_from_cam1.Center()| is the
// estimated relative scale. `solutions` is cleared first; the return value is the number of poses
// written.
//
// Yaw = 180 deg: the paper's Cayley parameter s = tan(theta/2) (eq. d1) cannot represent theta =
// pi, where the leading coefficient of the polynomial in s vanishes. Both solvers detect a leading
// coefficient below 1 % of the largest one and then use t = tan((theta - theta_0)/2) with another
// offset theta_0 (pi/2 first), so that theta = pi and yaws near it are ordinary, accurate roots.
//
// Degenerate input gives 0 solutions or only the candidates that survive; never a non-finite pose.
// Both solvers return 0 when one yaw maps all three rays of view 1 onto those of view 2 to within
// 1e-4 rad (no parallax in pair (1,2): zero baseline of camera 2, identical views, points at
// infinity), since |c_2| = 1 is then undefined; camera 3 may have none (c_3 = 0 is a valid pose).
// The decoupled solver also returns 0 when two of the three triplets coincide.
// Misuse throws std::invalid_argument: sizes differ, not exactly 3 triplets, non-finite numbers,
// zero-length rays, null output (and, for the gravity overloads, zero or non-finite gravity).

// The default 3-point solver: two upright 2-view problems plus a scale (derivations.md
// section 5.5). This is not the paper's formulation, which is 2-3x less accurate and
// ill-conditioned (derivations.md section 9).
//   1. For each view pair (1,k), k = 2, 3, the epipolar constraints (R_k c_k) . m_n = 0 with
//      m_n = (R_k x1_n) x xk_n give det[m_1; m_2; m_3] = 0: a trigonometric polynomial of degree 2
//      in theta_k, i.e. a quartic in tan(theta_k/2) (the degree-6 determinant divided by its exact
//      factor 1 + tan^2, derivations.md section 5.5). Its real roots come in closed form (Ferrari)
//      with Newton polish; under noise a complex pair with |Im tan| <= 0.1 (1 + Re(tan)^2) also
//      contributes its real part (noise turns near-double real roots into such pairs). R_k c_k
//      spans the null space of the m_n; roots whose 3 points are not all in front of cameras 1 and
//      k (for either sign of c_k) are dropped.
//   2. Every pair of surviving roots (theta_2, c_2, lambda_2) x (theta_3, c_3, lambda_3), lambda_k
//      the view-1 depths of the 3 points from pair (1,k) with |c_k| = 1, gives the candidate
//      (theta_2, c_2, theta_3, kappa c_3) with kappa = <lambda_2, lambda_3> / <lambda_3, lambda_3>.
//   3. Candidates are sorted by the depth-ratio residual |lambda_2 - kappa lambda_3| / |lambda_2|
//      (about 1e-14 for the true candidate without noise).
// At most 4 x 4 = 16 solutions (about 5 on average on the synthetic scenes of derivations.md
// section 8.5).
int SolveTrifocal3pt(const std::vector<Eigen::Vector3d>& x1,
                     const std::vector<Eigen::Vector3d>& x2,
                     const std::vector<Eigen::Vector3d>& x3,
                     std::vector<ThreeViewPose>* solutions);

// Raw rays K^-1 [u v 1]^T, plus each camera's gravity direction (down, any positive length) in its
// own frame; the rays are aligned, solved as above and the poses mapped back with the corrected
// eq. b4 (see gravity.h), in closed form from each candidate's yaw (derivations.md section 2.2).
// Poses are in the original camera frames.
int SolveTrifocal3pt(const std::vector<Eigen::Vector3d>& x1,
                     const std::vector<Eigen::Vector3d>& x2,
                     const std::vector<Eigen::Vector3d>& x3,
                     const Eigen::Vector3d& gravity_in_cam1,
                     const Eigen::Vector3d& gravity_in_cam2,
                     const Eigen::Vector3d& gravity_in_cam3,
                     std::vector<ThreeViewPose>* solutions);

// The paper's joint system for (theta_2, theta_3), in the corrected form of derivations.md
// sections 5.2-5.4. The paper (eqs d6-d8) sets two 6x6 minors of the 9x6 matrix F^(s_2, s_3) to
// zero. derivations.md section 5.2 shows (sympy, exact data) that each minor factors as
//   (1+s_2^2)^3 (1+s_3^2)^3 u1_a(s_2) u1_b(s_2) z1_a(s_3) z1_b(s_3) C_ab(s_2, s_3),
// and that two minors built from the paper's rows share the factors of their common point, so the
// paper's literal two-minor system is not zero-dimensional (erratum d8, derivations.md section 10).
// This solver solves the cores instead:
//   C_ab(theta_2, theta_3) = f_2b(theta_2) f_3a(theta_3) - f_2a(theta_2) f_3b(theta_3) = 0,
//   f_kn(theta) = (R_y(theta) x1_n) . (xk_a x xk_b),   for (a, b) = (1, 2) and (1, 3),
// i.e. equal view-1 depth ratios lambda_a / lambda_b from pairs (1,2) and (1,3). For fixed theta_2
// both are linear in (cos theta_3, sin theta_3, 1), so (cos theta_3, sin theta_3, 1) ~ row_12 x
// row_13 =: (cx, cy, cz), and cx^2 + cy^2 - cz^2 = 0 is a degree-8 polynomial in tan(theta_2/2)
// with the exact factor 1 + tan^2(theta_2/2): a sextic (derivations.md section 5.4). Its real roots
// come from Sturm sequences. The centres are the null vector of the 12x6
// translation system of the 3 triplets with the yaws fixed (derivations.md section 3.4), signed by
// cheirality. Candidates are sorted by sigma_min / sigma_max of that 12x6 system (sigma_max by
// power iteration), which involves all 9 trifocal constraints. At most 6 solutions (the paper's "6
// complex roots"; about 2.7 pass cheirality on the synthetic scenes). Kept for comparison with the
// paper: it is slower and less accurate than SolveTrifocal3pt (near-double roots, derivations.md
// section 9).
int SolveTrifocal3ptSextic(const std::vector<Eigen::Vector3d>& x1,
                           const std::vector<Eigen::Vector3d>& x2,
                           const std::vector<Eigen::Vector3d>& x3,
                           std::vector<ThreeViewPose>* solutions);

// Gravity overload of the sextic solver, as for SolveTrifocal3pt.
int SolveTrifocal3ptSextic(const std::vector<Eigen::Vector3d>& x1,
                           const std::vector<Eigen::Vector3d>& x2,
                           const std::vector<Eigen::Vector3d>& x3,
                           const Eigen::Vector3d& gravity_in_cam1,
                           const Eigen::Vector3d& gravity_in_cam2,
                           const Eigen::Vector3d& gravity_in_cam3,
                           std::vector<ThreeViewPose>* solutions);

}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_TRIFOCAL_3PT_H_
