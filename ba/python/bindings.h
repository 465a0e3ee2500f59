#ifndef TRIGRAV_PYTHON_BINDINGS_H_
#define TRIGRAV_PYTHON_BINDINGS_H_

// One function per area of the module; module.cc calls them in this order (later areas use the
// types of earlier ones as defaults and members).

#include <pybind11/pybind11.h>

#include <algorithm>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace trigrav::python {

namespace py = pybind11;

void BindGeometry(py::module_& m);    // CameraPose, ThreeViewPose, Camera, observations, gravity
void BindSolvers(py::module_& m);     // the minimal and non-minimal solvers
void BindRobust(py::module_& m);      // RANSAC options and the robust estimate
void BindRefine(py::module_& m);      // bundle adjustment, refine-only, InitializeAndRefine, batch
void BindEvaluation(py::module_& m);  // synthetic scenes and error metrics
void BindNView(py::module_& m);       // N-view bundle adjustment: RefineWithGravity
void BindColmap(py::module_& m);      // trigrav::colmap (built with it): models, database, triplets

// An options struct as a Python class: construction from keyword arguments (each a field; then the
// struct's Check(), so bad values raise ValueError), the fields as attributes, and a repr listing
// every field. Each field is declared once, with Field():
//   OptionsClass<RansacOptions>(m, "RansacOptions", doc)
//       .Field("max_error", &RansacOptions::max_error, "...")
//       .Finish(&RansacOptions::Check);
template <typename T>
class OptionsClass {
 public:
  OptionsClass(py::handle scope, const char* name, const char* doc)
      : class_(scope, name, doc),
        name_(name),
        fields_(std::make_shared<std::vector<std::string>>()) {}

  // A field of T or of a base of T (e.g. the shared BundleAdjustmentOptions).
  template <typename Value, typename Owner>
  OptionsClass& Field(const char* name, Value Owner::*member, const char* doc) {
    static_assert(std::is_base_of_v<Owner, T>, "a field of T or of one of its bases");
    class_.def_readwrite(name, member, doc);
    fields_->push_back(name);
    return *this;
  }
  py::class_<T>& cls() { return class_; }

  void Finish(void (T::*check)() const) {
    const auto fields = fields_;
    const std::string name = name_;
    class_.def(
        py::init([fields, name, check](const py::kwargs& kwargs) {
          py::object self = py::cast(T{});
          for (const auto& item : kwargs) {
            const std::string key = py::str(item.first);
            if (std::find(fields->begin(), fields->end(), key) == fields->end()) {
              throw py::type_error(name + "() got an unexpected keyword argument '" + key + "'");
            }
            py::setattr(self, key.c_str(), item.second);
          }
          T result = self.cast<T>();
          if (check != nullptr) (result.*check)();
          return result;
        }),
        "Keyword arguments set fields of the same name; the rest keep their defaults.");
    class_.def("__repr__", [fields, name](const py::object& self) {
      std::string repr = name + "(";
      for (std::size_t i = 0; i < fields->size(); ++i) {
        const py::object value = self.attr((*fields)[i].c_str());
        // Enumerators print as Type.NAME (their str), everything else as its repr.
        const bool is_enum = py::hasattr(py::type::of(value), "__members__");
        repr += (i ? ", " : "") + (*fields)[i] + "=" +
                std::string(is_enum ? py::str(value) : py::repr(value));
      }
      return repr + ")";
    });
  }

 private:
  py::class_<T> class_;
  std::string name_;
  std::shared_ptr<std::vector<std::string>> fields_;
};

}  // namespace trigrav::python

#endif  // TRIGRAV_PYTHON_BINDINGS_H_
