// Gravity-aware bundle adjustment of a COLMAP sparse model: reads the model and each image's
// gravity, refines every pose and point with trigrav's N-view bundle adjustment
// (trigrav/ba/nview_bundle_adjustment.h; intrinsics constant), writes the model back.
//
//   gravity_bundle_adjuster --input_path=sparse/0 --gravity_csv=g.csv --output_path=refined
//
// Nothing is written unless the refinement succeeds: an image without gravity, a bad model, a
// failed solve or an unwritable --covariance_csv leave --output_path and --covariance_csv
// untouched. README.md describes the flags.

#include <gflags/gflags.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/output_paths.h"
#include "common/require_flag.h"
#include "staged_file.h"
#include "trigrav/ba/nview_bundle_adjustment.h"
#include "trigrav/colmap/gravity_csv.h"
#include "trigrav/colmap/model_io.h"
#include "trigrav/colmap/nview_conversion.h"

DEFINE_string(input_path, "", "COLMAP sparse model folder, binary or text (required).");
DEFINE_string(gravity_csv,
              "",
              "Gravity per image (trigrav/colmap/gravity_csv.h); every image of the model needs "
              "one (required).");
DEFINE_string(output_path,
              "",
              "Folder (created, or replaced as a whole when it holds a model only) for the "
              "refined model (required).");
DEFINE_string(output_format, "binary", "Format of the written model: binary or text.");
DEFINE_string(rotation_model,
              "gravity_prior",
              "yaw_only: each image's pitch and roll exactly as its gravity says, one yaw each; "
              "gravity_prior: free rotations with a gravity prior of --gravity_sigma_deg.");
DEFINE_double(gravity_sigma_deg, 0.1, "IMU gravity sigma (deg) of the gravity-prior model.");
DEFINE_string(loss, "huber", "Robust loss on the reprojection errors: huber, cauchy or none.");
DEFINE_double(loss_scale_px, 2.0, "Scale (px) of the robust loss.");
DEFINE_double(pixel_sigma_px,
              1.0,
              "Pixel noise (px) weighting the gravity prior and scaling the covariances.");
DEFINE_int32(max_iterations, 100, "Ceres iterations at most.");
DEFINE_int32(threads, 2, "Ceres threads.");
DEFINE_string(covariance_csv,
              "",
              "If set, also compute every image's pose covariance and write it there (one row per "
              "image).");

