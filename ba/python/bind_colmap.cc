// trigrav::colmap from Python, in the style of pycolmap: COLMAP 3.8 models (text and binary, the
// safe set write), the read-only database reader, the gravity CSV, a model <-> the N-view bundle
// adjustment's input, and what examples/colmap/triplet_initializer runs per database: the match
// graph, three-view tracks, triplet selection, the triplet verdict, CSV and seed model.
//
// Errors: a missing input file or folder raises FileNotFoundError; a failed write (I/O, a folder
// that holds other files) OSError; malformed content and invalid values ValueError; each with the
// C++ message, which names the file and line, record or id.

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bindings.h"
#include "index_arrays.h"
#include "numpy_input.h"
#include "trigrav/colmap/database.h"
#include "trigrav/colmap/gravity_csv.h"
#include "trigrav/colmap/match_graph.h"
#include "trigrav/colmap/model_io.h"
#include "trigrav/colmap/nview_conversion.h"
#include "trigrav/colmap/reconstruction.h"
#include "trigrav/colmap/triplet_csv.h"
#include "trigrav/colmap/triplet_model.h"

namespace trigrav::python {
namespace {

namespace colmap = trigrav::colmap;
namespace fs = std::filesystem;

[[noreturn]] void RaiseOSError(PyObject* type, const std::string& message) {
  PyErr_SetString(type, message.c_str());
  throw py::error_already_set();
}

// FileNotFoundError unless `path` exists (as a regular file or a folder, as `kind` says).
void RequireInput(const std::string& path, const char* what, bool folder) {
  std::error_code error;
  const bool ok = folder ? fs::is_directory(path, error) : fs::is_regular_file(path, error);
  if (!ok) {
    RaiseOSError(PyExc_FileNotFoundError, std::string("trigrav: ") + what + " " + path +
                                              (folder ? ": no such folder" : ": no such file"));
  }
}

// Runs `work` without the GIL; its std::invalid_argument becomes ValueError and its other
// std::runtime_error / filesystem_error OSError (the writers throw those for I/O problems).
template <typename Work>
void RunWrite(Work&& work) {
  std::string invalid, io;
  {
    py::gil_scoped_release release;
    try {
      work();
    } catch (const std::invalid_argument& e) {
      invalid = e.what();
    } catch (const std::exception& e) {
      io = e.what();
    }
  }
  if (!invalid.empty()) throw py::value_error(invalid);
  if (!io.empty()) RaiseOSError(PyExc_OSError, io);
}

// Point3D ids as int64 with -1 for "none" (COLMAP's images.txt spelling of kInvalidPoint3DId).
py::array_t<std::int64_t> Point3DIdsToArray(const std::vector<colmap::Point3DId>& ids) {
  py::array_t<std::int64_t> array(static_cast<py::ssize_t>(ids.size()));
  for (std::size_t i = 0; i < ids.size(); ++i) {
    array.mutable_data()[i] =
        ids[i] == colmap::kInvalidPoint3DId ? -1 : static_cast<std::int64_t>(ids[i]);
  }
  return array;
}

std::vector<colmap::Point3DId> ToPoint3DIds(const py::handle& object, const std::string& name) {
  const py::array_t<std::int64_t> values = ToInt64Array<std::int64_t, 0>(object, name);
  std::vector<colmap::Point3DId> ids(static_cast<std::size_t>(values.size()));
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const std::int64_t v = values.data()[i];
    if (v < -1) {
      throw py::value_error("trigrav: " + name + "[" + std::to_string(i) +
                            "] = " + std::to_string(v) + ": point3D ids are >= 0, or -1 for none");
    }
    ids[i] = v == -1 ? colmap::kInvalidPoint3DId : static_cast<colmap::Point3DId>(v);
  }
  return ids;
}

colmap::GravityByImageName ToGravity(const py::handle& object, const std::string& name) {
  if (!py::isinstance<py::dict>(object)) {
    throw py::type_error("trigrav: " + name + ": expected a dict {image name: 3-vector}, got " +
                         std::string(py::str(py::type::of(object))));
  }
  colmap::GravityByImageName gravity;
  for (const auto& item : py::reinterpret_borrow<py::dict>(object)) {
    if (!py::isinstance<py::str>(item.first)) {
      throw py::type_error("trigrav: " + name + ": keys must be image names (str), got " +
                           std::string(py::repr(item.first)));
    }
    const std::string key = py::str(item.first);
    gravity[key] = ToVector3(item.second, name + "['" + key + "']");
  }
  return gravity;
}

py::dict GravityToDict(const colmap::GravityByImageName& gravity) {
  py::dict dict;
  for (const auto& [name, g] : gravity) dict[py::str(name)] = py::cast(Eigen::Vector3d(g));
  return dict;
}

std::array<colmap::ImageId, 3> ToTriplet(const py::handle& object, const std::string& name) {
  const std::vector<colmap::ImageId> ids = ToIndexVector<colmap::ImageId>(object, name);
  if (ids.size() != 3) {
    throw py::value_error("trigrav: " + name + ": expected 3 image ids, got " +
                          std::to_string(ids.size()));
  }
  return {ids[0], ids[1], ids[2]};
}

// A database opened read-only, closed by close() or the end of a `with` block. Calls release the
// GIL; one call at a time per object (the mutex).
struct DatabaseHandle {
  std::string path;
  std::unique_ptr<colmap::Database> database;
  std::mutex mutex;

