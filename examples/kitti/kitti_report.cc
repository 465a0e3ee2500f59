#include "kitti_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <ostream>
#include <utility>

#include "trigrav/evaluation/statistics.h"
#include "trigrav/evaluation/trajectory.h"

namespace trigrav::kitti {
namespace {

TrajectoryResult EvaluateTrajectory(const KittiSequence& sequence,
                                    const std::vector<const PoseRecord*>& triplets) {
  std::vector<ThreeViewPose> poses;
  std::vector<char> valid;
  for (const PoseRecord* record : triplets) {
    poses.push_back(record->pose);
    valid.push_back(record->success ? 1 : 0);
  }
  const TrajectorySteps steps = StepsFromTriplets(poses, valid);
  std::vector<double> step_lengths;
  std::vector<Eigen::Vector3d> ground_truth_centers;
  for (int frame = sequence.first_frame; frame <= sequence.last_frame; ++frame) {
    ground_truth_centers.push_back(sequence.CamFromWorld(frame).Center());
    if (frame > sequence.first_frame) {
      step_lengths.push_back(
          (ground_truth_centers.back() - ground_truth_centers[ground_truth_centers.size() - 2])
              .norm());
    }
  }
  const std::vector<CameraPose> chained =
      ChainTrajectory(sequence.CamFromWorld(sequence.first_frame), steps, step_lengths);
  std::vector<Eigen::Vector3d> centers;
  for (const CameraPose& pose : chained) centers.push_back(pose.Center());
  const AbsoluteTrajectoryError ate = ComputeAbsoluteTrajectoryError(centers, ground_truth_centers);
  return {ate.aligned_centers, ate.error_m, ate.rmse_m};
}

constexpr double kRadToDeg = 180.0 / M_PI;

std::string Number(const char* format, double value) {
  char text[32];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

// rows[0] is the header. Text: columns separated by one space, each as wide as its widest cell,
// the first `left_aligned_columns` left-aligned and the others right-aligned. Markdown: '|'
// between the cells and a separator row after the header.
void PrintTable(const std::vector<std::vector<std::string>>& rows,
                std::size_t left_aligned_columns,
                TableFormat format,
                std::ostream& out) {
  std::vector<std::size_t> widths;
  for (const std::vector<std::string>& row : rows) {
    widths.resize(std::max(widths.size(), row.size()), 0);
    for (std::size_t c = 0; c < row.size(); ++c) widths[c] = std::max(widths[c], row[c].size());
  }
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (std::size_t c = 0; c < rows[r].size(); ++c) {
      const std::string& cell = rows[r][c];
      if (format == TableFormat::kMarkdown) {
        out << (c == 0 ? "| " : " | ") << cell;
        continue;
      }
      const std::string padding(widths[c] - cell.size(), ' ');
      out << (c == 0 ? "" : " ") << (c < left_aligned_columns ? cell + padding : padding + cell);
    }
    out << (format == TableFormat::kMarkdown ? " |\n" : "\n");
    if (format == TableFormat::kMarkdown && r == 0) {
      out << "|";
      for (std::size_t c = 0; c < rows[0].size(); ++c) out << "---|";
      out << "\n";
    }
  }
}

double AzimuthDeg(const Eigen::Vector3d& d) { return std::atan2(d.x(), d.z()) * kRadToDeg; }
double ElevationDeg(const Eigen::Vector3d& d) {
  return std::atan2(-d.y(), std::hypot(d.x(), d.z())) * kRadToDeg;
}

}  // namespace

PoseRecord EvaluatePose(int frame,
                        const std::string& method,
                        const MethodPose& pose,
                        int num_tracks,
                        const ThreeViewPose& ground_truth,
                        const Eigen::Vector3d& gravity_in_cam2,
                        const Eigen::Vector3d& gravity_in_cam3) {
  PoseRecord record;
  record.frame = frame;
  record.method = method;
  record.stage = pose.stage;
  record.success = pose.success && pose.pose.IsFinite();
  record.num_tracks = num_tracks;
  record.num_inliers = pose.ransac.num_inliers;
  record.time_s = pose.time_s;
  record.pose = pose.pose;
  record.message = pose.message;
  record.cause = pose.cause;
  record.msac_cost = pose.ransac.msac_cost;
  record.evidence = pose.evidence;
  record.gravity = pose.gravity;
  if (!record.success) return record;
  record.errors = ComputeThreeViewPoseErrors(ground_truth, pose.pose);
  if (!pose.relative_scale_known) {
    record.errors.relative_scale = std::numeric_limits<double>::infinity();
  }
  record.split[0] = SplitRotationErrorDeg(ground_truth.cam2_from_cam1.R, pose.pose.cam2_from_cam1.R,
                                          gravity_in_cam2);
  record.split[1] = SplitRotationErrorDeg(ground_truth.cam3_from_cam1.R, pose.pose.cam3_from_cam1.R,
                                          gravity_in_cam3);
  const CameraPose* truth[2] = {&ground_truth.cam2_from_cam1, &ground_truth.cam3_from_cam1};
  const CameraPose* estimate[2] = {&pose.pose.cam2_from_cam1, &pose.pose.cam3_from_cam1};
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector3d c_gt = truth[k]->Center(), c = estimate[k]->Center();
    // Wrapped into (-180, 180].
    record.azimuth_deg[k] = std::remainder(AzimuthDeg(c) - AzimuthDeg(c_gt), 360.0);
    record.elevation_deg[k] = ElevationDeg(c) - ElevationDeg(c_gt);
  }
  return record;
}

