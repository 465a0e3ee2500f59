#ifndef TRIGRAV_EXAMPLES_COMMON_POOLED_ERRORS_H_
#define TRIGRAV_EXAMPLES_COMMON_POOLED_ERRORS_H_

// Errors of many three-view estimates against their ground truth with views 2 and 3 pooled (the
// paper's convention, derivations.md section 8.4): per estimate two rotation and two
// translation-direction errors in degrees and one relative-scale error |log(s_est / s_gt)|
// (pose_errors.h). The accumulator of the example tools' accuracy tables (header only; a failure
// counted as 180 deg is their convention), not part of the installed library.

#include <limits>
#include <vector>

#include "trigrav/evaluation/pose_errors.h"

namespace trigrav {

struct PooledErrors {
  std::vector<double> rotation_deg, translation_deg;  // two per estimate: views 2 and 3
  std::vector<double> relative_scale;                 // one per estimate

  void Add(const ThreeViewPoseErrors& e) {
    for (int k = 0; k < 2; ++k) {
      rotation_deg.push_back(e.rotation_deg[k]);
      translation_deg.push_back(e.translation_deg[k]);
    }
    relative_scale.push_back(e.relative_scale);
  }

  // A failed estimate, for tables that count a failure as an error: 180 deg, scale error +inf.
  void AddFailure() {
    ThreeViewPoseErrors failure;
    failure.rotation_deg[0] = failure.rotation_deg[1] = 180.0;
    failure.translation_deg[0] = failure.translation_deg[1] = 180.0;
    failure.relative_scale = std::numeric_limits<double>::infinity();
    Add(failure);
  }

  void Append(const PooledErrors& other) {
    rotation_deg.insert(rotation_deg.end(), other.rotation_deg.begin(), other.rotation_deg.end());
    translation_deg.insert(translation_deg.end(), other.translation_deg.begin(),
                           other.translation_deg.end());
    relative_scale.insert(relative_scale.end(), other.relative_scale.begin(),
                          other.relative_scale.end());
  }
};

}  // namespace trigrav

#endif  // TRIGRAV_EXAMPLES_COMMON_POOLED_ERRORS_H_
