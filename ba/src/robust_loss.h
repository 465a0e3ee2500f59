#ifndef TRIGRAV_BA_SRC_ROBUST_LOSS_H_
#define TRIGRAV_BA_SRC_ROBUST_LOSS_H_

// The robust loss of ThreeViewBundleAdjustmentOptions::loss, one definition for both engines: the
// Ceres problem's residual blocks and the dedicated engine (ba/derivations.md section 13.2).

#include <ceres/loss_function.h>

#include "trigrav/ba/three_view_bundle_adjustment.h"

namespace trigrav {
namespace internal {

// New loss of the given type and scale; nullptr for kNone (Ceres' convention for no loss).
inline ceres::LossFunction* MakeLoss(ThreeViewBundleAdjustmentOptions::LossType loss,
                                     double scale) {
  using LossType = ThreeViewBundleAdjustmentOptions::LossType;
  switch (loss) {
    case LossType::kNone:
      return nullptr;
    case LossType::kHuber:
      return new ceres::HuberLoss(scale);
    case LossType::kCauchy:
      return new ceres::CauchyLoss(scale);
  }
  return nullptr;
}

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_BA_SRC_ROBUST_LOSS_H_