std::vector<MethodSummary> Summarize(const KittiSequence& sequence,
                                     const std::vector<PoseRecord>& records) {
  std::vector<std::pair<std::string, std::string>> order;
  std::map<std::pair<std::string, std::string>, std::vector<const PoseRecord*>> groups;
  for (const PoseRecord& record : records) {
    const auto key = std::make_pair(record.method, record.stage);
    if (groups.find(key) == groups.end()) order.push_back(key);
    groups[key].push_back(&record);
  }
  std::vector<MethodSummary> summaries;
  for (const auto& key : order) {
    std::vector<const PoseRecord*>& group = groups[key];
    std::sort(group.begin(), group.end(),
              [](const PoseRecord* a, const PoseRecord* b) { return a->frame < b->frame; });
    MethodSummary summary;
    summary.method = key.first;
    summary.stage = key.second;
    summary.num_triplets = static_cast<int>(group.size());
    std::vector<double> rotation, translation, yaw, tilt, azimuth, elevation, scale, inliers,
        tracks;
    double time_s = 0.0;
    for (const PoseRecord* record : group) {
      time_s += record->time_s;
      tracks.push_back(record->num_tracks);
      if (!record->success) {
        ++summary.num_failures;
        ++summary.num_gross;
        continue;
      }
      if (record->errors.MaxTranslationDeg() > kGrossTranslationErrorDeg) ++summary.num_gross;
      for (int k = 0; k < 2; ++k) {
        rotation.push_back(record->errors.rotation_deg[k]);
        translation.push_back(record->errors.translation_deg[k]);
        yaw.push_back(record->split[k].yaw_deg);
        tilt.push_back(record->split[k].tilt_deg);
        azimuth.push_back(record->azimuth_deg[k]);
        elevation.push_back(record->elevation_deg[k]);
      }
      scale.push_back(record->errors.relative_scale);
      inliers.push_back(record->num_inliers);
    }
    summary.rotation_deg = Median(rotation);
    summary.translation_deg = Median(translation);
    summary.yaw_deg = Median(yaw);
    summary.tilt_deg = Median(tilt);
    summary.azimuth_deg = Median(azimuth);
    summary.elevation_deg = Median(elevation);
    summary.relative_scale = Median(scale);
    summary.median_inliers = Median(inliers);
    summary.median_tracks = Median(tracks);
    summary.mean_time_ms = group.empty() ? 0.0 : 1e3 * time_s / group.size();
    summary.trajectory = EvaluateTrajectory(sequence, group);
    summaries.push_back(std::move(summary));
  }
  return summaries;
}

