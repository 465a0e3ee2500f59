#include "numpy_input.h"

#include <cstddef>
#include <cstdint>

namespace trigrav::python {
namespace {

std::string ShapeString(const py::array& array) {
  std::string shape = "(";
  for (py::ssize_t d = 0; d < array.ndim(); ++d) {
    shape +=
        std::to_string(array.shape(d)) + (array.ndim() == 1 || d + 1 < array.ndim() ? "," : "");
    if (d + 1 < array.ndim()) shape += " ";
  }
  return shape + ")";
}

// A numpy masked array would lose its mask in the conversion: refused, the remedy named.
void RejectMasked(const py::handle& object, const std::string& name) {
  const py::module_ numpy_ma = py::module_::import("numpy.ma");
  if (py::isinstance(object, numpy_ma.attr("MaskedArray"))) {
    throw py::value_error("trigrav: " + name +
                          ": a masked array (its mask would be ignored); pass the unmasked rows "
                          "(a.compressed() per column, or a[~a.mask.any(axis=1)].data) or "
                          "a.filled()");
  }
}

// The object as a C-contiguous float64 array of the given shape (-1: any length), or ValueError
// "trigrav: <name>: expected <what>, got ...".
py::array_t<double> ToFloat64(const py::handle& object,
                              const std::string& name,
                              std::initializer_list<py::ssize_t> shape,
                              const char* what) {
  const auto fail = [&](const std::string& got) {
    throw py::value_error("trigrav: " + name + ": expected " + what + ", got " + got);
  };
  if (object.is_none()) fail("None");
  RejectMasked(object, name);
  py::array array = py::array::ensure(object);
  if (!array) {
    PyErr_Clear();
    fail("an object numpy cannot convert (" + std::string(py::str(py::type::of(object))) + ")");
  }
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    fail("dtype " + std::string(py::str(array.dtype())) + " (real numbers needed)");
  }
  bool shape_ok = array.ndim() == static_cast<py::ssize_t>(shape.size());
  py::ssize_t d = 0;
  for (const py::ssize_t size : shape) {
    if (shape_ok && size >= 0 && array.shape(d) != size) shape_ok = false;
    ++d;
  }
  if (!shape_ok) fail("shape " + ShapeString(array));
  return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
}

template <int D>
std::vector<Eigen::Matrix<double, D, 1>> ToPoints(const py::handle& object,
                                                  const std::string& name,
                                                  const char* what) {
  const py::array_t<double> array = ToFloat64(object, name, {-1, D}, what);
  const double* data = array.data();
  std::vector<Eigen::Matrix<double, D, 1>> points(static_cast<std::size_t>(array.shape(0)));
  for (std::size_t n = 0; n < points.size(); ++n) {
    points[n] = Eigen::Map<const Eigen::Matrix<double, D, 1>>(data + D * n);
  }
  return points;
}

template <int D>
py::array_t<double> PointsToArray(const std::vector<Eigen::Matrix<double, D, 1>>& points) {
  py::array_t<double> array({static_cast<py::ssize_t>(points.size()), static_cast<py::ssize_t>(D)});
  double* data = array.mutable_data();
  for (std::size_t n = 0; n < points.size(); ++n) {
    Eigen::Map<Eigen::Matrix<double, D, 1>>(data + D * n) = points[n];
  }
  return array;
}

}  // namespace

std::vector<Eigen::Vector2d> ToPoints2(const py::handle& object, const std::string& name) {
  return ToPoints<2>(object, name, "an N x 2 array of real numbers");
}

std::vector<Eigen::Vector3d> ToPoints3(const py::handle& object, const std::string& name) {
  return ToPoints<3>(object, name, "an N x 3 array of real numbers");
}

Eigen::Vector3d ToVector3(const py::handle& object, const std::string& name) {
  const py::array_t<double> array = ToFloat64(object, name, {3}, "a 3-vector of real numbers");
  return Eigen::Map<const Eigen::Vector3d>(array.data());
}

Eigen::Matrix3d ToMatrix3(const py::handle& object, const std::string& name) {
  const py::array_t<double> array =
      ToFloat64(object, name, {3, 3}, "a 3 x 3 array of real numbers");
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(array.data());
}

std::array<Eigen::Vector3d, 3> ToThreeVectors(const py::handle& object, const std::string& name) {
  const py::array_t<double> array =
      ToFloat64(object, name, {3, 3}, "three 3-vectors (a 3 x 3 array, row k for camera k + 1)");
  std::array<Eigen::Vector3d, 3> vectors;
  for (int k = 0; k < 3; ++k) vectors[k] = Eigen::Map<const Eigen::Vector3d>(array.data() + 3 * k);
  return vectors;
}

std::vector<char> ToMask(const py::handle& object, const std::string& name) {
  const auto fail = [&](const std::string& got) {
    throw py::value_error("trigrav: " + name + ": expected a 1-D bool array (one entry per " +
                          "triplet), got " + got);
  };
  if (object.is_none()) fail("None");
  RejectMasked(object, name);
  py::array array = py::array::ensure(object);
  if (!array) {
    PyErr_Clear();
    fail("an object numpy cannot convert");
  }
  const char kind = array.dtype().kind();
  if (kind != 'b' && kind != 'i' && kind != 'u')
    fail("dtype " + std::string(py::str(array.dtype())));
  if (array.ndim() != 1) fail("shape " + ShapeString(array));
  // Integers must be 0 / 1: an index array (np.flatnonzero) is not a mask.
  if (kind != 'b') {
    const auto values =
        py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(array);
    for (py::ssize_t n = 0; n < values.shape(0); ++n) {
      if (values.data()[n] != 0 && values.data()[n] != 1) {
        fail("integers other than 0 and 1 (an index array? give a bool mask)");
      }
    }
  }
  const auto flags = py::array_t<bool, py::array::c_style | py::array::forcecast>::ensure(
      array.attr("astype")("bool"));
  std::vector<char> mask(static_cast<std::size_t>(flags.shape(0)));
  for (std::size_t n = 0; n < mask.size(); ++n) mask[n] = flags.data()[n] ? 1 : 0;
  return mask;
}

py::array_t<double> ToArray(const std::vector<Eigen::Vector2d>& points) {
  return PointsToArray<2>(points);
}

py::array_t<double> ToArray(const std::vector<Eigen::Vector3d>& points) {
  return PointsToArray<3>(points);
}

py::array_t<bool> MaskToArray(const std::vector<char>& mask) {
  py::array_t<bool> array(static_cast<py::ssize_t>(mask.size()));
  bool* data = array.mutable_data();
  for (std::size_t n = 0; n < mask.size(); ++n) data[n] = mask[n] != 0;
  return array;
}

py::array_t<double> RowsToArray(const std::array<Eigen::Vector3d, 3>& vectors) {
  py::array_t<double> array({3, 3});
  for (int k = 0; k < 3; ++k) {
    Eigen::Map<Eigen::Vector3d>(array.mutable_data() + 3 * k) = vectors[k];
  }
  return array;
}

}  // namespace trigrav::python
