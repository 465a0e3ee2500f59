#ifndef TRIGRAV_PYTHON_NUMPY_INPUT_H_
#define TRIGRAV_PYTHON_NUMPY_INPUT_H_

// Conversions between numpy and the library's Eigen types, shared by the binding files.
// Input: any array-like of real numbers (a float or integer dtype, converted to float64); other
// dtypes (bool, complex, object, strings) and wrong shapes raise ValueError naming the argument
// and what it got. Values are not checked here: the library's Check() functions reject NaN.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace trigrav::python {

namespace py = pybind11;

// N x 2 (pixels) and N x 3 (rays, points) arrays.
std::vector<Eigen::Vector2d> ToPoints2(const py::handle& object, const std::string& name);
std::vector<Eigen::Vector3d> ToPoints3(const py::handle& object, const std::string& name);
// A 3-vector (shape (3,)) and a 3 x 3 matrix.
Eigen::Vector3d ToVector3(const py::handle& object, const std::string& name);
Eigen::Matrix3d ToMatrix3(const py::handle& object, const std::string& name);
// Three 3-vectors, one per camera: a 3 x 3 array (row k: camera k + 1) or a sequence of three
// 3-vectors.
std::array<Eigen::Vector3d, 3> ToThreeVectors(const py::handle& object, const std::string& name);
// A per-triplet mask of length N: bool or integer (non-zero: set).
std::vector<char> ToMask(const py::handle& object, const std::string& name);

// N x D float64 arrays of points, and bool arrays of masks (copies).
py::array_t<double> ToArray(const std::vector<Eigen::Vector2d>& points);
py::array_t<double> ToArray(const std::vector<Eigen::Vector3d>& points);
py::array_t<bool> MaskToArray(const std::vector<char>& mask);
// (3, 3) array whose row k is vectors[k].
py::array_t<double> RowsToArray(const std::array<Eigen::Vector3d, 3>& vectors);

}  // namespace trigrav::python

#endif  // TRIGRAV_PYTHON_NUMPY_INPUT_H_