  template <typename Work>
  auto Call(Work&& work) -> decltype(work(std::declval<const colmap::Database&>())) {
    std::string error;
    decltype(work(std::declval<const colmap::Database&>())) result;
    {
      py::gil_scoped_release release;
      std::lock_guard<std::mutex> lock(mutex);
      try {
        if (!database) throw std::runtime_error("trigrav: the database " + path + " is closed");
        result = work(*database);
      } catch (const std::exception& e) {
        error = e.what();
      }
    }
    if (!error.empty()) throw py::value_error(error);
    return result;
  }
};

void BindModel(py::module_& m) {
  py::enum_<colmap::ModelFormat>(m, "ModelFormat", "COLMAP model files: .txt or .bin.")
      .value("TEXT", colmap::ModelFormat::kText)
      .value("BINARY", colmap::ModelFormat::kBinary);

  py::class_<colmap::ColmapCamera>(m, "ColmapCamera", "A camera of a COLMAP model or database.")
      .def(py::init([](colmap::CameraId camera_id, const Camera& camera, int width, int height) {
             return colmap::ColmapCamera{camera_id, camera, width, height};
           }),
           py::arg("camera_id"), py::arg("camera"), py::arg("width"), py::arg("height"))
      .def_readwrite("camera_id", &colmap::ColmapCamera::camera_id)
      .def_readwrite("camera", &colmap::ColmapCamera::camera, "Camera (model and parameters)")
      .def_readwrite("width", &colmap::ColmapCamera::width)
      .def_readwrite("height", &colmap::ColmapCamera::height)
      .def("__repr__", [](const colmap::ColmapCamera& c) {
        return "ColmapCamera(camera_id=" + std::to_string(c.camera_id) +
               ", camera=" + std::string(py::repr(py::cast(c.camera))) +
               ", width=" + std::to_string(c.width) + ", height=" + std::to_string(c.height) + ")";
      });

  py::class_<colmap::ColmapImage>(m, "ColmapImage",
                                  "A registered image of a COLMAP model: pose, keypoints and "
                                  "the 3D point each observes. Array properties are copies.")
      .def(py::init([](colmap::ImageId image_id, const std::string& name,
                       colmap::CameraId camera_id, const CameraPose& cam_from_world,
                       const py::object& points2D, const py::object& point3D_ids) {
             colmap::ColmapImage image;
             image.image_id = image_id;
             image.name = name;
             image.camera_id = camera_id;
             image.cam_from_world = cam_from_world;
             if (!points2D.is_none()) image.points2D = ToPoints2(points2D, "points2D");
             if (point3D_ids.is_none()) {
               image.point3D_ids.assign(image.points2D.size(), colmap::kInvalidPoint3DId);
             } else {
               image.point3D_ids = ToPoint3DIds(point3D_ids, "point3D_ids");
             }
             return image;
           }),
           py::arg("image_id"), py::arg("name"), py::arg("camera_id"),
           py::arg_v("cam_from_world", CameraPose(), "CameraPose()"),
           py::arg("points2D") = py::none(), py::arg("point3D_ids") = py::none(),
           "points2D: N x 2 keypoints (pixels); point3D_ids: (N,) the 3D point of each, -1 for "
           "none (default: all -1).")
      .def_readwrite("image_id", &colmap::ColmapImage::image_id)
      .def_readwrite("name", &colmap::ColmapImage::name)
      .def_readwrite("camera_id", &colmap::ColmapImage::camera_id)
      .def_readwrite("cam_from_world", &colmap::ColmapImage::cam_from_world,
                     "CameraPose: x_cam = R x_world + t")
      .def_property(
          "points2D", [](const colmap::ColmapImage& i) { return ToArray(i.points2D); },
          [](colmap::ColmapImage& i, const py::object& p) {
            i.points2D = ToPoints2(p, "points2D");
          },
          "N x 2 keypoints (pixels, (0.5, 0.5) the centre of the top-left pixel)")
      .def_property(
          "point3D_ids",
          [](const colmap::ColmapImage& i) { return Point3DIdsToArray(i.point3D_ids); },
          [](colmap::ColmapImage& i, const py::object& ids) {
            i.point3D_ids = ToPoint3DIds(ids, "point3D_ids");
          },
          "(N,) int64: the 3D point of each keypoint, -1 for none")
      .def("__repr__", [](const colmap::ColmapImage& i) {
        return "ColmapImage(image_id=" + std::to_string(i.image_id) +
               ", name=" + std::string(py::repr(py::str(i.name))) +
               ", camera_id=" + std::to_string(i.camera_id) +
               ", points2D=" + std::to_string(i.points2D.size()) + ")";
      });

  py::class_<colmap::ColmapPoint3D>(m, "ColmapPoint3D", "A 3D point of a COLMAP model.")
      .def(py::init([](const py::object& xyz, const py::object& color, double error,
                       const py::object& track) {
             colmap::ColmapPoint3D point;
             point.xyz = ToVector3(xyz, "xyz");
             if (!color.is_none()) {
               const std::vector<std::uint8_t> c = ToIndexVector<std::uint8_t>(color, "color");
               if (c.size() != 3) throw py::value_error("trigrav: color: expected 3 values");
               point.color = {c[0], c[1], c[2]};
             }
             point.error = error;
             if (!track.is_none()) {
               for (const auto& [image_id, idx] : ToIndexRows<std::uint32_t, 2>(track, "track")) {
                 point.track.push_back({image_id, idx});
               }
             }
             return point;
           }),
           py::arg("xyz"), py::arg("color") = py::none(), py::arg("error") = -1.0,
           py::arg("track") = py::none(),
           "xyz: point in the world; color: 3 values 0-255 (default black); error: mean "
           "reprojection error, -1 unknown; track: K x 2 (image_id, point2D_idx).")
      .def_property(
          "xyz", [](const colmap::ColmapPoint3D& p) { return Eigen::Vector3d(p.xyz); },
          [](colmap::ColmapPoint3D& p, const py::object& xyz) { p.xyz = ToVector3(xyz, "xyz"); },
          "(3,) point in the world (a copy)")
      .def_property(
          "color",
          [](const colmap::ColmapPoint3D& p) {
            return VectorToArray(std::vector<std::uint8_t>(p.color.begin(), p.color.end()));
          },
          [](colmap::ColmapPoint3D& p, const py::object& color) {
            const std::vector<std::uint8_t> c = ToIndexVector<std::uint8_t>(color, "color");
            if (c.size() != 3) throw py::value_error("trigrav: color: expected 3 values");
            p.color = {c[0], c[1], c[2]};
          },
          "(3,) uint8 RGB")
      .def_readwrite("error", &colmap::ColmapPoint3D::error,
                     "mean reprojection error (px), -1 unknown")
      .def_property(
          "track",
          [](const colmap::ColmapPoint3D& p) {
            std::vector<std::array<std::uint32_t, 2>> rows;
            for (const colmap::TrackElement& e : p.track)
              rows.push_back({e.image_id, e.point2D_idx});
            return IndexRowsToArray(rows);
          },
          [](colmap::ColmapPoint3D& p, const py::object& track) {
            p.track.clear();
            for (const auto& [image_id, idx] : ToIndexRows<std::uint32_t, 2>(track, "track")) {
              p.track.push_back({image_id, idx});
            }
          },
          "K x 2 uint32: (image_id, point2D_idx) of each observation")
      .def("__repr__", [](const colmap::ColmapPoint3D& p) {
        return "ColmapPoint3D(xyz=" + std::string(py::repr(py::cast(Eigen::Vector3d(p.xyz)))) +
               ", error=" + std::string(py::repr(py::float_(p.error))) +
               ", track=" + std::to_string(p.track.size()) + ")";
      });

  py::class_<colmap::Reconstruction>(
      m, "Reconstruction",
      "A COLMAP sparse model in memory. cameras, images and points3D are dicts keyed by id; "
      "reading one gives a copy (reconstruction.images[3].name = ... changes the copy only): "
      "change a copy and assign the dict back.")
      .def(py::init<>())
      // Copies both ways (def_readwrite would hand out references into the maps, left dangling
      // when a map is assigned).
      .def_property(
          "cameras", [](const colmap::Reconstruction& r) { return r.cameras; },
          [](colmap::Reconstruction& r, const std::map<colmap::CameraId, colmap::ColmapCamera>& c) {
            r.cameras = c;
          },
          "dict {camera_id: ColmapCamera} (a copy)")
      .def_property(
          "images", [](const colmap::Reconstruction& r) { return r.images; },
          [](colmap::Reconstruction& r, const std::map<colmap::ImageId, colmap::ColmapImage>& i) {
            r.images = i;
          },
          "dict {image_id: ColmapImage} (a copy)")
      .def_property(
          "points3D", [](const colmap::Reconstruction& r) { return r.points3D; },
          [](colmap::Reconstruction& r,
             const std::map<colmap::Point3DId, colmap::ColmapPoint3D>& p) { r.points3D = p; },
          "dict {point3D_id: ColmapPoint3D} (a copy)")
      .def_property_readonly("num_cameras",
                             [](const colmap::Reconstruction& r) { return r.cameras.size(); })
      .def_property_readonly("num_images",
                             [](const colmap::Reconstruction& r) { return r.images.size(); })
      .def_property_readonly("num_points3D",
                             [](const colmap::Reconstruction& r) { return r.points3D.size(); })
      .def_property_readonly(
          "point3D_ids",
          [](const colmap::Reconstruction& r) {
            std::vector<std::uint64_t> ids;
            for (const auto& [id, p] : r.points3D) ids.push_back(id);
            return VectorToArray(ids);
          },
          "(P,) uint64, increasing")
      .def_property_readonly(
          "points3D_xyz",
          [](const colmap::Reconstruction& r) {
            std::vector<Eigen::Vector3d> xyz;
            for (const auto& [id, p] : r.points3D) xyz.push_back(p.xyz);
            return ToArray(xyz);
          },
          "P x 3, in the order of point3D_ids")
      .def("check", &colmap::Reconstruction::Check,
           "ValueError naming the first inconsistency (Reconstruction::Check).")
      .def("__repr__", [](const colmap::Reconstruction& r) {
        return "Reconstruction(cameras=" + std::to_string(r.cameras.size()) +
               ", images=" + std::to_string(r.images.size()) +
               ", points3D=" + std::to_string(r.points3D.size()) + ")";
      });

  m.def(
      "read_model",
      [](const std::string& folder, const py::object& format) {
        RequireInput(folder, "model folder", true);
        const bool automatic = format.is_none();
        const colmap::ModelFormat f =
            automatic ? colmap::ModelFormat::kText : format.cast<colmap::ModelFormat>();
        colmap::Reconstruction model;
        std::string error;
        {
          py::gil_scoped_release release;
          try {
            model = automatic ? colmap::ReadModel(folder) : colmap::ReadModel(folder, f);
          } catch (const std::exception& e) {
            error = e.what();
          }
        }
        if (!error.empty()) {
          // A model file missing from an existing folder: FileNotFoundError too.
          if (error.find(": no such file") != std::string::npos) {
            RaiseOSError(PyExc_FileNotFoundError, error);
          }
          throw py::value_error(error);
        }
        return model;
      },
      py::arg("folder"), py::arg("format") = py::none(),
      "The COLMAP model in `folder` (cameras, images, points3D): binary when the three .bin "
      "files exist, else text; or the given ModelFormat. FileNotFoundError for a missing folder "
      "or file, ValueError for a malformed record (file and line or record named).");
  m.def(
      "write_model",
      [](colmap::Reconstruction model, const std::string& folder, colmap::ModelFormat format,
         bool create_parents) {
        RunWrite([&] {
          if (create_parents) {
            colmap::WriteModelCreatingParents(model, folder, format);
          } else {
            colmap::WriteModel(model, folder, format);
          }
        });
      },
      py::arg("reconstruction"), py::arg("folder"),
      py::arg_v("format", colmap::ModelFormat::kBinary, "ModelFormat.BINARY"),
      py::arg("create_parents") = false,
      "Writes the model into `folder` as one set (WriteModel: a temporary sibling folder, "
      "flushed, then swapped in by one rename: the old model or the new one, never a mix). "
      "`folder` may exist only holding a model; its parent must exist unless create_parents. "
      "ValueError for a model failing check(); OSError for I/O problems or a folder holding "
      "other files (nothing changed then).");
}

void BindDatabase(py::module_& m) {
  py::class_<colmap::DatabaseImage>(m, "DatabaseImage", "An image row of a COLMAP database.")
      .def(py::init(
               [](colmap::ImageId image_id, const std::string& name, colmap::CameraId camera_id) {
                 return colmap::DatabaseImage{image_id, name, camera_id};
               }),
           py::arg("image_id"), py::arg("name"), py::arg("camera_id"))
      .def_readwrite("image_id", &colmap::DatabaseImage::image_id)
      .def_readwrite("name", &colmap::DatabaseImage::name)
      .def_readwrite("camera_id", &colmap::DatabaseImage::camera_id)
      .def("__repr__", [](const colmap::DatabaseImage& i) {
        return "DatabaseImage(image_id=" + std::to_string(i.image_id) +
               ", name=" + std::string(py::repr(py::str(i.name))) +
               ", camera_id=" + std::to_string(i.camera_id) + ")";
      });

  py::class_<colmap::TwoViewGeometry>(m, "TwoViewGeometry",
                                      "The verified (inlier) matches of one image pair.")
      .def(py::init([](colmap::ImageId image_id1, colmap::ImageId image_id2, int config,
                       const py::object& matches) {
             colmap::TwoViewGeometry g;
             g.image_id1 = image_id1;
             g.image_id2 = image_id2;
             g.config = config;
             g.matches = ToIndexRows<std::uint32_t, 2>(matches, "matches");
             return g;
           }),
           py::arg("image_id1"), py::arg("image_id2"), py::arg("config"), py::arg("matches"),
           "matches: K x 2 keypoint indices (into image_id1's, image_id2's keypoints); config: "
           "COLMAP's TwoViewGeometry configuration (2 calibrated, 3 uncalibrated, ...).")
      .def_readwrite("image_id1", &colmap::TwoViewGeometry::image_id1)
      .def_readwrite("image_id2", &colmap::TwoViewGeometry::image_id2)
      .def_readwrite("config", &colmap::TwoViewGeometry::config)
      .def_property(
          "matches", [](const colmap::TwoViewGeometry& g) { return IndexRowsToArray(g.matches); },
          [](colmap::TwoViewGeometry& g, const py::object& matches) {
            g.matches = ToIndexRows<std::uint32_t, 2>(matches, "matches");
          },
          "K x 2 uint32 keypoint indices (a copy)")
      .def("__repr__", [](const colmap::TwoViewGeometry& g) {
        return "TwoViewGeometry(image_id1=" + std::to_string(g.image_id1) +
               ", image_id2=" + std::to_string(g.image_id2) +
               ", config=" + std::to_string(g.config) +
               ", matches=" + std::to_string(g.matches.size()) + ")";
      });

  py::class_<DatabaseHandle>(
      m, "Database",
      "A COLMAP 3.8 database opened read-only (SQLite). Use as a context manager, or close(). "
      "Reads release the GIL.")
      .def(py::init([](const std::string& path) {
             RequireInput(path, "database", false);
             auto handle = std::make_unique<DatabaseHandle>();
             handle->path = path;
             std::string error;
             {
               py::gil_scoped_release release;
               try {
                 handle->database = std::make_unique<colmap::Database>(path);
               } catch (const std::exception& e) {
                 error = e.what();
               }
             }
             if (!error.empty()) throw py::value_error(error);
             return handle;
           }),
           py::arg("path"),
           "Opens `path` read-only. FileNotFoundError when it does not exist, ValueError when it "
           "is not an SQLite database or lacks COLMAP's tables.")
      .def_readonly("path", &DatabaseHandle::path)
      .def(
          "read_cameras",
          [](DatabaseHandle& h) {
            return h.Call([](const colmap::Database& d) { return d.ReadCameras(); });
          },
          "list of ColmapCamera; ValueError for a camera model trigrav does not have")
      .def(
          "read_images",
          [](DatabaseHandle& h) {
            return h.Call([](const colmap::Database& d) { return d.ReadImages(); });
          },
          "list of DatabaseImage, in the database's order")
      .def(
          "read_keypoints",
          [](DatabaseHandle& h, colmap::ImageId image_id) {
            return ToArray(h.Call(
                [image_id](const colmap::Database& d) { return d.ReadKeypoints(image_id); }));
          },
          py::arg("image_id"),
          "N x 2 keypoint positions (pixels) of the image; ValueError for an unknown image id")
      .def(
          "read_two_view_geometries",
          [](DatabaseHandle& h) {
            return h.Call([](const colmap::Database& d) { return d.ReadTwoViewGeometries(); });
          },
          "list of TwoViewGeometry: every verified pair with at least one inlier match")
      .def(
          "close",
          [](DatabaseHandle& h) {
            py::gil_scoped_release release;
            std::lock_guard<std::mutex> lock(h.mutex);
            h.database.reset();
          },
          "Closes the connection; later reads raise ValueError.")
      .def_property_readonly("closed", [](DatabaseHandle& h) { return h.database == nullptr; })
      .def("__enter__", [](py::object self) { return self; })
      .def(
          "__exit__",
          [](DatabaseHandle& h, const py::object&, const py::object&, const py::object&) {
            py::gil_scoped_release release;
            std::lock_guard<std::mutex> lock(h.mutex);
            h.database.reset();
          },
          py::arg("exc_type"), py::arg("exc_value"), py::arg("traceback"))
      .def("__repr__", [](DatabaseHandle& h) {
        return "Database(" + std::string(py::repr(py::str(h.path))) +
               (h.database ? ")" : ", closed)");
      });

  m.def("pair_id", &colmap::PairId, py::arg("image_id1"), py::arg("image_id2"),
        "COLMAP's pair id of two images (order-independent).");
  m.def(
      "images_of_pair_id",
      [](std::uint64_t pair_id) {
        colmap::ImageId a = 0, b = 0;
        colmap::ImagesOfPairId(pair_id, &a, &b);
        return py::make_tuple(a, b);
      },
      py::arg("pair_id"), "(image_id1, image_id2), image_id1 < image_id2.");
}

void BindGravityCsv(py::module_& m) {
  m.def(
      "read_gravity_csv",
      [](const std::string& path) {
        RequireInput(path, "gravity CSV", false);
        colmap::GravityByImageName gravity;
        std::string error;
        {
          py::gil_scoped_release release;
          try {
            gravity = colmap::ReadGravityCsv(path);
          } catch (const std::exception& e) {
            error = e.what();
          }
        }
        if (!error.empty()) throw py::value_error(error);
        return GravityToDict(gravity);
      },
      py::arg("path"),
      "dict {image name: gravity (3,)} (down, in the image's camera frame). FileNotFoundError "
      "for a missing file; ValueError naming the file and line for a missing header, a "
      "malformed line, a duplicate name, a zero or non-finite vector.");
  m.def(
      "write_gravity_csv",
      [](const py::object& gravity, const std::string& path) {
        const colmap::GravityByImageName g = ToGravity(gravity, "gravity");
        for (const auto& [name, v] : g) {
          if (!v.allFinite() || v.norm() == 0.0) {
            throw py::value_error("trigrav: gravity['" + name + "']: zero or non-finite vector");
          }
        }
        RunWrite([&] { colmap::WriteGravityCsv(g, path); });
      },
      py::arg("gravity"), py::arg("path"),
      "Writes {image name: 3-vector} sorted by name with 17 significant digits. ValueError for "
      "a zero or non-finite vector (nothing written), OSError for an I/O error.");
  m.def(
      "gravity_of_images",
      [](const py::object& gravity, const std::vector<std::string>& names) {
        const colmap::GravityByImageName g = ToGravity(gravity, "gravity");
        return ToArray(colmap::GravityOfImages(g, names));
      },
      py::arg("gravity"), py::arg("image_names"),
      "N x 3: the gravity of each name; ValueError listing the names without one.");
}

void BindMatchGraph(py::module_& m) {
  py::class_<colmap::MatchGraph>(
      m, "MatchGraph",
      "The verified pair matches as a graph over the images; ambiguous matches (a keypoint in "
      "more than one match of a pair) dropped.")
      .def(py::init([](const std::vector<colmap::TwoViewGeometry>& geometries) {
             py::gil_scoped_release release;
             return std::make_unique<colmap::MatchGraph>(geometries);
           }),
           py::arg("geometries"),
           "From a list of TwoViewGeometry (Database.read_two_view_geometries).")
      .def("num_matches", &colmap::MatchGraph::NumMatches, py::arg("a"), py::arg("b"),
           "one-to-one matches of the pair (0 when none)")
      .def(
          "match",
          [](const colmap::MatchGraph& g, colmap::ImageId a, std::uint32_t keypoint_a,
             colmap::ImageId b) -> py::object {
            std::uint32_t keypoint_b = 0;
            if (!g.Match(a, keypoint_a, b, &keypoint_b)) return py::none();
            return py::int_(keypoint_b);
          },
          py::arg("a"), py::arg("keypoint_a"), py::arg("b"),
          "the keypoint of image b matched to keypoint_a of image a, or None")
      .def(
          "matches",
          [](const colmap::MatchGraph& g, colmap::ImageId a, colmap::ImageId b) {
            return IndexRowsToArray(g.Matches(a, b));
          },
          py::arg("a"), py::arg("b"), "K x 2 uint32 (keypoint of a, keypoint of b), sorted by a's")
      .def(
          "neighbors",
          [](const colmap::MatchGraph& g, colmap::ImageId image) {
            return VectorToArray(g.Neighbors(image));
          },
          py::arg("image"), "(n,) uint32: images matched to `image`, increasing");

  m.def(
      "three_view_tracks",
      [](const colmap::MatchGraph& graph, const py::object& images) {
        const std::array<colmap::ImageId, 3> triplet = ToTriplet(images, "images");
        std::vector<colmap::ThreeViewTrack> tracks;
        {
          py::gil_scoped_release release;
          tracks = colmap::ThreeViewTracks(graph, triplet);
        }
        return IndexRowsToArray(tracks);
      },
      py::arg("graph"), py::arg("images"),
      "N x 3 uint32: keypoint indices of the three-view tracks of the three images (in that "
      "order), chained through the hub image (ThreeViewTracks); sorted.");
  m.def(
      "consecutive_triplets",
      [](const py::object& images_by_name) {
        return IndexRowsToArray(colmap::ConsecutiveTriplets(
            ToIndexVector<colmap::ImageId>(images_by_name, "images_by_name")));
      },
      py::arg("images_by_name"),
      "M x 3 uint32: (i, i+1, i+2) of the image ids, sorted by name as a sequence's frames.");
  m.def(
      "connected_triplets",
      [](const colmap::MatchGraph& graph, const py::object& images_by_name, int max_triplets) {
        const std::vector<colmap::ImageId> ids =
            ToIndexVector<colmap::ImageId>(images_by_name, "images_by_name");
        std::vector<std::array<colmap::ImageId, 3>> triplets;
        std::string error;
        {
          py::gil_scoped_release release;
          try {
            triplets = colmap::ConnectedTriplets(graph, ids, max_triplets);
          } catch (const std::exception& e) {
            error = e.what();
          }
        }
        if (!error.empty()) throw py::value_error(error);
        return IndexRowsToArray(triplets);
      },
      py::arg("graph"), py::arg("images_by_name"), py::arg("max_triplets"),
      "M x 3 uint32: the best-connected triplets, greedily (ConnectedTriplets); each lists its "
      "images in the order of images_by_name. ValueError if max_triplets < 1.");
}

void BindTriplets(py::module_& m) {
  py::class_<colmap::TripletResult>(m, "TripletResult",
                                    "One triplet of a triplet initialisation: its images, "
                                    "track count and, when estimated, the estimate.")
      .def(py::init([](const std::array<colmap::DatabaseImage, 3>& images, int num_tracks,
                       bool estimated, const py::object& estimate) {
             colmap::TripletResult r;
             r.images = images;
             r.num_tracks = num_tracks;
             r.estimated = estimated;
             if (!estimate.is_none()) r.estimate = estimate.cast<ThreeViewEstimate>();
             return r;
           }),
           py::arg("images"), py::arg("num_tracks") = 0, py::arg("estimated") = false,
           py::arg("estimate") = py::none(),
           "images: 3 DatabaseImage (image 1 the reference); estimate: initialize_and_refine's "
           "answer when estimated (None: an empty ThreeViewEstimate).")
      .def_property(
          "images", [](const colmap::TripletResult& r) { return r.images; },
          [](colmap::TripletResult& r, const std::array<colmap::DatabaseImage, 3>& images) {
            r.images = images;
          },
          "list of 3 DatabaseImage (a copy)")
      .def_readwrite("num_tracks", &colmap::TripletResult::num_tracks)
      .def_readwrite("estimated", &colmap::TripletResult::estimated)
      .def_readwrite("estimate", &colmap::TripletResult::estimate, "ThreeViewEstimate")
      .def_property_readonly("verdict", &colmap::TripletVerdict, "triplet_verdict(self)")
      .def("__repr__", [](const colmap::TripletResult& r) {
        return "TripletResult(images=(" + std::string(py::repr(py::str(r.images[0].name))) + ", " +
               std::string(py::repr(py::str(r.images[1].name))) + ", " +
               std::string(py::repr(py::str(r.images[2].name))) +
               "), num_tracks=" + std::to_string(r.num_tracks) +
               ", verdict=" + std::string(py::repr(py::str(colmap::TripletVerdict(r)))) + ")";
      });
  m.def("triplet_verdict", &colmap::TripletVerdict, py::arg("result"),
        "'trusted', or the first of 'too_few_tracks', 'failed', 'unrefined', 'no_covariance' "
        "that applies.");
  m.def(
      "format_triplet_csv",
      [](const std::vector<colmap::TripletResult>& results,
         ThreeViewBundleAdjustmentOptions::RotationModel rotation_model) {
        py::gil_scoped_release release;
        return colmap::FormatTripletCsv(results, rotation_model);
      },
      py::arg("results"), py::arg("rotation_model"),
      "The per-triplet CSV text of triplet_initializer: '#' lines documenting the columns, the "
      "header, one row per result (examples/colmap/README.md, 'The triplet CSV').");
  m.def(
      "triplet_model",
      [](const std::vector<colmap::ColmapCamera>& cameras,
         const std::array<colmap::DatabaseImage, 3>& images, const py::sequence& keypoints,
         const py::object& tracks, const ThreeViewEstimate& estimate) {
        if (py::len(keypoints) != 3) {
          throw py::value_error("trigrav: keypoints: expected 3 arrays (N x 2), got " +
                                std::to_string(py::len(keypoints)));
        }
        std::array<std::vector<Eigen::Vector2d>, 3> points;
        for (int k = 0; k < 3; ++k) {
          points[k] = ToPoints2(keypoints[k], "keypoints[" + std::to_string(k) + "]");
        }
        const std::vector<colmap::ThreeViewTrack> t =
            ToIndexRows<std::uint32_t, 3>(tracks, "tracks");
        return colmap::TripletModel(cameras, images, points, t, estimate);
      },
      py::arg("cameras"), py::arg("images"), py::arg("keypoints"), py::arg("tracks"),
      py::arg("estimate"),
      "The seed model of a refined triplet (TripletModel): every camera, the three images "
      "(camera 1 the world) with all their keypoints, the refined inlier points. ValueError "
      "when the refinement did not succeed.");
}

void BindConversion(py::module_& m) {
  py::class_<colmap::NViewInput>(m, "NViewInput",
                                 "A COLMAP model as refine_with_gravity's input, with the "
                                 "COLMAP ids behind its indices.")
      .def_readwrite("reconstruction", &colmap::NViewInput::reconstruction, "NViewReconstruction")
      .def_property_readonly(
          "image_ids", [](const colmap::NViewInput& i) { return VectorToArray(i.image_ids); },
          "(N,) uint32: COLMAP image id of reconstruction.images[k]")
      .def_property_readonly(
          "point_ids", [](const colmap::NViewInput& i) { return VectorToArray(i.point_ids); },
          "(P,) uint64: COLMAP point3D id of reconstruction.points_in_world[p]");
  m.def(
      "to_nview",
      [](const colmap::Reconstruction& model, const py::object& gravity) {
        const colmap::GravityByImageName g = ToGravity(gravity, "gravity");
        py::gil_scoped_release release;
        return colmap::ToNView(model, g);
      },
      py::arg("model"), py::arg("gravity"),
      "The model (Reconstruction) with each image's gravity ({name: 3-vector}) as an "
      "NViewInput; ValueError listing the images without gravity.");
  m.def(
      "from_nview",
      [](const colmap::Reconstruction& model, const colmap::NViewInput& input,
         const NViewReconstruction& refined) {
        py::gil_scoped_release release;
        return colmap::FromNView(model, input, refined);
      },
      py::arg("model"), py::arg("input"), py::arg("refined"),
      "`model` with the poses and points of `refined` (to_nview's indices), each point's error "
      "its mean reprojection error at the refined pose.");
}

}  // namespace

void BindColmap(py::module_& m) {
  BindModel(m);
  BindDatabase(m);
  BindGravityCsv(m);
  BindMatchGraph(m);
  BindTriplets(m);
  BindConversion(m);
}

}  // namespace trigrav::python
