// Synthetic scenes and error metrics.

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <random>
#include <string>
#include <vector>

#include "bindings.h"
#include "numpy_input.h"
#include "trigrav/evaluation/pose_errors.h"
#include "trigrav/evaluation/synthetic_scene.h"
#include "trigrav/initializers/three_view_error.h"

namespace trigrav::python {
namespace {

template <typename Points>
py::list ViewsToList(const std::array<Points, 3>& views) {
  py::list list;
  for (const auto& points : views) list.append(ToArray(points));
  return list;
}

void BindSyntheticScenes(py::module_& m) {
  OptionsClass<SyntheticSceneOptions>(
      m, "SyntheticSceneOptions",
      "Synthetic three-view scenes of the paper's protocol (f = 500 px, 640 x 480, +-10 deg, "
      "+-10 m); world y axis along gravity.")
      .Field("num_points", &SyntheticSceneOptions::num_points, "(4)")
      .Field("focal_px", &SyntheticSceneOptions::focal_px, "(500)")
      .Field("opencv_distortion", &SyntheticSceneOptions::opencv_distortion,
             "OPENCV (k1, k2, p1, p2) of all cameras; all 0 gives PINHOLE")
      .Field("width_px", &SyntheticSceneOptions::width_px, "(640)")
      .Field("height_px", &SyntheticSceneOptions::height_px, "(480)")
      .Field("max_yaw_deg", &SyntheticSceneOptions::max_yaw_deg, "(10)")
      .Field("max_tilt_deg", &SyntheticSceneOptions::max_tilt_deg, "(10)")
      .Field("max_center_m", &SyntheticSceneOptions::max_center_m, "(10)")
      .Field("min_depth_m", &SyntheticSceneOptions::min_depth_m, "(10)")
      .Field("max_depth_m", &SyntheticSceneOptions::max_depth_m, "(40)")
      .Field("min_depth_all_views_m", &SyntheticSceneOptions::min_depth_all_views_m, "(1)")
      .Field("pixel_noise_px", &SyntheticSceneOptions::pixel_noise_px, "(0)")
      .Field("imu_pitch_noise_deg", &SyntheticSceneOptions::imu_pitch_noise_deg, "(0)")
      .Field("imu_roll_noise_deg", &SyntheticSceneOptions::imu_roll_noise_deg, "(0)")
      .Field("outlier_ratio", &SyntheticSceneOptions::outlier_ratio, "(0)")
      .Finish(&SyntheticSceneOptions::Check);

  py::class_<SyntheticScene>(m, "SyntheticScene", "A synthetic scene and its ground truth.")
      .def_readonly("ground_truth", &SyntheticScene::ground_truth)
      .def_readonly("cam_from_world", &SyntheticScene::cam_from_world, "three 3 x 3 rotations")
      .def_readonly("center_in_world", &SyntheticScene::center_in_world)
      .def_readonly("pitch_rad", &SyntheticScene::pitch_rad)
      .def_readonly("roll_rad", &SyntheticScene::roll_rad)
      .def_readonly("yaw_rad", &SyntheticScene::yaw_rad)
      .def_property_readonly("points_in_world",
                             [](const SyntheticScene& s) { return ToArray(s.points_in_world); })
      .def_property_readonly(
          "pixels", [](const SyntheticScene& s) { return ViewsToList(s.pixels); },
          "three N x 2 arrays of noisy pixels")
      .def_property_readonly(
          "rays", [](const SyntheticScene& s) { return ViewsToList(s.rays); },
          "three N x 3 arrays: the unprojected noisy pixels (z = 1)")
      .def_readonly("gravity_alignment_true", &SyntheticScene::gravity_alignment_true)
      .def_readonly("gravity_alignment_measured", &SyntheticScene::gravity_alignment_measured)
      .def_property_readonly(
          "gravity_in_cam_measured",
          [](const SyntheticScene& s) { return RowsToArray(s.gravity_in_cam_measured); },
          "3 x 3: row k is the measured gravity (unit, down) in camera k + 1")
      .def_readonly("camera", &SyntheticScene::camera, "the camera of all three views")
      .def_property_readonly("is_inlier",
                             [](const SyntheticScene& s) { return MaskToArray(s.is_inlier); })
      .def("__repr__", [](const SyntheticScene& s) {
        return "SyntheticScene(" + std::to_string(s.points_in_world.size()) + " triplets)";
      });

  m.def(
      "generate_synthetic_scene",
      [](SyntheticSceneOptions options, std::uint64_t seed) {  // a copy: used without the GIL
        py::gil_scoped_release release;
        std::mt19937_64 rng(seed);
        return GenerateSyntheticScene(options, &rng);
      },
      py::arg_v("options", SyntheticSceneOptions(), "SyntheticSceneOptions()"), py::arg("seed") = 0,
      "One scene, drawn with std::mt19937_64(seed) (the C++ GenerateSyntheticScene with that "
      "generator).");
  m.def("to_observations", &ToObservations, py::arg("scene"),
        "The scene as a pipeline sees it: cameras, measured gravity, noisy pixels.");
  m.def("to_bearing_observations", &ToBearingObservations, py::arg("scene"),
        "The same as bearings (unit rays), no cameras.");
}

void BindMetrics(py::module_& m) {
  m.def(
      "rotation_error_deg",
      [](const py::object& R_gt, const py::object& R) {
        return RotationErrorDeg(ToMatrix3(R_gt, "R_gt"), ToMatrix3(R, "R"));
      },
      py::arg("R_gt"), py::arg("R"), "Angle of R_gt @ R.T, degrees.");
  m.def(
      "direction_error_deg",
      [](const py::object& a_gt, const py::object& a) {
        return DirectionErrorDeg(ToVector3(a_gt, "a_gt"), ToVector3(a, "a"));
      },
      py::arg("a_gt"), py::arg("a"), "Angle between two directions, degrees (180 if one is 0).");

  py::class_<ThreeViewPoseErrors>(m, "ThreeViewPoseErrors",
                                  "Errors of views 2 and 3 against the truth, degrees.")
      .def_property_readonly("rotation_deg",
                             [](const ThreeViewPoseErrors& e) {
                               return std::array<double, 2>{e.rotation_deg[0], e.rotation_deg[1]};
                             })
      .def_property_readonly(
          "translation_deg",
          [](const ThreeViewPoseErrors& e) {
            return std::array<double, 2>{e.translation_deg[0], e.translation_deg[1]};
          },
          "angle of the camera centre directions")
      .def_readonly("relative_scale", &ThreeViewPoseErrors::relative_scale,
                    "|log((|C3|/|C2|)_est / (|C3|/|C2|)_gt)|")
      .def("max_rotation_deg", &ThreeViewPoseErrors::MaxRotationDeg)
      .def("max_translation_deg", &ThreeViewPoseErrors::MaxTranslationDeg)
      .def("max_angle_deg", &ThreeViewPoseErrors::MaxAngleDeg)
      .def("__repr__", [](const ThreeViewPoseErrors& e) {
        const auto f = [](double x) { return std::string(py::repr(py::float_(x))); };
        return "ThreeViewPoseErrors(rotation_deg=[" + f(e.rotation_deg[0]) + ", " +
               f(e.rotation_deg[1]) + "], translation_deg=[" + f(e.translation_deg[0]) + ", " +
               f(e.translation_deg[1]) + "], relative_scale=" + f(e.relative_scale) + ")";
      });
  m.def("compute_three_view_pose_errors", &ComputeThreeViewPoseErrors, py::arg("ground_truth"),
        py::arg("estimate"));

  py::class_<YawTiltErrorDeg>(m, "YawTiltErrorDeg", "A rotation error split about gravity.")
      .def_readonly("yaw_deg", &YawTiltErrorDeg::yaw_deg)
      .def_readonly("tilt_deg", &YawTiltErrorDeg::tilt_deg)
      .def("__repr__", [](const YawTiltErrorDeg& e) {
        return "YawTiltErrorDeg(yaw_deg=" + std::string(py::repr(py::float_(e.yaw_deg))) +
               ", tilt_deg=" + std::string(py::repr(py::float_(e.tilt_deg))) + ")";
      });
  m.def(
      "split_rotation_error_deg",
      [](const py::object& R_gt, const py::object& R, const py::object& gravity) {
        return SplitRotationErrorDeg(ToMatrix3(R_gt, "R_gt"), ToMatrix3(R, "R"),
                                     ToVector3(gravity, "gravity_in_cam"));
      },
      py::arg("R_gt"), py::arg("R"), py::arg("gravity_in_cam"),
      "The error R_gt @ R.T split into its yaw (about gravity) and tilt parts, degrees.");

  m.def(
      "three_view_errors",
      [](ThreeViewObservations observations, ThreeViewPose pose) {  // copies: used without the GIL
        std::vector<double> errors;
        {
          py::gil_scoped_release release;
          const ThreeViewReprojectionError error(observations);
          const ThreeViewReprojectionError::PreparedPose prepared =
              ThreeViewReprojectionError::Prepare(pose);
          errors.resize(error.size());
          for (std::size_t n = 0; n < errors.size(); ++n) errors[n] = error(prepared, n);
        }
        return py::array_t<double>(errors.size(), errors.data());
      },
      py::arg("observations"), py::arg("pose"),
      "The inlier error of every triplet under a pose: the largest reprojection error over the "
      "three views of its midpoint triangulation (px; degrees for bearings; inf behind a "
      "camera).");
}

}  // namespace

void BindEvaluation(py::module_& m) {
  BindSyntheticScenes(m);
  BindMetrics(m);
}

}  // namespace trigrav::python
