#ifndef TRIGRAV_FACTORS_SRC_POINT_GAUSS_NEWTON_H_
#define TRIGRAV_FACTORS_SRC_POINT_GAUSS_NEWTON_H_

// One triplet's point X (camera 1's frame) with the three cameras fixed: its robust cost
// f = 1/2 sum_k rho(|r_k|^2) over the views k = 1, 2, 3, the Gauss-Newton system of f with the
// losses as weights, and the minimisation of f over X by Gauss-Newton with step halving
// (ba/derivations.md 15.1): the inner minimisation of EliminatedPointReprojectionError.
// Fixed-size, no allocation.
//
// The cameras: x_cam = rotation[k] (X - center[k]) (rotation[0] = I, center[0] = 0 for camera 1).
// The observations: a callable observe(k, x_cam, &r, &d_r_d_x) with LinearizeObservation's
// contract (observation_jacobian.h) for view k's observation, so that each caller keeps its own
// storage of them. The loss: nullptr for the squared loss.
//
// Internal to the factors (factors/src, not installed): no installed header includes it.

#include <ceres/loss_function.h>

#include <Eigen/Core>
#include <cmath>

namespace trigrav {

// Gauss-Newton on the point stops when its decrement g^T H^-1 g (twice the predicted decrease of
// f) is below kPointRelativeDecrement f or kPointAbsoluteDecrement, or after kPointMaxIterations
// steps; a step that raises f is halved, at most kPointMaxHalvings times.
inline constexpr double kPointRelativeDecrement = 1e-12;
inline constexpr double kPointAbsoluteDecrement = 1e-24;
inline constexpr int kPointMaxIterations = 20;
inline constexpr int kPointMaxHalvings = 10;
// The damping mu = kPointDamping trace(H) of InvertDampedPointMatrix.
inline constexpr double kPointDamping = 1e-10;

// The triplet at one point: per view the residual, d r / d x_cam, x_cam and rho(s) (rho, rho',
// rho''); the cost f; h = sum rho' J_X^T J_X and g = sum rho' J_X^T r with J_X = d r / d x_cam R_k,
// the point's Gauss-Newton system with the losses as weights (reweighted least squares).
struct TripletLinearization {
  Eigen::Vector2d r[3];
  Eigen::Matrix<double, 2, 3> jr[3];
  Eigen::Vector3d x_cam[3];
  double rho[3][3];
  double cost = 0.0;
  Eigen::Matrix3d h;
  Eigen::Vector3d g;
};

// The linearisation at `point`; false if an observation cannot see it or a result is not finite.
template <typename Observe>
bool LinearizeTriplet(const Observe& observe,
                      const ceres::LossFunction* loss,
                      const Eigen::Matrix3d* rotation,
                      const Eigen::Vector3d* center,
                      const Eigen::Vector3d& point,
                      TripletLinearization* out) {
  out->cost = 0.0;
  out->h.setZero();
  out->g.setZero();
  for (int k = 0; k < 3; ++k) {
    out->x_cam[k] = rotation[k] * (point - center[k]);
    if (!observe(k, out->x_cam[k], &out->r[k], &out->jr[k])) return false;
    const double s = out->r[k].squaredNorm();
    double* rho = out->rho[k];
    if (loss == nullptr) {
      rho[0] = s;
      rho[1] = 1.0;
      rho[2] = 0.0;
    } else {
      loss->Evaluate(s, rho);
    }
    out->cost += 0.5 * rho[0];
    const Eigen::Matrix<double, 2, 3> jx = out->jr[k] * rotation[k];
    out->h.noalias() += rho[1] * jx.transpose() * jx;
    out->g.noalias() += rho[1] * jx.transpose() * out->r[k];
  }
  return std::isfinite(out->cost) && out->h.allFinite() && out->g.allFinite();
}

// (m + mu I)^-1 of a symmetric positive semi-definite 3 x 3 matrix by cofactors, with
// mu = kPointDamping trace(m): a point whose depth the observations hardly constrain (no parallax)
// has a nearly singular system, along a direction in which its cost hardly changes; the damping
// keeps the step (and the projection of section 15.3) finite there and leaves the others as they
// are. False if the damped matrix is not positive definite (Sylvester's criterion) or the inverse
// not finite.
inline bool InvertDampedPointMatrix(const Eigen::Matrix3d& undamped, Eigen::Matrix3d* inverse) {
  const Eigen::Matrix3d m =
      undamped + kPointDamping * undamped.trace() * Eigen::Matrix3d::Identity();
  const double c00 = m(1, 1) * m(2, 2) - m(1, 2) * m(1, 2);
  const double c01 = m(0, 2) * m(1, 2) - m(0, 1) * m(2, 2);
  const double c02 = m(0, 1) * m(1, 2) - m(0, 2) * m(1, 1);
  const double det = m(0, 0) * c00 + m(0, 1) * c01 + m(0, 2) * c02;
  if (!(m(0, 0) > 0.0) || !(m(0, 0) * m(1, 1) - m(0, 1) * m(0, 1) > 0.0) || !(det > 0.0)) {
    return false;
  }
  const double c11 = m(0, 0) * m(2, 2) - m(0, 2) * m(0, 2);
  const double c12 = m(0, 1) * m(0, 2) - m(0, 0) * m(1, 2);
  const double c22 = m(0, 0) * m(1, 1) - m(0, 1) * m(0, 1);
  *inverse << c00, c01, c02, c01, c11, c12, c02, c12, c22;
  *inverse /= det;
  return inverse->allFinite();
}

// Minimises f over the point from *point, where *lin is the linearisation (LinearizeTriplet): steps
// -(h + mu I)^-1 g, each halved until f does not rise; none is taken once the decrement is below
// the tolerances above, or when every halving raises f (the minimum to round-off). *point and *lin
// hold the last accepted point throughout, so f never rises. False if the damped system is not
// positive definite or the decrement not finite (*point and *lin as they were then).
template <typename Observe>
bool MinimizeTripletCost(const Observe& observe,
                         const ceres::LossFunction* loss,
                         const Eigen::Matrix3d* rotation,
                         const Eigen::Vector3d* center,
                         Eigen::Vector3d* point,
                         TripletLinearization* lin) {
  TripletLinearization trial;
  for (int iteration = 0; iteration < kPointMaxIterations; ++iteration) {
    Eigen::Matrix3d h_inverse;
    if (!InvertDampedPointMatrix(lin->h, &h_inverse)) return false;
    const Eigen::Vector3d step = -h_inverse * lin->g;
    const double decrement = -lin->g.dot(step);
    if (!std::isfinite(decrement)) return false;
    if (decrement <= kPointRelativeDecrement * lin->cost || decrement <= kPointAbsoluteDecrement) {
      break;
    }
    bool moved = false;
    double length = 1.0;
    for (int halving = 0; halving <= kPointMaxHalvings && !moved; ++halving, length *= 0.5) {
      const Eigen::Vector3d candidate = *point + length * step;
      if (LinearizeTriplet(observe, loss, rotation, center, candidate, &trial) &&
          trial.cost <= lin->cost) {
        *point = candidate;
        *lin = trial;
        moved = true;
      }
    }
    if (!moved) break;
  }
  return true;
}

}  // namespace trigrav

#endif  // TRIGRAV_FACTORS_SRC_POINT_GAUSS_NEWTON_H_
