// CameraPose, ThreeViewPose, Camera, ThreeViewObservations and the gravity helpers.

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <cstdio>
#include <string>
#include <vector>

#include "bindings.h"
#include "numpy_input.h"
#include "trigrav/initializers/camera_model.h"
#include "trigrav/initializers/camera_pose.h"
#include "trigrav/initializers/gravity.h"
#include "trigrav/initializers/three_view_observations.h"

namespace trigrav::python {
namespace {

std::string Format(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), format, value);
  return buffer;
}

void BindPoses(py::module_& m) {
  py::class_<CameraPose>(
      m, "CameraPose",
      "Rigid transform from the reference frame (camera 1) into a camera: x_cam = R @ x_ref + t. "
      "t is the fourth column of [R | t], not the centre; center = -R.T @ t.")
      .def(py::init([](const py::object& R, const py::object& t) {
             CameraPose pose;
             if (!R.is_none()) pose.R = ToMatrix3(R, "R");
             if (!t.is_none()) pose.t = ToVector3(t, "t");
             return pose;
           }),
           py::arg("R") = py::none(), py::arg("t") = py::none(),
           "R: 3 x 3 rotation (identity if None), t: 3-vector (zero if None).")
      .def_property(
          "R", [](CameraPose& pose) -> Eigen::Matrix3d& { return pose.R; },
          [](CameraPose& pose, const py::object& R) { pose.R = ToMatrix3(R, "R"); },
          py::return_value_policy::reference_internal, "3 x 3 rotation cam_from_ref")
      .def_property(
          "t", [](CameraPose& pose) -> Eigen::Vector3d& { return pose.t; },
          [](CameraPose& pose, const py::object& t) { pose.t = ToVector3(t, "t"); },
          py::return_value_policy::reference_internal, "translation, the fourth column of [R | t]")
      .def_property_readonly("center", &CameraPose::Center,
                             "camera centre in reference coordinates, -R.T @ t")
      .def("inverse", &CameraPose::Inverse, "a_from_b of b_from_a: [R.T | -R.T @ t]")
      .def(
          "apply",
          [](const CameraPose& pose, const py::object& points) {
            std::vector<Eigen::Vector3d> in_cam = ToPoints3(points, "points_in_ref");
            for (Eigen::Vector3d& point : in_cam) point = pose.Apply(point);
            return ToArray(in_cam);
          },
          py::arg("points_in_ref"), "N x 3 points in reference coordinates -> N x 3 in the camera")
      .def("is_finite", &CameraPose::IsFinite)
      .def(
          "__mul__",
          [](const CameraPose& c_from_b, const CameraPose& b_from_a) {
            return c_from_b * b_from_a;
          },
          py::is_operator(), py::arg("b_from_a"), "c_from_a = c_from_b * b_from_a")
      .def("__repr__", [](const CameraPose& pose) {
        return "CameraPose(R=" + std::string(py::repr(py::cast(pose.R))) +
               ", t=" + std::string(py::repr(py::cast(pose.t))) + ")";
      });

  py::class_<ThreeViewPose>(m, "ThreeViewPose",
                            "Poses of cameras 2 and 3 relative to camera 1. trigrav returns "
                            "|cam2_from_cam1.center| = 1, so |cam3_from_cam1.center| is the "
                            "relative scale.")
      .def(py::init([](const CameraPose& cam2_from_cam1, const CameraPose& cam3_from_cam1) {
             return ThreeViewPose{cam2_from_cam1, cam3_from_cam1};
           }),
           py::arg_v("cam2_from_cam1", CameraPose(), "CameraPose()"),
           py::arg_v("cam3_from_cam1", CameraPose(), "CameraPose()"))
      .def_readwrite("cam2_from_cam1", &ThreeViewPose::cam2_from_cam1)
      .def_readwrite("cam3_from_cam1", &ThreeViewPose::cam3_from_cam1)
      .def("cam3_from_cam2", &ThreeViewPose::Cam3FromCam2,
           "cam3_from_cam1 * cam2_from_cam1.inverse()")
      .def("is_finite", &ThreeViewPose::IsFinite)
      .def("__repr__", [](const ThreeViewPose& pose) {
        return "ThreeViewPose(cam2_from_cam1=" +
               std::string(py::repr(py::cast(pose.cam2_from_cam1))) +
               ", cam3_from_cam1=" + std::string(py::repr(py::cast(pose.cam3_from_cam1))) + ")";
      });
}

