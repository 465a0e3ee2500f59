// Internal pieces the trifocal solvers share: the trifocal incidence equations of an aligned
// triplet (as linear functions of the centres), the epipoles of a tensor, and the final orientation
// and scaling into a ThreeViewPose. Not installed; not part of the public API.
#ifndef TRIGRAV_INITIALIZERS_SRC_TRIFOCAL_COMMON_H_
#define TRIGRAV_INITIALIZERS_SRC_TRIFOCAL_COMMON_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "trigrav/initializers/camera_pose.h"

namespace trigrav {
namespace internal {

// The centres (c_2; c_3) of a three-view estimate, the unknowns of the translation rows below.
using Vector6d = Eigen::Matrix<double, 6, 1>;
// A trifocal tensor as its slices T_1, T_2, T_3.
using TensorSlices = std::array<Eigen::Matrix3d, 3>;

// The fewest triplets each non-minimal trifocal solver accepts (SolveTrifocal4pt,
// SolveTrifocalLinear); with exactly that many each runs its fixed-size path.
inline constexpr int kTrifocal4ptMinTriplets = 4;
inline constexpr int kTrifocalLinearMinTriplets = 7;

// A yaw R_y(theta) held as its cosine and sine: the solvers build rotations from it without
// trigonometric calls (they cost about as much as a 6x6 triangular solve each).
struct Yaw {
  double c = 1.0, s = 0.0;
  // The yaw of the direction (c, s), any positive length: atan2(s, c) without the call. (0, 0)
  // (either sign) gives theta = 0; a NaN or infinite input gives a non-finite yaw.
  static Yaw FromDirection(double c, double s) {
    if (c == 0.0 && s == 0.0) return {};
    const double scale = std::max(std::abs(c), std::abs(s));  // NaN: 0 or NaN, both propagate
    c /= scale;
    s /= scale;
    const double inverse_norm = 1.0 / std::sqrt(c * c + s * s);
    return {c * inverse_norm, s * inverse_norm};
  }
  bool IsFinite() const { return std::isfinite(c) && std::isfinite(s); }
  Eigen::Matrix3d Matrix() const {
    Eigen::Matrix3d R;
    R << c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c;
    return R;
  }
  // R_y x = (c x_x + s x_z, x_y, -s x_x + c x_z) and R_y^T x, without forming R_y.
  Eigen::Vector3d Rotate(const Eigen::Vector3d& x) const {
    return Eigen::Vector3d(c * x.x() + s * x.z(), x.y(), c * x.z() - s * x.x());
  }
  Eigen::Vector3d RotateBack(const Eigen::Vector3d& x) const {
    return Eigen::Vector3d(c * x.x() - s * x.z(), x.y(), c * x.z() + s * x.x());
  }
};

// Orthonormal basis (p1, p2) of the plane orthogonal to x (x non-zero).
inline void PerpendicularBasis(const Eigen::Vector3d& x, Eigen::Vector3d* p1, Eigen::Vector3d* p2) {
  const Eigen::Vector3d unit = x.normalized();
  *p1 = unit.unitOrthogonal();
  *p2 = unit.cross(*p1);
}

// The parts of one triplet's incidence rows that do not depend on the rotations (derivations.md
// section 3.4): orthonormal bases (p_a) of x2^perp and (r_b) of x3^perp, and p_a x x2, r_b x x3.
struct TripletFrame {
  Eigen::Vector3d x1;
  Eigen::Vector3d p[2], r[2];
  Eigen::Vector3d left[2], right[2];  // p_a x x2, r_b x x3
  Eigen::Vector3d x2, x3;
};

inline TripletFrame MakeTripletFrame(const Eigen::Vector3d& x1,
                                     const Eigen::Vector3d& x2,
                                     const Eigen::Vector3d& x3) {
  TripletFrame frame;
  frame.x1 = x1;
  frame.x2 = x2;
  frame.x3 = x3;
  PerpendicularBasis(x2, &frame.p[0], &frame.p[1]);
  PerpendicularBasis(x3, &frame.r[0], &frame.r[1]);
  for (int i = 0; i < 2; ++i) {
    frame.left[i] = frame.p[i].cross(x2);
    frame.right[i] = frame.r[i].cross(x3);
  }
  return frame;
}

// The incidence rows of one triplet in (c_2; c_3) for given R2, R3, in factored form
// (derivations.md section 3.4): row (a, b) = [ zr_b left_R2_a^T , pu_a right_R3_b^T ] with
// left_R2_a = R2^T (p_a x x2), right_R3_b = R3^T (r_b x x3), pu_a = p_a . u = left_R2_a . x1 and
// zr_b = z . r_b = -right_R3_b . x1 (u = x2 x R2 x1, z = R3 x1 x x3).
struct TranslationTerms {
  Eigen::Vector3d left_R2[2], right_R3[2];
  double pu[2], zr[2];
};

inline TranslationTerms MakeTranslationTerms(const TripletFrame& frame,
                                             const Eigen::Matrix3d& R2,
                                             const Eigen::Matrix3d& R3) {
  TranslationTerms terms;
  for (int i = 0; i < 2; ++i) {
    terms.left_R2[i] = R2.transpose() * frame.left[i];
    terms.right_R3[i] = R3.transpose() * frame.right[i];
    terms.pu[i] = terms.left_R2[i].dot(frame.x1);
    terms.zr[i] = -terms.right_R3[i].dot(frame.x1);
  }
  return terms;
}

// The 4 trifocal incidence equations of one triplet as linear functions of the centres (c_2; c_3)
// for fixed rotations (derivations.md section 3.4), from their factored form.
inline Eigen::Matrix<double, 4, 6> TranslationRows(const TranslationTerms& terms) {
  Eigen::Matrix<double, 4, 6> rows;
  for (int a = 0; a < 2; ++a) {
    for (int b = 0; b < 2; ++b) {
      rows.block<1, 3>(2 * a + b, 0) = terms.zr[b] * terms.left_R2[a].transpose();
      rows.block<1, 3>(2 * a + b, 3) = terms.pu[a] * terms.right_R3[b].transpose();
    }
  }
  return rows;
}

// The same rows from the rays of one aligned triplet.
inline Eigen::Matrix<double, 4, 6> TranslationRows(const Eigen::Vector3d& x1,
                                                   const Eigen::Vector3d& x2,
                                                   const Eigen::Vector3d& x3,
                                                   const Eigen::Matrix3d& R2,
                                                   const Eigen::Matrix3d& R3) {
  return TranslationRows(MakeTranslationTerms(MakeTripletFrame(x1, x2, x3), R2, R3));
}

// Epipoles e', e'' of a trifocal tensor with slices T_1, T_2, T_3: the left null vectors of
// [u1 u2 u3] and [v1 v2 v3], u_i and v_i the left and right null vectors of T_i (eq. f1, H&Z
// algorithm 15.1). False if either is not defined (zero).
bool EpipolesFromTensor(const TensorSlices& T,
                        Eigen::Vector3d* epipole2,
                        Eigen::Vector3d* epipole3);

// Finishes an aligned three-view estimate known up to a common factor of the centres: flips the
// sign of (c2, c3) if most view-1 depths of pairs (1,2) and (1,3) are negative, scales to |c2| = 1
// and writes the pose. Returns false (writing nothing) if the result is degenerate or not finite.
bool OrientScaleAndMakePose(const std::vector<Eigen::Vector3d>& x1,
                            const std::vector<Eigen::Vector3d>& x2,
                            const std::vector<Eigen::Vector3d>& x3,
                            const Yaw& yaw2,
                            Eigen::Vector3d center2,
                            const Yaw& yaw3,
                            Eigen::Vector3d center3,
                            ThreeViewPose* pose);

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_TRIFOCAL_COMMON_H_
