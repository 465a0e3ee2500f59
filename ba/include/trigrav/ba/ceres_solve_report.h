#ifndef TRIGRAV_BA_CERES_SOLVE_REPORT_H_
#define TRIGRAV_BA_CERES_SOLVE_REPORT_H_

// The Ceres report of one bundle adjustment and its accessors, shared by the summaries of the
// three-view and the N-view adjusters (ThreeViewBundleAdjustmentSummary,
// NViewBundleAdjustmentSummary derive from it).

#include <ceres/solver.h>

#include <string>

namespace trigrav {

struct CeresSolveReport {
  // The full report of ceres::Solve (costs 1/2 sum rho(|r|^2), steps, termination, timings).
  ceres::Solver::Summary ceres_summary;

  double InitialCost() const { return ceres_summary.initial_cost; }
  double FinalCost() const { return ceres_summary.final_cost; }
  // Successful + unsuccessful steps (iteration 0 counts as a successful one, as in Ceres).
  int Iterations() const {
    return ceres_summary.num_successful_steps + ceres_summary.num_unsuccessful_steps;
  }
  std::string BriefReport() const { return ceres_summary.BriefReport(); }
};

}  // namespace trigrav

#endif  // TRIGRAV_BA_CERES_SOLVE_REPORT_H_
