#ifndef TRIGRAV_INITIALIZERS_TRIFOCAL_4PT_H_
#define TRIGRAV_INITIALIZERS_TRIFOCAL_4PT_H_

#include <Eigen/Core>
#include <vector>

#include "trigrav/initializers/camera_pose.h"

namespace trigrav {

// 4-point trifocal solver with known vertical direction ("4pt-Our-3view" of Li, Yu, Guan et al.,
// "Trifocal Tensor and Relative Pose Estimation with Known Vertical Direction", Section III-B/D).
//
// In gravity-aligned frames (camera y axis = gravity, down) the cameras are P_1 = [I | 0],
// P_k = [R_y(theta_k) | -R_y(theta_k) c_k] and the trifocal tensor T_i = a_i b_4^T - a_4 b_i^T has
// 17 non-zero entries q = (Q_1..Q_17) (eqs c2-c5). Each triplet x1 <-> x2 <-> x3 gives the
// incidence [x2]_x (sum_i x1_i T_i) [x3]_x = 0, 4 independent equations linear in q (eq. c6), so 4
// triplets determine q up to scale. The pipeline follows derivations.md section 4, which corrects
// and completes the paper (section 4.7 gives the default):
//   1. q = least-squares null vector of the stacked 4N x 17 system (one row per x2/x3 perp pair);
//   2. the pose read from q:
//      - 4 triplets (the default): yaws and centres by the least-squares read of the bilinear
//        relations of q (derivations.md section 4.2, closed form);
//      - more triplets, or recovery = kEnforced: constraint enforcement (eqs f1-f7), the 6
//        parameters a minimising |A E a| with |E a| = 1 for given epipoles (section 4.3), the
//        yaws read from a (section 4.4), and the centres re-solved linearly from all triplets with
//        the yaws fixed (section 3.4); optionally (epipole_iterations) epipoles from that pose and
//        the enforcement again;
//   3. Gauss-Newton steps on the incidence residuals over yaws and centres jointly (section 4.5,
//      trigrav's own) until converged: noise-free one step takes the read to rounding level; with
//      noise they move the estimate to the nearest minimum of the algebraic residual. The default
//      runs at most one step after the enforcement of more than 4 triplets;
//   4. the common sign of the translations by a cheirality vote, scale |c_2| = 1;
//   5. poses mapped to the original frames with the corrected eq. b4 (see gravity.h).
// Noise-free every recovery is exact to rounding. With noise, recovery = kEnforced (with the
// default polish to convergence) is the most accurate choice, at a higher cost per call. The
// default is chosen for RANSAC, whose samples are 4 triplets: what counts there is how many usable
// models a second of sampling yields, and the default yields more of them per unit time; its bad
// samples are worse, which RANSAC discards either way. A caller who solves 4 noisy triplets once,
// without RANSAC, should take kEnforced. The errors and times behind this choice: derivations.md
// section 4.7.
// With noise, the result depends slightly on which yaw the caller's alignment rotations choose (the
// normalisation |q| = 1 is not yaw-invariant); the gravity overload always uses
// GravityAlignmentFromGravity.
// Exactly one solution (or none for numerically degenerate input).

// How the poses are read from the tensor. The paper's own variants stay selectable because the
// experiments compare them.
enum class Trifocal4ptRecovery {
  kEnforced,         // constraint enforcement (f1-f7), poses read as in derivations.md section 4.3
  kLeastSquares,     // no enforcement; yaws from all 8 relations of eq. c5 by least squares
                     // (derivations.md section 4.2)
  kPaperClosedForm,  // no enforcement; the paper's eqs c8-c11 (singular for straight or sideways
                     // motion)
  kLeastSquaresIfMinimal,  // the default: kLeastSquares for 4 triplets, kEnforced for more
};

// Where constraint enforcement (kEnforced) takes the epipoles from (derivations.md section 4.3
// step 1). No effect with the default recovery: for 4 triplets it reads the pose without
// enforcement (and where that read is undefined, so are the read's epipoles), for more it takes
// the null vectors of T_i either way.
enum class Trifocal4ptEpipoles {
  kLeastSquaresReadIfMinimal,  // the least-squares read of q for 4 triplets (more accurate and
                               // cheaper there), the null vectors of T_i for more: the default
  kTensorNullVectors,          // the null vectors of T_i (eq. f1) at any size: the paper's
};

struct Trifocal4ptOptions {
  Trifocal4ptRecovery recovery = Trifocal4ptRecovery::kLeastSquaresIfMinimal;
  Trifocal4ptEpipoles epipoles = Trifocal4ptEpipoles::kLeastSquaresReadIfMinimal;
  // Re-solve (c_2, c_3) from all triplets with the yaws fixed (derivations.md section 4.5); cuts
  // the translation error of the enforcement by about a third. The paper does not do this. The
  // default recovery does not re-solve after its least-squares read of 4 triplets: at the read's
  // yaws the re-solve moves the centres away from the polish's optimum.
  bool resolve_translations = true;
  // With the enforcement (kEnforced; the default recovery for more than 4 triplets, and for 4
  // where its read is undefined): times to re-estimate the epipoles from the current pose and
  // repeat enforcement and the translation solve (derivations.md section 4.5; not in the paper).
  // Without polish each pass lowers the error of noisy input; with one polish step it is not
  // needed (its errors and cost: derivations.md section 4.5).
  int epipole_iterations = 0;
  // At most this many Gauss-Newton steps on the incidence residuals over yaws and centres jointly
  // (step 3 above). The polish ends early once a step is at rounding level or the step before the
  // last changed the cost by less than 1 %: one step noise-free. The default recovery runs at most
  // one step for more than 4 triplets (the cost is algebraic: more steps lower it, not the
  // reprojection error); the explicit recoveries run up to this many at any size. 0 leaves the
  // polish out. Step counts and times: derivations.md section 4.5.
  int polish_iterations = 8;