namespace {

namespace fs = std::filesystem;
namespace colmap = trigrav::colmap;
namespace tools = trigrav::colmap_tools;
using trigrav::examples::RequireFlag;
using Options = trigrav::NViewBundleAdjustmentOptions;

void CheckFlags() {
  RequireFlag(!FLAGS_input_path.empty(), "--input_path is required");
  RequireFlag(fs::is_directory(FLAGS_input_path),
              "--input_path=" + FLAGS_input_path + " is not a folder");
  RequireFlag(!FLAGS_gravity_csv.empty(), "--gravity_csv is required");
  RequireFlag(!FLAGS_output_path.empty(), "--output_path is required");
  RequireFlag(FLAGS_output_format == "binary" || FLAGS_output_format == "text",
              "--output_format must be binary or text");
  RequireFlag(FLAGS_rotation_model == "yaw_only" || FLAGS_rotation_model == "gravity_prior",
              "--rotation_model must be yaw_only or gravity_prior");
  RequireFlag(FLAGS_gravity_sigma_deg > 0.0 && std::isfinite(FLAGS_gravity_sigma_deg),
              "--gravity_sigma_deg must be positive and finite");
  RequireFlag(FLAGS_loss == "huber" || FLAGS_loss == "cauchy" || FLAGS_loss == "none",
              "--loss must be huber, cauchy or none");
  RequireFlag(FLAGS_loss_scale_px > 0.0 && std::isfinite(FLAGS_loss_scale_px),
              "--loss_scale_px must be positive and finite");
  RequireFlag(FLAGS_pixel_sigma_px > 0.0 && std::isfinite(FLAGS_pixel_sigma_px),
              "--pixel_sigma_px must be positive and finite");
  RequireFlag(FLAGS_max_iterations >= 0, "--max_iterations must be >= 0");
  RequireFlag(FLAGS_threads >= 1 && FLAGS_threads <= 256, "--threads must be in [1, 256]");
  using trigrav::examples::ToolPath;
  std::vector<ToolPath> outputs = {{"--output_path", FLAGS_output_path, ToolPath::kFolder}};
  if (!FLAGS_covariance_csv.empty()) outputs.push_back({"--covariance_csv", FLAGS_covariance_csv});
  trigrav::examples::RequireOutputsApartFromInputs(
      {{"--input_path", FLAGS_input_path, ToolPath::kFolder}, {"--gravity_csv", FLAGS_gravity_csv}},
      outputs);
}

Options AdjusterOptions() {
  Options options;
  options.rotation_model = FLAGS_rotation_model == "yaw_only"
                               ? Options::RotationModel::kYawOnly
                               : Options::RotationModel::kGravityPrior;
  options.loss = FLAGS_loss == "huber"    ? Options::LossType::kHuber
                 : FLAGS_loss == "cauchy" ? Options::LossType::kCauchy
                                          : Options::LossType::kNone;
  options.loss_scale_px = FLAGS_loss_scale_px;
  options.pixel_sigma_px = FLAGS_pixel_sigma_px;
  options.gravity_sigma_deg = FLAGS_gravity_sigma_deg;
  options.compute_covariance = !FLAGS_covariance_csv.empty();
  options.max_num_iterations = FLAGS_max_iterations;
  options.num_threads = FLAGS_threads;
  options.Check();
  return options;
}

// One row per image: name, id, then the covariance (layout of NViewBundleAdjustmentSummary::
// covariances) row-major, space separated.
std::string FormatCovarianceCsv(const colmap::Reconstruction& model,
                                const colmap::NViewInput& input,
                                const trigrav::NViewBundleAdjustmentSummary& summary) {
  std::ostringstream out;
  out << std::setprecision(17);
  out << "# per image: the covariance of "
      << (FLAGS_rotation_model == "yaw_only" ? "[yaw (rad), C_world (3)], 4x4"
                                             : "[omega (rad, camera frame), C_world (3)], 6x6")
      << ", row-major; gauge-fixed parameters have zero rows (nview_bundle_adjustment.h)\n";
  out << "image_name,image_id,covariance\n";
  for (std::size_t i = 0; i < input.image_ids.size(); ++i) {
    out << model.images.at(input.image_ids[i]).name << ',' << input.image_ids[i] << ',';
    const Eigen::MatrixXd& covariance = summary.covariances.at(i);
    for (int r = 0; r < covariance.rows(); ++r) {
      for (int c = 0; c < covariance.cols(); ++c) out << (r + c > 0 ? " " : "") << covariance(r, c);
    }
    out << '\n';
  }
  return out.str();
}

int Run() {
  const Options options = AdjusterOptions();
  const colmap::Reconstruction model = colmap::ReadModel(FLAGS_input_path);
  const colmap::GravityByImageName gravity = colmap::ReadGravityCsv(FLAGS_gravity_csv);
  const colmap::NViewInput input = colmap::ToNView(model, gravity);
  trigrav::NViewReconstruction refined;
  const trigrav::NViewBundleAdjustmentSummary summary =
      trigrav::RefineWithGravity(input.reconstruction, {}, options, &refined);
  if (!summary.success) {
    std::cerr << "error: the refinement failed: " << summary.message << "; nothing written"
              << std::endl;
    return 1;
  }
  if (options.compute_covariance && summary.covariances.size() != input.image_ids.size()) {
    std::cerr << "error: no covariances: " << summary.message << "; nothing written" << std::endl;
    return 1;
  }
  const colmap::Reconstruction result = colmap::FromNView(model, input, refined);
  // The covariance CSV is staged before the model and committed after it: a failure leaves
  // neither.
  std::unique_ptr<tools::StagedFile> covariance_csv;
  if (options.compute_covariance) {
    covariance_csv = std::make_unique<tools::StagedFile>(
        FLAGS_covariance_csv, FormatCovarianceCsv(result, input, summary));
  }
  colmap::WriteModelCreatingParents(
      result, FLAGS_output_path,
      FLAGS_output_format == "text" ? colmap::ModelFormat::kText : colmap::ModelFormat::kBinary);
  if (covariance_csv) {
    try {
      covariance_csv->Commit();
    } catch (const std::exception& error) {
      std::cerr << "error: " << error.what() << "; the model is written to " << FLAGS_output_path
                << ", the covariance CSV is not" << std::endl;
      return 1;
    }
  }
  std::vector<double> rms = summary.residual_rms_px;
  rms.erase(std::remove_if(rms.begin(), rms.end(), [](double r) { return !std::isfinite(r); }),
            rms.end());
  std::nth_element(rms.begin(), rms.begin() + rms.size() / 2, rms.end());
  std::cout << "gravity bundle adjustment (" << FLAGS_rotation_model << ", " << FLAGS_loss
            << " loss): " << summary.num_images << " images, " << summary.num_points << " points, "
            << summary.num_observations << " observations (" << summary.num_skipped_observations
            << " skipped)\n"
            << "  cost " << summary.InitialCost() << " -> " << summary.FinalCost()
            << "; median over the images of their RMS reprojection error after: "
            << (rms.empty() ? 0.0 : rms[rms.size() / 2]) << " px\n"
            << "  " << summary.Iterations() << " iterations, " << summary.solve_s << " s solve";
  if (options.compute_covariance) std::cout << ", " << summary.covariance_s << " s covariance";
  std::cout << "\n  " << summary.BriefReport() << "\n  model written to " << FLAGS_output_path
            << " (" << FLAGS_output_format << ")\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  gflags::SetUsageMessage(
      "gravity_bundle_adjuster --input_path=sparse/0 --gravity_csv=g.csv --output_path=refined");
  gflags::ParseCommandLineFlags(&argc, &argv, true);
  CheckFlags();
  try {
    return Run();
  } catch (const std::exception& error) {
    std::cerr << "error: " << error.what() << "; nothing written" << std::endl;
    return 1;
  }
}
