// The N-view gravity-aware bundle adjustment (trigrav/ba/nview_bundle_adjustment.h):
// NViewReconstruction with numpy arrays, its Config and Options, RefineWithGravity and its summary.

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <string>
#include <utility>
#include <vector>

#include "bindings.h"
#include "index_arrays.h"
#include "numpy_input.h"
#include "signal_watch.h"
#include "trigrav/ba/nview_bundle_adjustment.h"

namespace trigrav::python {
namespace {

using Options = NViewBundleAdjustmentOptions;
using Config = NViewBundleAdjustmentConfig;
using Summary = NViewBundleAdjustmentSummary;

void BindOptions(py::module_& m) {
  // The enums are those of the three-view options (one C++ type, bound once):
  // ThreeViewBundleAdjustmentOptions.RotationModel, .LossType, .LinearSolverType.
  OptionsClass<Options> options(
      m, "NViewBundleAdjustmentOptions",
      "N-view gravity-aware bundle adjustment (refine_with_gravity): rotation model, loss, "
      "sigmas, Ceres settings, the gravity verdict. The enums are "
      "ThreeViewBundleAdjustmentOptions'.");
  options
      .Field("rotation_model", &Options::rotation_model,
             "ThreeViewBundleAdjustmentOptions.RotationModel (YAW_ONLY): YAW_ONLY takes each "
             "image's pitch and roll from its gravity, GRAVITY_PRIOR adds a prior of sigma "
             "gravity_sigma_deg")
      .Field("loss", &Options::loss, "ThreeViewBundleAdjustmentOptions.LossType (HUBER)")
      .Field("loss_scale_px", &Options::loss_scale_px, "loss scale on pixel residuals (2)")
      .Field("pixel_sigma_px", &Options::pixel_sigma_px,
             "pixel noise: the gravity prior's weight and the covariances' scale (1)")
      .Field("gravity_sigma_deg", &Options::gravity_sigma_deg,
             "IMU angular sigma of the gravity prior (0.1)")
      .Field("compute_covariance", &Options::compute_covariance,
             "also each image's covariance (summary.covariances) (False)")
      .Field("max_num_iterations", &Options::max_num_iterations, "(100)")
      .Field("num_threads", &Options::num_threads, "Ceres threads (1)")
      .Field("linear_solver_type", &Options::linear_solver_type,
             "ThreeViewBundleAdjustmentOptions.LinearSolverType (SPARSE_SCHUR)")
      .Field("function_tolerance", &Options::function_tolerance, "(1e-6)")
      .Field("gradient_tolerance", &Options::gradient_tolerance, "(1e-10)")
      .Field("parameter_tolerance", &Options::parameter_tolerance, "(1e-8)")
      .Field("check_gravity", &Options::check_gravity,
             "the gravity verdict: a solve in which the images dominate measures each image's "
             "gravity disagreement; inconsistent images lose their gravity, yaw-only is kept "
             "only when the data accept exact tilts (True)")
      .Field("gravity_sigma_from_data", &Options::gravity_sigma_from_data,
             "use the IMU sigma the verdict estimates instead of gravity_sigma_deg (True)")
      .Field("max_gravity_disagreement_sigmas", &Options::max_gravity_disagreement_sigmas,
             "an image whose disagreement exceeds this many estimated sigmas loses its gravity "
             "(5)");
  options.Finish(&Options::Check);
  options.cls().attr("VERDICT_GRAVITY_SIGMA_DEG") = Options::kVerdictGravitySigmaDeg;
  options.cls().attr("MIN_GRAVITY_DISAGREEMENT_BOUND_DEG") =
      Options::kMinGravityDisagreementBoundDeg;
  options.cls().attr("MIN_ESTIMATED_GRAVITY_SIGMA_DEG") = Options::kMinEstimatedGravitySigmaDeg;
  options.cls().attr("YAW_ONLY_TEST_SIGMAS") = Options::kYawOnlyTestSigmas;

  // Its Check() needs the reconstruction: refine_with_gravity checks the config.
  OptionsClass<Config>(m, "NViewBundleAdjustmentConfig",
                       "What refine_with_gravity holds constant and how the gauge is fixed; "
                       "checked against the reconstruction by the call.")
      .Field("reference_image", &Config::reference_image,
             "image whose centre and yaw (rotation about gravity) are constant (0)")
      .Field("scale_image", &Config::scale_image,
             "image whose centre keeps one coordinate (the scale); -1: the farthest from the "
             "reference (-1)")
      .Field("constant_images", &Config::constant_images,
             "images whose pose is held constant (list of indices) ([])")
      .Field("images_without_gravity", &Config::images_without_gravity,
             "images whose measured gravity is left out (GRAVITY_PRIOR only); refine_with_gravity "
             "adds those its verdict finds inconsistent ([])")
      .Field("constant_points", &Config::constant_points, "motion-only refinement (False)")
      .Finish(nullptr);
}

void BindReconstruction(py::module_& m) {
  py::class_<NViewImage>(m, "NViewImage", "One image of an NViewReconstruction.")
      .def(py::init([](int camera_index, const CameraPose& cam_from_world,
                       const py::object& gravity_in_cam) {
             NViewImage image;
             image.camera_index = camera_index;
             image.cam_from_world = cam_from_world;
             image.gravity_in_cam = ToVector3(gravity_in_cam, "gravity_in_cam");
             return image;
           }),
           py::arg("camera_index"), py::arg("cam_from_world"), py::arg("gravity_in_cam"),
           "camera_index into NViewReconstruction.cameras; cam_from_world (x_cam = R x_world + "
           "t); gravity_in_cam: measured gravity (down) in this camera's frame, a 3-vector.")
      .def_readwrite("camera_index", &NViewImage::camera_index)
      .def_readwrite("cam_from_world", &NViewImage::cam_from_world)
      .def_property(
          "gravity_in_cam",
          [](const NViewImage& image) { return Eigen::Vector3d(image.gravity_in_cam); },
          [](NViewImage& image, const py::object& g) {
            image.gravity_in_cam = ToVector3(g, "gravity_in_cam");
          },
          "measured gravity (down) in the camera frame, a copy (3,)")
      .def("__repr__", [](const NViewImage& image) {
        return "NViewImage(camera_index=" + std::to_string(image.camera_index) +
               ", cam_from_world=" + std::string(py::repr(py::cast(image.cam_from_world))) +
               ", gravity_in_cam=" +
               std::string(py::repr(py::cast(Eigen::Vector3d(image.gravity_in_cam)))) + ")";
      });

  py::class_<NViewReconstruction>(
      m, "NViewReconstruction",
      "Input and output of refine_with_gravity: cameras, images (pose, gravity), points and "
      "observations (image index, point index, pixel). Array properties return copies; assign "
      "to change them.")
      .def(py::init([](const std::vector<Camera>& cameras, const std::vector<NViewImage>& images,
                       const py::object& points_in_world,
                       const py::object& observation_image_indices,
                       const py::object& observation_point_indices,
                       const py::object& observation_pixels) {
             NViewReconstruction r;
             r.cameras = cameras;
             r.images = images;
             if (!points_in_world.is_none())
               r.points_in_world = ToPoints3(points_in_world, "points_in_world");
             const std::vector<int> image_index =
                 observation_image_indices.is_none()
                     ? std::vector<int>()
                     : ToIndexVector<int>(observation_image_indices, "observation_image_indices");
             const std::vector<int> point_index =
                 observation_point_indices.is_none()
                     ? std::vector<int>()
                     : ToIndexVector<int>(observation_point_indices, "observation_point_indices");
             const std::vector<Eigen::Vector2d> pixels =
                 observation_pixels.is_none() ? std::vector<Eigen::Vector2d>()
                                              : ToPoints2(observation_pixels, "observation_pixels");
             if (image_index.size() != point_index.size() || image_index.size() != pixels.size()) {
               throw py::value_error(
                   "trigrav: NViewReconstruction: observation_image_indices, "
                   "observation_point_indices and observation_pixels differ in length (" +
                   std::to_string(image_index.size()) + ", " + std::to_string(point_index.size()) +
                   ", " + std::to_string(pixels.size()) + ")");
             }
             r.observations.resize(pixels.size());
             for (std::size_t i = 0; i < pixels.size(); ++i) {
               r.observations[i] = {image_index[i], point_index[i], pixels[i]};
             }
             return r;
           }),
           py::arg("cameras") = std::vector<Camera>(),
           py::arg("images") = std::vector<NViewImage>(), py::arg("points_in_world") = py::none(),
           py::arg("observation_image_indices") = py::none(),
           py::arg("observation_point_indices") = py::none(),
           py::arg("observation_pixels") = py::none(),
           "cameras: list of Camera; images: list of NViewImage; points_in_world: P x 3; one "
           "observation per row of observation_image_indices (M,), observation_point_indices "
           "(M,) and observation_pixels (M x 2, COLMAP's pixel convention).")
      // Copies both ways (def_readwrite would hand out references into the vectors).
      .def_property(
          "cameras", [](const NViewReconstruction& r) { return r.cameras; },
          [](NViewReconstruction& r, const std::vector<Camera>& c) { r.cameras = c; },
          "list of Camera (a copy)")
      .def_property(
          "images", [](const NViewReconstruction& r) { return r.images; },
          [](NViewReconstruction& r, const std::vector<NViewImage>& i) { r.images = i; },
          "list of NViewImage (a copy)")
      .def_property(
          "points_in_world",
          [](const NViewReconstruction& r) { return ToArray(r.points_in_world); },
          [](NViewReconstruction& r, const py::object& points) {
            r.points_in_world = ToPoints3(points, "points_in_world");
          },
          "P x 3")
      .def_property_readonly(
          "observation_image_indices",
          [](const NViewReconstruction& r) {
            std::vector<int> v(r.observations.size());
            for (std::size_t i = 0; i < v.size(); ++i) v[i] = r.observations[i].image_index;
            return VectorToArray(v);
          },
          "(M,) int32: each observation's image")
      .def_property_readonly(
          "observation_point_indices",
          [](const NViewReconstruction& r) {
            std::vector<int> v(r.observations.size());
            for (std::size_t i = 0; i < v.size(); ++i) v[i] = r.observations[i].point_index;
            return VectorToArray(v);
          },
          "(M,) int32: each observation's point")
      .def_property_readonly(
          "observation_pixels",
          [](const NViewReconstruction& r) {
            std::vector<Eigen::Vector2d> v(r.observations.size());
            for (std::size_t i = 0; i < v.size(); ++i) v[i] = r.observations[i].pixel;
            return ToArray(v);
          },
          "M x 2: each observation's pixel")
      .def_property_readonly(
          "cams_from_world_R",
          [](const NViewReconstruction& r) {
            py::array_t<double> array(
                {static_cast<py::ssize_t>(r.images.size()), py::ssize_t{3}, py::ssize_t{3}});
            for (std::size_t k = 0; k < r.images.size(); ++k) {
              Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(
                  array.mutable_data() + 9 * k) = r.images[k].cam_from_world.R;
            }
            return array;
          },
          "N x 3 x 3: every image's cam_from_world rotation")
      .def_property_readonly(
          "cams_from_world_t",
          [](const NViewReconstruction& r) {
            std::vector<Eigen::Vector3d> t(r.images.size());
            for (std::size_t k = 0; k < t.size(); ++k) t[k] = r.images[k].cam_from_world.t;
            return ToArray(t);
          },
          "N x 3: every image's cam_from_world translation")
      .def_property_readonly(
          "centers",
          [](const NViewReconstruction& r) {
            std::vector<Eigen::Vector3d> c(r.images.size());
            for (std::size_t k = 0; k < c.size(); ++k) c[k] = r.images[k].cam_from_world.Center();
            return ToArray(c);
          },
          "N x 3: every image's centre in the world")
      .def_property_readonly(
          "gravity_in_cam",
          [](const NViewReconstruction& r) {
            std::vector<Eigen::Vector3d> g(r.images.size());
            for (std::size_t k = 0; k < g.size(); ++k) g[k] = r.images[k].gravity_in_cam;
            return ToArray(g);
          },
          "N x 3: every image's measured gravity")
      .def_property_readonly("num_observations",
                             [](const NViewReconstruction& r) { return r.observations.size(); })
      .def("check", &NViewReconstruction::Check,
           "ValueError naming the first bad field and index, as the C++ Check().")
      .def("__repr__", [](const NViewReconstruction& r) {
        return "NViewReconstruction(cameras=" + std::to_string(r.cameras.size()) +
               ", images=" + std::to_string(r.images.size()) +
               ", points=" + std::to_string(r.points_in_world.size()) +
               ", observations=" + std::to_string(r.observations.size()) + ")";
      });
}

void BindSummary(py::module_& m) {
  py::class_<Summary>(m, "NViewBundleAdjustmentSummary", "What refine_with_gravity did.")
      .def_readonly("success", &Summary::success,
                    "Ceres returned a usable solution and every refined value is finite")
      .def_readonly("message", &Summary::message, "why not, or a note")
      .def_readonly("num_images", &Summary::num_images)
      .def_readonly("num_points", &Summary::num_points, "points in the problem")
      .def_readonly("num_observations", &Summary::num_observations, "observations in the problem")
      .def_readonly("num_skipped_observations", &Summary::num_skipped_observations,
                    "observations left out (point behind the camera at the start, or of a point "
                    "left out)")
      .def_property_readonly(
          "gravity_in_world", [](const Summary& s) { return Eigen::Vector3d(s.gravity_in_world); },
          "unit gravity of the caller's world frame the problem was aligned to (3,)")
      .def_property_readonly(
          "residual_rms_px", [](const Summary& s) { return VectorToArray(s.residual_rms_px); },
          "(N,) per image: RMS pixel residual norm at the solution (NaN without observations)")
      .def_property_readonly(
          "covariances",
          [](const Summary& s) {
            py::list list;
            for (const Eigen::MatrixXd& c : s.covariances) list.append(py::cast(c));
            return list;
          },
          "per image (with compute_covariance and success): 4 x 4 (YAW_ONLY: yaw, C) or 6 x 6 "
          "(GRAVITY_PRIOR: omega, C); an empty list otherwise")
      .def_property_readonly(
          "observations_per_image",
          [](const Summary& s) { return VectorToArray(s.observations_per_image); },
          "(N,) int32: each image's observations in the problem")
      .def_property_readonly(
          "images_losing_observations",
          [](const Summary& s) { return VectorToArray(s.images_losing_observations); },
          "int32 indices of the images that kept fewer than half of their observations (not a "
          "success when any)")
      .def_readonly("rotation_model", &Summary::rotation_model,
                    "the ThreeViewBundleAdjustmentOptions.RotationModel solved")
      .def_readonly("gravity_sigma_deg", &Summary::gravity_sigma_deg,
                    "the IMU sigma the gravity priors used (GRAVITY_PRIOR)")
      .def_property_readonly(
          "gravity_disagreement_deg",
          [](const Summary& s) { return VectorToArray(s.gravity_disagreement_deg); },
          "(N,) per image: angle between its measured gravity and the one the images imply "
          "(deg); empty without the verdict")
      .def_property_readonly(
          "gravity_used", [](const Summary& s) { return MaskToArray(s.gravity_used); },
          "(N,) bool per image: its gravity took part; empty without the verdict")
      .def_readonly("estimated_gravity_sigma_deg", &Summary::estimated_gravity_sigma_deg,
                    "the IMU sigma estimated from the consistent images (deg); NaN without the "
                    "verdict")
      .def_readonly("solve_s", &Summary::solve_s,
                    "wall-clock seconds of ceres::Solve (both solves of the verdict)")
      .def_readonly("covariance_s", &Summary::covariance_s)
      .def_property_readonly("initial_cost", &Summary::InitialCost)
      .def_property_readonly("final_cost", &Summary::FinalCost)
      .def_property_readonly("iterations", &Summary::Iterations)
      .def("brief_report", &Summary::BriefReport)
      .def(
          "full_report", [](const Summary& s) { return s.ceres_summary.FullReport(); },
          "Ceres' full report")
      .def("__repr__", [](const Summary& s) {
        return "NViewBundleAdjustmentSummary(success=" + std::string(s.success ? "True" : "False") +
               ", num_images=" + std::to_string(s.num_images) +
               ", num_points=" + std::to_string(s.num_points) +
               ", message=" + std::string(py::repr(py::str(s.message))) + ")";
      });

  m.def(
      "refine_with_gravity",
      // Arguments by value: the call works on copies another Python thread cannot change.
      [](NViewReconstruction input, Config config, Options options) {
        SignalWatch watch;
        options.stop_requested = watch.StopRequested();
        NViewReconstruction refined;
        Summary summary;
        watch.Run(1, 1, [&](std::size_t) {
          summary = RefineWithGravity(input, config, options, &refined);
        });
        return py::make_tuple(std::move(summary), std::move(refined));
      },
      py::arg("reconstruction"), py::arg_v("config", Config(), "NViewBundleAdjustmentConfig()"),
      py::arg_v("options", Options(), "NViewBundleAdjustmentOptions()"),
      "Gravity-aware bundle adjustment of a whole reconstruction (RefineWithGravity). Returns "
      "(summary, refined): the NViewBundleAdjustmentSummary and the refined NViewReconstruction "
      "(the input's when not summary.success). ValueError for an invalid reconstruction, config "
      "or options. The GIL is released; Ctrl-C raises KeyboardInterrupt after the current "
      "solver iteration.");
}

void BindUpright(py::module_& m) {
  m.def(
      "upright_reconstruction",
      [](const NViewReconstruction& reconstruction, const py::object& gravity_in_world) {
        const Eigen::Vector3d g = ToVector3(gravity_in_world, "gravity_in_world");
        py::gil_scoped_release release;
        return UprightReconstruction(reconstruction, g);
      },
      py::arg("reconstruction"), py::arg("gravity_in_world"),
      "The reconstruction rotated about the origin so that +y is gravity_in_world (down; e.g. "
      "summary.gravity_in_world) and +z the horizontal part of the old +z (UprightReconstruction). "
      "ValueError for a zero or non-finite gravity.");
}

}  // namespace

void BindNView(py::module_& m) {
  BindOptions(m);
  BindReconstruction(m);
  BindSummary(m);
  BindUpright(m);
}

}  // namespace trigrav::python
