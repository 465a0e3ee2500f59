// The Python module `trigrav` (ba/python/README.md): numpy in, option objects built from keyword
// arguments, results with numpy arrays. One file per area binds its part (bindings.h).

#include <pybind11/pybind11.h>

#include <exception>
#include <new>

#include "bindings.h"

PYBIND11_MODULE(trigrav, m) {
  m.doc() =
      "trigrav: gravity-aware three-view relative pose (trifocal minimal solvers in RANSAC, "
      "three-view bundle adjustment with Ceres).\n\n"
      "Frames: CameraPose(R, t) maps camera 1 coordinates into the camera, x_cam = R x_ref + t; "
      "center = -R^T t. Poses are returned with |cam2_from_cam1.center| = 1. gravity_in_cam[k] is "
      "gravity (pointing down) in camera k's frame. Errors of the library (std::exception) raise "
      "ValueError with the C++ message.";
  namespace py = pybind11;
  // Every C++ exception of the library (std::invalid_argument for bad input, std::runtime_error
  // when no synthetic scene can be drawn) becomes ValueError with its message; pybind11's own
  // exceptions (TypeError, ValueError, ...) and out-of-memory keep their Python types.
  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const py::builtin_exception&) {
      throw;
    } catch (const py::error_already_set&) {
      throw;
    } catch (const std::exception& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  trigrav::python::BindGeometry(m);
  trigrav::python::BindSolvers(m);
  trigrav::python::BindRobust(m);
  trigrav::python::BindRefine(m);
  trigrav::python::BindEvaluation(m);
  trigrav::python::BindNView(m);
#ifdef TRIGRAV_PYTHON_WITH_COLMAP
  trigrav::python::BindColmap(m);
#endif
}
