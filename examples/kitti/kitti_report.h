#ifndef TRIGRAV_EXAMPLES_KITTI_KITTI_REPORT_H_
#define TRIGRAV_EXAMPLES_KITTI_KITTI_REPORT_H_

// Errors of every method's poses on KITTI triplets: per-triplet records, per-method summaries in
// the paper's format (median rotation and translation-direction errors of views 2 and 3 pooled,
// deg), the yaw / tilt split, run times, chained trajectories and their ATE; CSV writers.

#include <Eigen/Core>
#include <iosfwd>
#include <string>
#include <vector>

#include "kitti_methods.h"
#include "kitti_sequence.h"
#include "trigrav/evaluation/pose_errors.h"

namespace trigrav::kitti {

// One pose of one method on one triplet (f, f+1, f+2).
struct PoseRecord {
  int frame = 0;
  std::string method, stage;
  bool success = false;
  int num_tracks = 0, num_inliers = 0;  // inliers: the pose's own (MethodPose::ransac.num_inliers)
  double time_s = 0.0;
  ThreeViewPose pose;
  ThreeViewPoseErrors errors;  // views 2 and 3
  YawTiltErrorDeg split[2];    // views 2 and 3, about each camera's ground-truth gravity
  // Signed errors (estimate - truth) of the direction of the camera centres of views 2 and 3 in
  // camera 1's frame (x right, y down, z forward): azimuth atan2(x, z) and elevation
  // atan2(-y, |(x, z)|). Their medians expose a bias that a median angle alone hides.
  double azimuth_deg[2] = {0.0, 0.0};
  double elevation_deg[2] = {0.0, 0.0};
  std::string message;  // why not, when !success
  FailureCause cause = FailureCause::kNone;
  double msac_cost = 0.0;      // of the RANSAC winner
  ConsensusEvidence evidence;  // of the RANSAC winner (robust_three_view.h)
  GravityConsistency gravity;  // the gravity-free comparison (robust_three_view.h)
};

// A gross error: translation direction of view 2 or 3 off by more than this (or no pose).
inline constexpr double kGrossTranslationErrorDeg = 10.0;

// Errors of a method's pose against the triplet's ground truth; gravity_in_cam2 / 3: exact
// (ground-truth) gravity of views 2 and 3 for the yaw / tilt split.
PoseRecord EvaluatePose(int frame,
                        const std::string& method,
                        const MethodPose& pose,
                        int num_tracks,
                        const ThreeViewPose& ground_truth,
                        const Eigen::Vector3d& gravity_in_cam2,
                        const Eigen::Vector3d& gravity_in_cam3);

// A method's poses chained into a trajectory (trigrav/evaluation/trajectory.h) and its ATE.
struct TrajectoryResult {
  std::vector<Eigen::Vector3d> aligned_centers;  // per frame of the range, ground-truth world
  std::vector<double> error_m;                   // per frame, after alignment
  double ate_rmse_m = 0.0;
};

struct MethodSummary {
  std::string method, stage;
  int num_triplets = 0, num_failures = 0;
  int num_gross = 0;  // failures and triplets with a gross error
  // Medians over the successful triplets, views 2 and 3 pooled (deg); relative scale |log|.
  double rotation_deg = 0.0, translation_deg = 0.0, yaw_deg = 0.0, tilt_deg = 0.0;
  double azimuth_deg = 0.0, elevation_deg = 0.0;  // signed
  double relative_scale = 0.0;
  double median_inliers = 0.0, median_tracks = 0.0;
  double mean_time_ms = 0.0;  // per triplet
  TrajectoryResult trajectory;
};

// One summary per (method, stage) in order of first appearance; records hold every triplet of the
// range for each (method, stage), in frame order.
std::vector<MethodSummary> Summarize(const KittiSequence& sequence,
                                     const std::vector<PoseRecord>& records);

enum class TableFormat { kText, kMarkdown };

// One row per summary: medians (rotation, translation, yaw, tilt, signed azimuth / elevation, deg;
// |log s|), failures, gross errors, inliers, mean time per triplet (ms) and ATE (m); fixed-width
// text or a markdown table.
void PrintSummaryTable(const std::vector<MethodSummary>& summaries,
                       std::ostream& out,
                       TableFormat format = TableFormat::kText);

// The verdict's counts per method and stage: successes, and failures by cause (FailureCause),
// "method stage: N successes; cause M, ...".
void PrintVerdictCounts(const std::vector<PoseRecord>& records, std::ostream& out);

// Ratios row / column of mean time per triplet, median rotation error and median translation error
// ("time / rotation / translation"; below 1: the row is faster or more accurate), one row per
// `rows` entry (e.g. trigrav's methods and stages) and one column per `columns` entry (e.g. the
// peers).
void PrintRatioTable(const std::vector<const MethodSummary*>& rows,
                     const std::vector<const MethodSummary*>& columns,
                     std::ostream& out,
                     TableFormat format = TableFormat::kText);

// CSVs (header row, comma-separated); false if the file cannot be written.
bool WritePoseRecordsCsv(const std::string& path, const std::vector<PoseRecord>& records);
bool WriteSummaryCsv(const std::string& path, const std::vector<MethodSummary>& summaries);
// Rows method,stage,frame,x,y,z,gt_x,gt_y,gt_z,error_m: aligned estimated and ground-truth camera
// centres in the world frame (m).
bool WriteTrajectoriesCsv(const std::string& path,
                          const KittiSequence& sequence,
                          const std::vector<MethodSummary>& summaries);

}  // namespace trigrav::kitti

#endif  // TRIGRAV_EXAMPLES_KITTI_KITTI_REPORT_H_
