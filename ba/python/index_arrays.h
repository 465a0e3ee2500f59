#ifndef TRIGRAV_PYTHON_INDEX_ARRAYS_H_
#define TRIGRAV_PYTHON_INDEX_ARRAYS_H_

// Integer arrays (ids, keypoint indices, matches, tracks) between numpy and std::vector, for
// bind_nview.cc and bind_colmap.cc. Input: any array-like of an integer dtype (an empty list or
// array of any dtype is empty) with values in the range of the C++ type; anything else raises
// ValueError naming the argument. Output: C-contiguous numpy copies.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

namespace trigrav::python {

namespace py = pybind11;

// Rows of `Columns` integers (Columns == 0: a 1-D array), each value checked against T's range.
template <typename T, int Columns>
py::array_t<std::int64_t> ToInt64Array(const py::handle& object, const std::string& name) {
  const std::string what = Columns == 0
                               ? std::string("a 1-D array of integers")
                               : "an N x " + std::to_string(Columns) + " array of integers";
  const auto fail = [&](const std::string& got) {
    throw py::value_error("trigrav: " + name + ": expected " + what + ", got " + got);
  };
  if (object.is_none()) fail("None");
  py::array array = py::array::ensure(object);
  if (!array) {
    PyErr_Clear();
    fail("an object numpy cannot convert (" + std::string(py::str(py::type::of(object))) + ")");
  }
  if (array.size() == 0) {
    return py::array_t<std::int64_t>(Columns == 0 ? std::vector<py::ssize_t>{0}
                                                  : std::vector<py::ssize_t>{0, Columns});
  }
  const char kind = array.dtype().kind();
  if (kind != 'i' && kind != 'u') {
    fail("dtype " + std::string(py::str(array.dtype())) + " (integers needed)");
  }
  const bool shape_ok =
      Columns == 0 ? array.ndim() == 1 : array.ndim() == 2 && array.shape(1) == Columns;
  if (!shape_ok) fail("shape " + std::string(py::str(array.attr("shape"))));
  if (kind == 'u' && array.dtype().itemsize() == 8) {
    // uint64 values above int64's range would wrap in the conversion below.
    const auto as_u64 =
        py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>::ensure(array);
    for (py::ssize_t i = 0; i < as_u64.size(); ++i) {
      if (as_u64.data()[i] > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
        fail("value " + std::to_string(as_u64.data()[i]) + " out of range");
      }
    }
  }
  auto values = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(array);
  const std::int64_t low = static_cast<std::int64_t>(std::numeric_limits<T>::min());
  const std::int64_t high = sizeof(T) >= sizeof(std::int64_t)
                                ? std::numeric_limits<std::int64_t>::max()
                                : static_cast<std::int64_t>(std::numeric_limits<T>::max());
  for (py::ssize_t i = 0; i < values.size(); ++i) {
    const std::int64_t v = values.data()[i];
    if (v < low || v > high) {
      throw py::value_error("trigrav: " + name + ": value " + std::to_string(v) +
                            " at flat index " + std::to_string(i) + " out of range [" +
                            std::to_string(low) + ", " + std::to_string(high) + "]");
    }
  }
  return values;
}

template <typename T>
std::vector<T> ToIndexVector(const py::handle& object, const std::string& name) {
  const py::array_t<std::int64_t> values = ToInt64Array<T, 0>(object, name);
  return std::vector<T>(values.data(), values.data() + values.size());
}

template <typename T, int Columns>
std::vector<std::array<T, Columns>> ToIndexRows(const py::handle& object, const std::string& name) {
  const py::array_t<std::int64_t> values = ToInt64Array<T, Columns>(object, name);
  std::vector<std::array<T, Columns>> rows(static_cast<std::size_t>(values.size() / Columns));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (int c = 0; c < Columns; ++c) rows[r][c] = static_cast<T>(values.data()[r * Columns + c]);
  }
  return rows;
}

// numpy copies: (N,) of T, and N x Columns of T.
template <typename T>
py::array_t<T> VectorToArray(const std::vector<T>& values) {
  py::array_t<T> array(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), array.mutable_data());
  return array;
}

template <typename T, std::size_t Columns>
py::array_t<T> IndexRowsToArray(const std::vector<std::array<T, Columns>>& rows) {
  py::array_t<T> array({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(Columns)});
  T* data = array.mutable_data();
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (std::size_t c = 0; c < Columns; ++c) data[r * Columns + c] = rows[r][c];
  }
  return array;
}

}  // namespace trigrav::python

#endif  // TRIGRAV_PYTHON_INDEX_ARRAYS_H_
