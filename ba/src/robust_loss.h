#ifndef TRIGRAV_BA_SRC_ROBUST_LOSS_H_
#define TRIGRAV_BA_SRC_ROBUST_LOSS_H_

// The robust loss of the bundle adjusters' options (ThreeViewBundleAdjustmentOptions::loss,
// NViewBundleAdjustmentOptions::loss) as a Ceres loss function, one definition for all problems.

#include <ceres/loss_function.h>

#include "trigrav/ba/bundle_adjustment_options.h"

namespace trigrav {
namespace internal {

// New loss of the given type and scale; nullptr for kNone (Ceres' convention for no loss).
inline ceres::LossFunction* MakeLoss(BundleAdjustmentOptions::LossType loss, double scale) {
  using LossType = BundleAdjustmentOptions::LossType;
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
