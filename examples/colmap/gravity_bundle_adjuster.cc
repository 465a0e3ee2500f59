// Gravity-aware bundle adjustment of a COLMAP sparse model: reads the model and each image's
// gravity, refines every pose and point with trigrav's N-view bundle adjustment
// (trigrav/ba/nview_bundle_adjustment.h; intrinsics constant), writes the model back.
//
//   gravity_bundle_adjuster --input_path=sparse/0 --gravity_csv=g.csv --output_path=refined
//
// Nothing is written unless the refinement succeeds and the refined model is not worse than the
// input (--max_rms_growth): an image without gravity, a bad model, a failed solve, an image whose
// reprojection error grew or an unwritable --covariance_csv or --gravity_report_csv leave every
// output untouched. README.md describes the flags.

#include <gflags/gflags.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/output_paths.h"
#include "common/require_flag.h"
#include "common/tool_flags.h"
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
DEFINE_double(gravity_sigma_deg,
              0.0,
              "IMU gravity sigma (deg) of the gravity-prior model; 0: estimated from the data by "
              "the gravity verdict (NViewBundleAdjustmentOptions::gravity_sigma_from_data).");
DEFINE_bool(check_gravity,
            true,
            "The gravity verdict: measure each image's gravity against the images, drop the "
            "gravity of inconsistent images, keep yaw-only only when the data accept exact tilts.");
DEFINE_double(max_rms_growth,
              1.5,
              "Refuse (exit 1, nothing written) when an image's RMS reprojection error after "
              "exceeds this factor times its RMS before, plus 0.1 px; 0: never refuse.");
DEFINE_bool(upright,
            false,
            "Write the model in a gravity-aligned world frame: +y down (along gravity), +z the "
            "horizontal part of the input's +z, origin kept (UprightReconstruction).");
DEFINE_string(gravity_report_csv,
              "",
              "If set, write one row per image: its gravity disagreement (deg and IMU sigmas), "
              "whether its gravity was used, observations, RMS reprojection error before and "
              "after.");
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
  RequireFlag(FLAGS_gravity_sigma_deg >= 0.0 && std::isfinite(FLAGS_gravity_sigma_deg),
              "--gravity_sigma_deg must be >= 0 and finite (0: from the data)");
  RequireFlag(FLAGS_gravity_sigma_deg > 0.0 || FLAGS_check_gravity,
              "--gravity_sigma_deg=0 (from the data) needs --check_gravity");
  RequireFlag(FLAGS_max_rms_growth == 0.0 ||
                  (FLAGS_max_rms_growth >= 1.0 && std::isfinite(FLAGS_max_rms_growth)),
              "--max_rms_growth must be 0 (off) or a finite factor >= 1");
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
  if (!FLAGS_gravity_report_csv.empty()) {
    outputs.push_back({"--gravity_report_csv", FLAGS_gravity_report_csv});
  }
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
  options.check_gravity = FLAGS_check_gravity;
  options.gravity_sigma_from_data = FLAGS_gravity_sigma_deg == 0.0;
  if (FLAGS_gravity_sigma_deg > 0.0) options.gravity_sigma_deg = FLAGS_gravity_sigma_deg;
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

// One row per image: the gravity verdict and the reprojection error before and after.
std::string FormatGravityReportCsv(const colmap::Reconstruction& model,
                                   const colmap::NViewInput& input,
                                   const trigrav::NViewBundleAdjustmentSummary& summary,
                                   const std::vector<double>& rms_before,
                                   const std::vector<double>& rms_after) {
  std::ostringstream out;
  out << std::setprecision(9);
  out << "image_name,image_id,gravity_disagreement_deg,gravity_disagreement_sigmas,gravity_used,"
         "observations,rms_before_px,rms_after_px\n";
  const bool verdict = !summary.gravity_disagreement_deg.empty();
  const double sigma_deg = summary.estimated_gravity_sigma_deg;
  for (std::size_t i = 0; i < input.image_ids.size(); ++i) {
    out << model.images.at(input.image_ids[i]).name << ',' << input.image_ids[i] << ',';
    if (verdict) {
      out << summary.gravity_disagreement_deg[i] << ','
          << summary.gravity_disagreement_deg[i] / sigma_deg << ','
          << (summary.gravity_used[i] ? 1 : 0);
    } else {
      out << ",,1";
    }
    out << ',' << summary.observations_per_image.at(i) << ',' << rms_before[i] << ','
        << rms_after[i] << '\n';
  }
  return out.str();
}

// The image whose RMS grew the most (ratio after / before); -1 if none has both.
int WorstImage(const std::vector<double>& rms_before, const std::vector<double>& rms_after) {
  int worst = -1;
  double worst_excess = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < rms_before.size(); ++i) {
    const double excess = rms_after[i] - FLAGS_max_rms_growth * rms_before[i];
    if (std::isfinite(excess) && excess > worst_excess) {
      worst_excess = excess;
      worst = static_cast<int>(i);
    }
  }
  return worst;
}

