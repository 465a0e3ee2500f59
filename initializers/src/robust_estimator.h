#ifndef TRIGRAV_INITIALIZERS_SRC_ROBUST_ESTIMATOR_H_
#define TRIGRAV_INITIALIZERS_SRC_ROBUST_ESTIMATOR_H_

// One method as the RANSAC estimator concept of ransac.h, and the RANSAC run that turns its report
// into a RobustThreeViewEstimate.

#include <array>
#include <cstddef>
#include <vector>

#include "robust_triplet_data.h"
#include "trigrav/initializers/ransac.h"
#include "trigrav/initializers/robust_three_view.h"
#include "trigrav/initializers/three_view_error.h"

namespace trigrav {
namespace internal {

struct ScoredPose {
  ThreeViewPose pose;
  ThreeViewReprojectionError::PreparedPose prepared;
};

// The RANSAC estimator concept of ransac.h for one method.
template <typename M>
class Estimator {
 public:
  using Model = ScoredPose;
  static constexpr int kSampleSize = M::kSampleSize;

  explicit Estimator(const TripletData& data) : data_(data) {}

  std::size_t num_data() const { return data_.error.size(); }

  void generate_models(const std::array<int, kSampleSize>& sample,
                       std::vector<Model>* models) const {
    Solve(sample, &M::Minimal);
    for (const ThreeViewPose& pose : poses_) {
      if (pose.IsFinite()) models->push_back({pose, ThreeViewReprojectionError::Prepare(pose)});
    }
  }

  void errors(
      const Model& model, std::size_t begin, std::size_t end, double cap, double* errors) const {
    data_.error.Errors(model.prepared, begin, end, cap, errors);
  }

  bool refine_model(const std::vector<int>& inliers, Model* model) const {
    if (static_cast<int>(inliers.size()) < M::kMinTripletsToRefine) return false;
    Solve(inliers, &M::Refine);
    for (const ThreeViewPose& pose : poses_) {
      if (pose.IsFinite()) {
        *model = {pose, ThreeViewReprojectionError::Prepare(pose)};
        return true;
      }
    }
    return false;
  }

 private:
  template <typename Indices>
  void Solve(const Indices& indices, SolveFunction solve) const {
    const ViewRays& source = M::kAligned ? data_.aligned : data_.raw;
    for (int k = 0; k < 3; ++k) {
      selected_[k].clear();
      for (const int i : indices) selected_[k].push_back(source[k][i]);
    }
    poses_.clear();
    solve(data_, selected_, &work_, &poses_);
  }

  const TripletData& data_;
  // Scratch storage reused across samples; an Estimator serves one RANSAC call on one thread.
  mutable ViewRays selected_;
  mutable Workspace work_;
  mutable std::vector<ThreeViewPose> poses_;
};

template <typename M>
RobustThreeViewEstimate Run(const TripletData& data, const RansacOptions& options) {
  const RansacReport<ScoredPose> report = Ransac(Estimator<M>(data), options);
  RobustThreeViewEstimate estimate;
  estimate.success = report.success;
  estimate.message = report.message;
  estimate.ransac = report.statistics;
  if (report.success) {
    estimate.pose = report.model.pose;
    estimate.inliers = report.inlier_mask;
  }
  return estimate;
}

}  // namespace internal
}  // namespace trigrav

#endif  // TRIGRAV_INITIALIZERS_SRC_ROBUST_ESTIMATOR_H_
