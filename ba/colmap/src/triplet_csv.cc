#include "trigrav/colmap/triplet_csv.h"

#include <Eigen/Geometry>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "trigrav/ba/three_view_covariance.h"

namespace trigrav {
namespace colmap {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

// Column names and their meaning, in order.
constexpr std::array<std::array<const char*, 2>, 39> kColumns = {{
    {"image_name1", "name of image 1 (the reference: camera 1 is the triplet's frame)"},
    {"image_name2", "name of image 2"},
    {"image_name3", "name of image 3"},
    {"image_id1", "database image id of image 1"},
    {"image_id2", "database image id of image 2"},
    {"image_id3", "database image id of image 3"},
    {"num_tracks", "three-view tracks chained from the verified pair matches"},
    {"verdict", "trusted | too_few_tracks | failed | unrefined | no_covariance"},
    {"success", "1 when InitializeAndRefine found a pose"},
    {"num_inliers", "inlier tracks of the answer"},
    {"ransac_inliers", "inliers of the RANSAC winner"},
    {"ransac_iterations", "RANSAC samples drawn"},
    {"qw2", "cam2_from_cam1 rotation as a unit quaternion (w x y z, COLMAP's order)"},
    {"qx2", ""},
    {"qy2", ""},
    {"qz2", ""},
    {"tx2", "cam2_from_cam1 translation (x_cam2 = R x_cam1 + t), |C2| = 1"},
    {"ty2", ""},
    {"tz2", ""},
    {"qw3", "cam3_from_cam1 rotation (w x y z)"},
    {"qx3", ""},
    {"qy3", ""},
    {"qz3", ""},
    {"tx3", "cam3_from_cam1 translation, same scale"},
    {"ty3", ""},
    {"tz3", ""},
    {"relative_scale", "|C3| / |C2|"},
    {"refined", "1 when the bundle adjustment succeeded (else the pose is RANSAC's)"},
    {"residual_rms_px", "RMS of the refined reprojection residuals"},
    {"gravity_checked", "1 when a gravity-free estimate was compared with the gravity"},
    {"gravity_angle12_deg",
     "angle(R2 g1, g2), (1,3), (2,3) likewise: what the images say about the gravity"},
    {"gravity_angle13_deg", ""},
    {"gravity_angle23_deg", ""},
    {"inconsistent_camera", "camera (1-3) whose gravity the images contradict; 0 none"},
    {"sigma_rotation2_deg",
     "standard deviation of camera 2's rotation (yaw-only: of the yaw; gravity prior: sqrt of "
     "the trace of its 3x3 block), camera 3 likewise; empty without covariance"},
    {"sigma_rotation3_deg", ""},
    {"sigma_center2",
     "sqrt of the trace of the covariance of C2 (2 dof on |C2| = 1), in units of |C2|"},
    {"sigma_center3", "the same for C3 (3 dof)"},
    {"covariance",
     "the full covariance (7x7 yaw-only, 11x11 gravity prior, three_view_covariance.h), row-major, "
     "space separated"},
}};

// A CSV field: quoted, with quotes doubled, when it holds a comma, quote or newline.
std::string Quoted(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) {
    quoted += c;
    if (c == '"') quoted += '"';
  }
  return quoted + "\"";
}

void WritePose(const CameraPose& pose, std::ostream* out) {
  const Eigen::Quaterniond q(pose.R);
  *out << ',' << q.w() << ',' << q.x() << ',' << q.y() << ',' << q.z() << ',' << pose.t.x() << ','
       << pose.t.y() << ',' << pose.t.z();
}

void WriteCovariance(const Eigen::MatrixXd& covariance,
                     const ThreeViewCovarianceLayout& layout,
                     std::ostream* out) {
  if (covariance.rows() != layout.Size()) {
    *out << ",,,,,";
    return;
  }
  const auto root_trace = [&covariance](int first, int size) {
    return std::sqrt(covariance.block(first, first, size, size).trace());
  };
  *out << ',' << kRadToDeg * root_trace(layout.Rotation(2), layout.rotation_size) << ','
       << kRadToDeg * root_trace(layout.Rotation(3), layout.rotation_size) << ','
       << root_trace(layout.Center2(), 2) << ',' << root_trace(layout.Center3(), 3) << ',';
  for (int i = 0; i < covariance.size(); ++i) {
    *out << (i > 0 ? " " : "") << covariance(i / covariance.cols(), i % covariance.cols());
  }
}

}  // namespace

std::string TripletVerdict(const TripletResult& result) {
  if (!result.estimated) return "too_few_tracks";
  if (!result.estimate.success) return "failed";
  if (!result.estimate.refinement.summary.success) return "unrefined";
  if (result.estimate.refinement.covariance.size() == 0) return "no_covariance";
  return "trusted";
}

std::string FormatTripletCsv(const std::vector<TripletResult>& results,
                             ThreeViewBundleAdjustmentOptions::RotationModel rotation_model) {
  std::ostringstream out;
  out << std::setprecision(17);
  out << "# trigrav triplet_initializer: one row per triplet; columns:\n";
  for (const auto& [name, meaning] : kColumns) {
    if (*meaning != '\0') out << "#   " << name << ": " << meaning << "\n";
  }
  out << "#   message: why not, or a note (last column)\n";
  for (const auto& [name, meaning] : kColumns) out << name << ',';
  out << "message\n";
  const ThreeViewCovarianceLayout layout = ThreeViewCovarianceLayout::For(rotation_model);
  for (const TripletResult& result : results) {
    const ThreeViewEstimate& estimate = result.estimate;
    for (const DatabaseImage& image : result.images) out << Quoted(image.name) << ',';
    for (const DatabaseImage& image : result.images) out << image.image_id << ',';
    out << result.num_tracks << ',' << TripletVerdict(result) << ',' << estimate.success << ','
        << estimate.num_inliers << ',' << estimate.robust.ransac.num_inliers << ','
        << estimate.robust.ransac.iterations;
    WritePose(estimate.refined.cam2_from_cam1, &out);
    WritePose(estimate.refined.cam3_from_cam1, &out);
    const double c2 = estimate.refined.cam2_from_cam1.Center().norm();
    out << ',' << (c2 > 0.0 ? estimate.refined.cam3_from_cam1.Center().norm() / c2 : 0.0) << ','
        << estimate.refinement.summary.success << ',' << estimate.refinement.residual_rms << ','
        << estimate.robust.gravity.measured;
    for (const double angle : estimate.robust.gravity.pair_inconsistency_deg) out << ',' << angle;
    out << ',' << estimate.robust.gravity.inconsistent_camera;
    WriteCovariance(estimate.refinement.covariance, layout, &out);
    out << ',' << Quoted(estimate.message) << '\n';
  }
  return out.str();
}

}  // namespace colmap
}  // namespace trigrav