void BindCamera(py::module_& m) {
  std::vector<std::string> names;
  for (const CameraModel model : kCameraModels) names.emplace_back(CameraModelName(model));
  m.attr("CAMERA_MODELS") = py::tuple(py::cast(names));

  py::class_<Camera>(m, "Camera",
                     "A camera of one of COLMAP's models with COLMAP's parameter order "
                     "(CAMERA_MODELS): SIMPLE_PINHOLE f, cx, cy; PINHOLE fx, fy, cx, cy; "
                     "SIMPLE_RADIAL f, cx, cy, k; RADIAL f, cx, cy, k1, k2; OPENCV fx, fy, cx, "
                     "cy, k1, k2, p1, p2; OPENCV_FISHEYE fx, fy, cx, cy, k1, k2, k3, k4. The "
                     "centre of the top-left pixel is (0.5, 0.5).")
      .def(py::init(&Camera::FromColmap), py::arg("model"), py::arg("params"),
           "From COLMAP's model name and parameter list (a cameras.txt line without width and "
           "height), e.g. Camera('PINHOLE', [fx, fy, cx, cy]). ValueError for an unknown model, "
           "a wrong parameter count or bad values.")
      .def_static(
          "pinhole",
          [](double fx, double fy, double cx, double cy) {
            return Camera::FromColmap("PINHOLE", {fx, fy, cx, cy});
          },
          py::arg("fx"), py::arg("fy"), py::arg("cx"), py::arg("cy"), "The PINHOLE camera.")
      .def_property_readonly(
          "model", [](const Camera& camera) { return CameraModelName(camera.model); },
          "COLMAP's model name")
      .def_property_readonly(
          "params",
          [](const Camera& camera) {
            return std::vector<double>(camera.params.begin(),
                                       camera.params.begin() + NumCameraParams(camera.model));
          },
          "COLMAP's parameters of the model (a list)")
      .def_property_readonly("focal_x", &Camera::FocalX)
      .def_property_readonly("focal_y", &Camera::FocalY)
      .def_property_readonly("is_pinhole", &Camera::IsPinhole, "no distortion")
      .def(
          "project",
          [](Camera camera, const py::object& points) {  // a copy: used without the GIL
            const std::vector<Eigen::Vector3d> in_cam = ToPoints3(points, "points_in_cam");
            std::vector<Eigen::Vector2d> pixels(in_cam.size());
            {
              py::gil_scoped_release release;
              for (std::size_t n = 0; n < in_cam.size(); ++n) {
                if (!camera.Project(in_cam[n].data(), pixels[n].data())) {
                  throw py::value_error("trigrav: Camera.project: points_in_cam[" +
                                        std::to_string(n) +
                                        "] is not in front of the camera (z <= 0)");
                }
              }
            }
            return ToArray(pixels);
          },
          py::arg("points_in_cam"), "N x 3 points (z > 0) in the camera frame -> N x 2 pixels")
      .def(
          "unproject",
          [](Camera camera, const py::object& pixels) {  // a copy: used without the GIL
            const std::vector<Eigen::Vector2d> in_image = ToPoints2(pixels, "pixels");
            std::vector<Eigen::Vector3d> rays(in_image.size());
            {
              py::gil_scoped_release release;
              for (std::size_t n = 0; n < in_image.size(); ++n) {
                if (!camera.Unproject(in_image[n], &rays[n])) {
                  throw py::value_error("trigrav: Camera.unproject: pixels[" + std::to_string(n) +
                                        "] cannot be unprojected (not finite, or outside the "
                                        "model's image of the front hemisphere)");
                }
              }
            }
            return ToArray(rays);
          },
          py::arg("pixels"), "N x 2 pixels -> N x 3 rays (u, v, 1) whose projections they are")
      .def("__repr__", [](const Camera& camera) {
        std::string repr = std::string("Camera('") + CameraModelName(camera.model) + "', [";
        for (int i = 0; i < NumCameraParams(camera.model); ++i) {
          repr += (i ? ", " : "") + Format("%.17g", camera.params[i]);
        }
        return repr + "])";
      });
}