double Median(std::vector<double> values) {
  values.erase(
      std::remove_if(values.begin(), values.end(), [](double v) { return !std::isfinite(v); }),
      values.end());
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

int Run() {
  const Options options = AdjusterOptions();
  const colmap::Reconstruction model = colmap::ReadModel(FLAGS_input_path);
  const colmap::GravityByImageName gravity = colmap::ReadGravityCsv(FLAGS_gravity_csv);
  const colmap::NViewInput input = colmap::ToNView(model, gravity);
  trigrav::NViewReconstruction refined;
  const trigrav::NViewBundleAdjustmentSummary summary =
      trigrav::RefineWithGravity(input.reconstruction, {}, options, &refined);
  const auto name = [&](int i) { return model.images.at(input.image_ids.at(i)).name; };
  if (!summary.success) {
    std::cerr << "error: the refinement failed: " << summary.message;
    // Name the images that lost observations (the message gives their indices).
    std::string lost;
    for (const int i : summary.images_losing_observations) {
      lost += (lost.empty() ? "" : ", ") + name(i);
    }
    if (!lost.empty()) std::cerr << " (" << lost << ")";
    std::cerr << "; nothing written" << std::endl;
    return 1;
  }
  if (options.compute_covariance && summary.covariances.size() != input.image_ids.size()) {
    std::cerr << "error: no covariances: " << summary.message << "; nothing written" << std::endl;
    return 1;
  }
  const std::vector<double> rms_before = trigrav::ReprojectionRmsPx(input.reconstruction);
  const std::vector<double> rms_after = trigrav::ReprojectionRmsPx(refined);
  const int worst = WorstImage(rms_before, rms_after);
  if (FLAGS_max_rms_growth > 0.0 && worst >= 0 &&
      rms_after[worst] > FLAGS_max_rms_growth * rms_before[worst] + 0.1) {
    std::cerr << "error: the refined model is worse than the input: image " << name(worst)
              << " has an RMS reprojection error of " << rms_after[worst] << " px ("
              << rms_before[worst] << " px before; --max_rms_growth=" << FLAGS_max_rms_growth
              << "); check its gravity, or use --rotation_model=gravity_prior; nothing written"
              << std::endl;
    return 1;
  }
  if (FLAGS_upright) refined = trigrav::UprightReconstruction(refined, summary.gravity_in_world);
  const colmap::Reconstruction result = colmap::FromNView(model, input, refined);
  // The CSVs are staged before the model and committed after it: a failure leaves neither.
  std::vector<std::unique_ptr<tools::StagedFile>> csvs;
  if (options.compute_covariance) {
    csvs.push_back(std::make_unique<tools::StagedFile>(
        FLAGS_covariance_csv, FormatCovarianceCsv(result, input, summary)));
  }
  if (!FLAGS_gravity_report_csv.empty()) {
    csvs.push_back(std::make_unique<tools::StagedFile>(
        FLAGS_gravity_report_csv,
        FormatGravityReportCsv(result, input, summary, rms_before, rms_after)));
  }
  colmap::WriteModelCreatingParents(
      result, FLAGS_output_path,
      FLAGS_output_format == "text" ? colmap::ModelFormat::kText : colmap::ModelFormat::kBinary);
  for (const auto& csv : csvs) {
    try {
      csv->Commit();
    } catch (const std::exception& error) {
      std::cerr << "error: " << error.what() << "; the model is written to " << FLAGS_output_path
                << ", not every CSV" << std::endl;
      return 1;
    }
  }
  const bool yaw_only = summary.rotation_model == Options::RotationModel::kYawOnly;
  std::cout << "gravity bundle adjustment (" << (yaw_only ? "yaw_only" : "gravity_prior");
  if (!yaw_only) std::cout << ", gravity sigma " << summary.gravity_sigma_deg << " deg";
  std::cout << ", " << FLAGS_loss << " loss): " << summary.num_images << " images, "
            << summary.num_points << " points, " << summary.num_observations << " observations ("
            << summary.num_skipped_observations << " skipped)\n";
  if (!summary.gravity_disagreement_deg.empty()) {
    std::cout << "  gravity: IMU sigma estimated from the data "
              << summary.estimated_gravity_sigma_deg << " deg; median disagreement "
              << Median(summary.gravity_disagreement_deg) << " deg";
    std::string dropped;
    for (std::size_t i = 0; i < summary.gravity_used.size(); ++i) {
      if (!summary.gravity_used[i]) {
        std::ostringstream item;
        item << (dropped.empty() ? "" : ", ") << name(static_cast<int>(i)) << " ("
             << summary.gravity_disagreement_deg[i] << " deg)";
        dropped += item.str();
      }
    }
    std::cout << "; gravity dropped for " << (dropped.empty() ? "no image" : dropped) << "\n";
  }
  std::cout << "  cost " << summary.InitialCost() << " -> " << summary.FinalCost()
            << "; RMS reprojection error per image, median " << Median(rms_before) << " -> "
            << Median(rms_after) << " px";
  if (worst >= 0) {
    std::cout << "; worst image " << name(worst) << " " << rms_before[worst] << " -> "
              << rms_after[worst] << " px";
  }
  std::cout << "\n  " << summary.Iterations() << " iterations, " << summary.solve_s << " s solve";
  if (options.compute_covariance) std::cout << ", " << summary.covariance_s << " s covariance";
  std::cout << "\n  " << summary.BriefReport();
  if (!summary.message.empty()) std::cout << "\n  note: " << summary.message;
  std::cout << "\n  model written to " << FLAGS_output_path << " (" << FLAGS_output_format
            << (FLAGS_upright ? ", upright: +y down" : "") << ")\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  trigrav::examples::ParseToolFlags(
      "gravity_bundle_adjuster --input_path=sparse/0 --gravity_csv=g.csv --output_path=refined",
      __FILE__, &argc, &argv);
  CheckFlags();
  try {
    return Run();
  } catch (const std::exception& error) {
    std::cerr << "error: " << error.what() << "; nothing written" << std::endl;
    return 1;
  }
}