void PrintVerdictCounts(const std::vector<PoseRecord>& records, std::ostream& out) {
  // Keys in the order of first appearance (methods and stages as the records list them).
  std::vector<std::pair<std::string, std::map<FailureCause, int>>> counts;
  for (const PoseRecord& r : records) {
    const std::string key = r.method + " " + r.stage;
    auto it = std::find_if(counts.begin(), counts.end(),
                           [&](const auto& entry) { return entry.first == key; });
    if (it == counts.end()) it = counts.insert(counts.end(), {key, {}});
    ++it->second[r.success ? FailureCause::kNone : r.cause];
  }
  for (const auto& [key, by_cause] : counts) {
    out << key << ": "
        << (by_cause.count(FailureCause::kNone) ? by_cause.at(FailureCause::kNone) : 0)
        << " successes";
    for (const auto& [cause, count] : by_cause) {
      if (cause != FailureCause::kNone) out << "; " << FailureCauseName(cause) << " " << count;
    }
    out << '\n';
  }
}

void PrintSummaryTable(const std::vector<MethodSummary>& summaries,
                       std::ostream& out,
                       TableFormat format) {
  std::vector<std::vector<std::string>> rows = {{"method", "stage", "rot", "trans", "yaw", "tilt",
                                                 "azim", "elev", "|log s|", "fail", "gross",
                                                 "inliers", "ms/trip", "ATE m"}};
  for (const MethodSummary& s : summaries) {
    rows.push_back({s.method, s.stage, Number("%.4f", s.rotation_deg),
                    Number("%.3f", s.translation_deg), Number("%.4f", s.yaw_deg),
                    Number("%.4f", s.tilt_deg), Number("%.3f", s.azimuth_deg),
                    Number("%.3f", s.elevation_deg), Number("%.4f", s.relative_scale),
                    std::to_string(s.num_failures), std::to_string(s.num_gross),
                    Number("%.0f", s.median_inliers), Number("%.2f", s.mean_time_ms),
                    Number("%.3f", s.trajectory.ate_rmse_m)});
  }
  PrintTable(rows, /*left_aligned_columns=*/2, format, out);
}

void PrintRatioTable(const std::vector<const MethodSummary*>& rows,
                     const std::vector<const MethodSummary*>& columns,
                     std::ostream& out,
                     TableFormat format) {
  std::vector<std::vector<std::string>> cells = {{"time / rot / trans"}};
  for (const MethodSummary* column : columns) {
    cells[0].push_back(column->method + " " + column->stage);
  }
  for (const MethodSummary* row : rows) {
    cells.push_back({row->method + " " + row->stage});
    for (const MethodSummary* column : columns) {
      char cell[64];
      std::snprintf(
          cell, sizeof(cell), "%.2f / %.2f / %.2f", row->mean_time_ms / column->mean_time_ms,
          row->rotation_deg / column->rotation_deg, row->translation_deg / column->translation_deg);
      cells.back().push_back(cell);
    }
  }
  PrintTable(cells, /*left_aligned_columns=*/1, format, out);
}

