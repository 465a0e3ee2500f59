#include "observation_jacobian.h"

#include <ceres/jet.h>

namespace trigrav {

bool LinearizeObservationByJets(const PixelResidual& residual,
                                const Eigen::Vector3d& x_cam,
                                Eigen::Vector2d* r,
                                Eigen::Matrix<double, 2, 3>* d_r_d_x) {
  using Jet = ceres::Jet<double, 3>;
  const Jet x_jet[3] = {Jet(x_cam[0], 0), Jet(x_cam[1], 1), Jet(x_cam[2], 2)};
  Jet r_jet[2];
  if (!residual(x_jet, r_jet)) return false;
  for (int i = 0; i < 2; ++i) {
    (*r)[i] = r_jet[i].a;
    d_r_d_x->row(i) = r_jet[i].v.transpose();
  }
  return r->allFinite() && d_r_d_x->allFinite();
}

}  // namespace trigrav