void BindObservations(py::module_& m) {
  const auto set_cameras = [](ThreeViewObservations& observations, const py::object& cameras) {
    if (py::isinstance<Camera>(cameras)) {
      observations.cameras.fill(cameras.cast<Camera>());
      return;
    }
    if (!py::isinstance<py::sequence>(cameras) || py::len(cameras) != 3) {
      throw py::value_error("trigrav: cameras: expected a Camera or a sequence of three");
    }
    for (int k = 0; k < 3; ++k) {
      const py::object camera = py::sequence(cameras)[k];
      if (!py::isinstance<Camera>(camera)) {
        throw py::value_error("trigrav: cameras[" + std::to_string(k) + "]: expected a Camera");
      }
      observations.cameras[k] = camera.cast<Camera>();
    }
  };
  // Three per-view arrays (pixels or bearings): a sequence of three, or a (3, N, D) array.
  const auto per_view = [](const py::object& views, const char* name, const auto& convert) {
    if (!py::isinstance<py::sequence>(views) || py::isinstance<py::str>(views) ||
        py::len(views) != 3) {
      throw py::value_error(std::string("trigrav: ") + name +
                            ": expected three arrays, one per view");
    }
    using Points = decltype(convert(py::object(), std::string()));
    std::array<Points, 3> result;
    for (int k = 0; k < 3; ++k) {
      result[k] =
          convert(py::sequence(views)[k], std::string(name) + "[" + std::to_string(k) + "]");
    }
    return result;
  };
  const auto set_pixels = [per_view](ThreeViewObservations& observations, const py::object& v) {
    observations.pixels = per_view(v, "pixels", [](const py::handle& h, const std::string& name) {
      return ToPoints2(h, name);
    });
  };
  const auto set_bearings = [per_view](ThreeViewObservations& observations, const py::object& v) {
    observations.bearings =
        per_view(v, "bearings",
                 [](const py::handle& h, const std::string& name) { return ToPoints3(h, name); });
  };
  const auto set_gravity = [](ThreeViewObservations& observations, const py::object& gravity) {
    observations.gravity_in_cam = ToThreeVectors(gravity, "gravity_in_cam");
  };
  const auto views_to_list = [](const auto& views) {
    py::list list;
    for (const auto& points : views) list.append(ToArray(points));
    return list;
  };

  py::class_<ThreeViewObservations>(
      m, "ThreeViewObservations",
      "Three views' point triplets and gravity. Triplets as pixels (with a Camera per view) or as "
      "bearings (unit directions in each camera's frame, no cameras). Nothing has a usable "
      "default: the calls (and check()) raise ValueError for unset cameras or gravity.")
      .def(py::init([=](const py::object& pixels, const py::object& cameras,
                        const py::object& gravity_in_cam, const py::object& bearings) {
             ThreeViewObservations observations;
             if (!pixels.is_none()) set_pixels(observations, pixels);
             if (!cameras.is_none()) set_cameras(observations, cameras);
             if (!gravity_in_cam.is_none()) set_gravity(observations, gravity_in_cam);
             if (!bearings.is_none()) set_bearings(observations, bearings);
             return observations;
           }),
           py::kw_only(), py::arg("pixels") = py::none(), py::arg("cameras") = py::none(),
           py::arg("gravity_in_cam") = py::none(), py::arg("bearings") = py::none(),
           "pixels: three N x 2 arrays (pixels[k][n]: triplet n in view k); cameras: a Camera "
           "(all views) or three; gravity_in_cam: 3 x 3 (row k: gravity, down, in camera k + 1's "
           "frame, any positive length); bearings: three N x 3 arrays, instead of pixels and "
           "cameras. Shapes and dtypes are checked here, values by check() and every call.")
      .def_property(
          "pixels",
          [views_to_list](const ThreeViewObservations& o) { return views_to_list(o.pixels); },
          set_pixels, "three N x 2 arrays (copies)")
      .def_property(
          "bearings",
          [views_to_list](const ThreeViewObservations& o) { return views_to_list(o.bearings); },
          set_bearings, "three N x 3 arrays (copies); empty when triplets are pixels")
      .def_property(
          "cameras",
          [](const ThreeViewObservations& o) {
            return std::vector<Camera>(o.cameras.begin(), o.cameras.end());
          },
          set_cameras, "the camera of each view (a list of three copies)")
      .def_property(
          "gravity_in_cam",
          [](const ThreeViewObservations& o) { return RowsToArray(o.gravity_in_cam); }, set_gravity,
          "3 x 3: row k is gravity (down) in camera k + 1's frame (a copy)")
      .def("has_bearings", &ThreeViewObservations::HasBearings)
      .def("__len__", &ThreeViewObservations::size, "number of triplets")
      .def(
          "check",
          [](const ThreeViewObservations& o) {
            const ThreeViewObservations copy = o;  // checked without the GIL
            py::gil_scoped_release release;
            copy.Check();
          },
          "ValueError naming the problem: sizes differ, unset cameras or gravity, NaN, pixels "
          "the camera cannot unproject, ...")
      .def("__repr__", [](const ThreeViewObservations& o) {
        return "ThreeViewObservations(" + std::to_string(o.size()) + " triplets as " +
               (o.HasBearings() ? "bearings" : "pixels") + ")";
      });
}