bool WritePoseRecordsCsv(const std::string& path, const std::vector<PoseRecord>& records) {
  std::ofstream file(path);
  file << "frame,method,stage,success,tracks,inliers,rot2_deg,rot3_deg,yaw2_deg,yaw3_deg,"
          "tilt2_deg,tilt3_deg,trans2_deg,trans3_deg,azimuth2_deg,azimuth3_deg,elevation2_deg,"
          "elevation3_deg,log_scale_error,time_ms,log10_nfa,rotation_sigma_deg,"
          "direction_sigma_deg,gravity_free_inliers,free_rotation_disagreement_deg,"
          "free_direction_disagreement_deg,msac_cost,message\n";
  char line[640];
  for (const PoseRecord& r : records) {
    std::snprintf(
        line, sizeof(line),
        "%d,%s,%s,%d,%d,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,"
        "%.6g,%.4g,%.4g,%.4g,%.4g,%d,%.4g,%.4g,%.6g,",
        r.frame, r.method.c_str(), r.stage.c_str(), r.success ? 1 : 0, r.num_tracks, r.num_inliers,
        r.errors.rotation_deg[0], r.errors.rotation_deg[1], r.split[0].yaw_deg, r.split[1].yaw_deg,
        r.split[0].tilt_deg, r.split[1].tilt_deg, r.errors.translation_deg[0],
        r.errors.translation_deg[1], r.azimuth_deg[0], r.azimuth_deg[1], r.elevation_deg[0],
        r.elevation_deg[1], r.errors.relative_scale, 1e3 * r.time_s, r.evidence.log10_nfa,
        r.evidence.rotation_sigma_deg, r.evidence.direction_sigma_deg,
        r.gravity.measured ? r.gravity.num_inliers : -1,
        std::max(r.gravity.rotation_disagreement_deg[0], r.gravity.rotation_disagreement_deg[1]),
        std::max(r.gravity.direction_disagreement_deg[0], r.gravity.direction_disagreement_deg[1]),
        r.msac_cost);
    // The message as a quoted CSV field, its quotes doubled.
    std::string message;
    for (const char c : r.message) message += c == '"' ? std::string("\"\"") : std::string(1, c);
    file << line << '"' << message << "\"\n";
  }
  return static_cast<bool>(file);
}

bool WriteSummaryCsv(const std::string& path, const std::vector<MethodSummary>& summaries) {
  std::ofstream file(path);
  file << "method,stage,triplets,failures,gross,median_rot_deg,median_trans_deg,median_yaw_deg,"
          "median_tilt_deg,median_azimuth_deg,median_elevation_deg,median_log_scale_error,"
          "median_inliers,median_tracks,mean_time_ms,ate_rmse_m\n";
  char line[512];
  for (const MethodSummary& s : summaries) {
    std::snprintf(line, sizeof(line),
                  "%s,%s,%d,%d,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.1f,%.1f,%.4g,%.6g\n",
                  s.method.c_str(), s.stage.c_str(), s.num_triplets, s.num_failures, s.num_gross,
                  s.rotation_deg, s.translation_deg, s.yaw_deg, s.tilt_deg, s.azimuth_deg,
                  s.elevation_deg, s.relative_scale, s.median_inliers, s.median_tracks,
                  s.mean_time_ms, s.trajectory.ate_rmse_m);
    file << line;
  }
  return static_cast<bool>(file);
}

bool WriteTrajectoriesCsv(const std::string& path,
                          const KittiSequence& sequence,
                          const std::vector<MethodSummary>& summaries) {
  std::ofstream file(path);
  file << "method,stage,frame,x,y,z,gt_x,gt_y,gt_z,error_m\n";
  char line[512];
  for (const MethodSummary& s : summaries) {
    for (std::size_t i = 0; i < s.trajectory.aligned_centers.size(); ++i) {
      const int frame = sequence.first_frame + static_cast<int>(i);
      const Eigen::Vector3d& c = s.trajectory.aligned_centers[i];
      const Eigen::Vector3d gt = sequence.CamFromWorld(frame).Center();
      std::snprintf(line, sizeof(line), "%s,%s,%d,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f\n",
                    s.method.c_str(), s.stage.c_str(), frame, c.x(), c.y(), c.z(), gt.x(), gt.y(),
                    gt.z(), s.trajectory.error_m[i]);
      file << line;
    }
  }
  return static_cast<bool>(file);
}

}  // namespace trigrav::kitti