  // Throws std::invalid_argument naming the first bad field: recovery or epipoles not one of the
  // enumerators, negative iteration counts. The solvers call it.
  void Check() const;
};

// Rays already in gravity-aligned frames: camera y axis = gravity (down). N >= 4 triplets, more
// than 4 are used in least squares. Writes at most one solution, scaled so that
// |cam2_from_cam1.Center()| = 1; returns the number written (0 for numerically degenerate input).
// Throws std::invalid_argument on misuse: sizes differ, fewer than 4 triplets, non-finite numbers,
// zero-length rays, null output.
int SolveTrifocal4pt(const std::vector<Eigen::Vector3d>& x1,
                     const std::vector<Eigen::Vector3d>& x2,
                     const std::vector<Eigen::Vector3d>& x3,
                     std::vector<ThreeViewPose>* solutions);

// Raw rays K^-1 [u v 1]^T, plus each camera's gravity direction (down, any positive length) in its
// own frame. Poses are returned in the original camera frames. Also throws for zero or non-finite
// gravity.
int SolveTrifocal4pt(const std::vector<Eigen::Vector3d>& x1,
                     const std::vector<Eigen::Vector3d>& x2,
                     const std::vector<Eigen::Vector3d>& x3,
                     const Eigen::Vector3d& gravity_in_cam1,
                     const Eigen::Vector3d& gravity_in_cam2,
                     const Eigen::Vector3d& gravity_in_cam3,
                     std::vector<ThreeViewPose>* solutions);

// The same two entry points with explicit options (paper variants, no translation re-solve); they
// also throw std::invalid_argument for options that fail Trifocal4ptOptions::Check().
int SolveTrifocal4pt(const std::vector<Eigen::Vector3d>& x1,
                     const std::vector<Eigen::Vector3d>& x2,
                     const std::vector<Eigen::Vector3d>& x3,
                     const Trifocal4ptOptions& options,
                     std::vector<ThreeViewPose>* solutions);
int SolveTrifocal4pt(const std::vector<Eigen::Vector3d>& x1,
                     const std::vector<Eigen::Vector3d>& x2,
                     const std::vector<Eigen::Vector3d>& x3,
                     const Eigen::Vector3d& gravity_in_cam1,
                     const Eigen::Vector3d& gravity_in_cam2,
                     const Eigen::Vector3d& gravity_in_cam3,
                     const Trifocal4ptOptions& options,
                     std::vector<ThreeViewPose>* solutions);

}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_TRIFOCAL_4PT_H_