void BindGravity(py::module_& m) {
  m.def("rotation_about_y", &RotationAboutY, py::arg("theta_rad"),
        "R_y(theta) = [[cos, 0, sin], [0, 1, 0], [-sin, 0, cos]]");
  m.def(
      "gravity_alignment_from_gravity",
      [](const py::object& gravity) {
        return GravityAlignmentFromGravity(ToVector3(gravity, "gravity_in_cam"));
      },
      py::arg("gravity_in_cam"),
      "A rotation R_align with R_align @ g = |g| e_y (x_aligned = R_align @ x_cam).");
  m.def("gravity_alignment_from_pitch_roll", &GravityAlignmentFromPitchRoll, py::arg("pitch_rad"),
        py::arg("roll_rad"),
        "(R_x(pitch) R_z(roll)).T, for a camera with world-to-camera rotation R_x(pitch) "
        "R_z(roll) R_y(yaw), world y along gravity.");
  m.def(
      "gravity_in_camera",
      [](const py::object& alignment) {
        return GravityInCamera(ToMatrix3(alignment, "gravity_alignment"));
      },
      py::arg("gravity_alignment"), "Unit gravity (down) in the camera: R_align.T @ e_y.");
  m.def(
      "align_rays",
      [](const py::object& alignment, const py::object& rays) {
        return ToArray(
            AlignRays(ToMatrix3(alignment, "gravity_alignment"), ToPoints3(rays, "rays_in_cam")));
      },
      py::arg("gravity_alignment"), py::arg("rays_in_cam"), "N x 3 rays -> R_align @ rays");
  m.def(
      "unalign_pose",
      [](const CameraPose& pose, const py::object& alignment_ref, const py::object& alignment_cam) {
        return UnalignPose(pose, ToMatrix3(alignment_ref, "gravity_alignment_ref"),
                           ToMatrix3(alignment_cam, "gravity_alignment_cam"));
      },
      py::arg("aligned_cam_from_aligned_ref"), py::arg("gravity_alignment_ref"),
      py::arg("gravity_alignment_cam"),
      "A pose between aligned frames mapped back to the camera frames: R_cam.T @ R @ R_ref, "
      "R_cam.T @ t.");
}

}  // namespace

void BindGeometry(py::module_& m) {
  BindPoses(m);
  BindCamera(m);
  BindObservations(m);
  BindGravity(m);
}

}  // namespace trigrav::python
