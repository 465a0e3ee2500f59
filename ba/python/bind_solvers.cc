// The minimal and non-minimal solvers: rays (N x 3) in, a list of every solution out.

#include <pybind11/stl.h>

#include <optional>
#include <vector>

#include "bindings.h"
#include "numpy_input.h"
#include "trigrav/initializers/essential_5pt.h"
#include "trigrav/initializers/essential_8pt.h"
#include "trigrav/initializers/initial_solver.h"
#include "trigrav/initializers/trifocal_3pt.h"
#include "trigrav/initializers/trifocal_4pt.h"
#include "trigrav/initializers/trifocal_linear.h"
#include "trigrav/initializers/two_view_to_three_view.h"

namespace trigrav::python {
namespace {

struct Rays {
  std::vector<Eigen::Vector3d> x1, x2, x3;
};

Rays ToRays(const py::object& x1, const py::object& x2, const py::object& x3) {
  return {ToPoints3(x1, "x1"), ToPoints3(x2, "x2"), ToPoints3(x3, "x3")};
}

std::optional<std::array<Eigen::Vector3d, 3>> ToOptionalGravity(const py::object& gravity) {
  if (gravity.is_none()) return std::nullopt;
  return ToThreeVectors(gravity, "gravity_in_cam");
}

// A gravity-aware three-view solver: upright rays without gravity, raw rays and each camera's
// gravity with it; the GIL is released while it runs.
template <typename Upright, typename WithGravity>
std::vector<ThreeViewPose> SolveThreeView(const py::object& x1,
                                          const py::object& x2,
                                          const py::object& x3,
                                          const py::object& gravity_in_cam,
                                          const Upright& upright,
                                          const WithGravity& with_gravity) {
  const Rays rays = ToRays(x1, x2, x3);
  const auto gravity = ToOptionalGravity(gravity_in_cam);
  std::vector<ThreeViewPose> solutions;
  py::gil_scoped_release release;
  if (gravity) {
    with_gravity(rays, *gravity, &solutions);
  } else {
    upright(rays, &solutions);
  }
  return solutions;
}

constexpr const char* kGravityDoc =
    " Without gravity_in_cam the rays must be gravity-aligned (camera y axis along gravity, "
    "down); with it (3 x 3, row k: gravity in camera k + 1), the rays are raw and the poses are "
    "in the original frames. Returns every solution (a list of ThreeViewPose, "
    "|cam2_from_cam1.center| = 1); an empty list for degenerate data. ValueError on misuse.";

void BindTrifocal4ptOptions(py::module_& m) {
  py::enum_<Trifocal4ptRecovery>(m, "Trifocal4ptRecovery",
                                 "How the 4-point solver reads the poses from its tensor.")
      .value("ENFORCED", Trifocal4ptRecovery::kEnforced,
             "constraint enforcement (the most accurate for 4 noisy triplets solved once, "
             "without RANSAC)")
      .value("LEAST_SQUARES", Trifocal4ptRecovery::kLeastSquares,
             "the least-squares read of the tensor")
      .value("PAPER_CLOSED_FORM", Trifocal4ptRecovery::kPaperClosedForm)
      .value("LEAST_SQUARES_IF_MINIMAL", Trifocal4ptRecovery::kLeastSquaresIfMinimal,
             "LEAST_SQUARES for 4 triplets, ENFORCED for more (the default)");
  py::enum_<Trifocal4ptEpipoles>(m, "Trifocal4ptEpipoles",
                                 "Where the 4-point solver's constraint enforcement takes the "
                                 "epipoles from.")
      .value("LEAST_SQUARES_READ_IF_MINIMAL", Trifocal4ptEpipoles::kLeastSquaresReadIfMinimal,
             "the least-squares read of the tensor for 4 triplets, its null vectors for more (the "
             "default)")
      .value("TENSOR_NULL_VECTORS", Trifocal4ptEpipoles::kTensorNullVectors,
             "the tensor's null vectors at any size (the paper's)");
  OptionsClass<Trifocal4ptOptions>(m, "Trifocal4ptOptions", "Options of solve_trifocal_4pt.")
      .Field("recovery", &Trifocal4ptOptions::recovery, "Trifocal4ptRecovery")
      .Field("epipoles", &Trifocal4ptOptions::epipoles,
             "Trifocal4ptEpipoles (ENFORCED; no effect with the default recovery)")
      .Field("resolve_translations", &Trifocal4ptOptions::resolve_translations,
             "re-solve the centres from all triplets with the yaws fixed (not after the "
             "default's least-squares read of 4 triplets)")
      .Field("epipole_iterations", &Trifocal4ptOptions::epipole_iterations,
             "re-estimations of the epipoles (the enforcement: ENFORCED, and the default "
             "recovery for more than 4 triplets)")
      .Field("polish_iterations", &Trifocal4ptOptions::polish_iterations,
             "at most this many Gauss-Newton steps on the incidence residuals, fewer once "
             "converged (the default recovery with more than 4 triplets: at most 1)")
      .Finish(&Trifocal4ptOptions::Check);
}

}  // namespace

void BindSolvers(py::module_& m) {
  py::enum_<InitialSolver>(m, "InitialSolver", "The minimal solver inside RANSAC.")
      .value("TRIFOCAL_3PT", InitialSolver::kTrifocal3pt, "'3pt': decoupled 3-point (the default)")
      .value("TRIFOCAL_3PT_SEXTIC", InitialSolver::kTrifocal3ptSextic,
             "'3pt-sextic': the paper's 3-point system")
      .value("TRIFOCAL_4PT", InitialSolver::kTrifocal4pt, "'4pt': linear 4-point trifocal")
      .value("TRIFOCAL_LINEAR", InitialSolver::kTrifocalLinear,
             "'7pt-linear': linear trifocal tensor, no gravity")
      .value("ESSENTIAL_5PT", InitialSolver::kEssential5pt, "'5pt': Nister on pairs (1,2), (1,3)")
      .value("ESSENTIAL_8PT", InitialSolver::kEssential8pt, "'8pt': eight-point on the pairs")
      .def_property_readonly("short_name", [](InitialSolver s) { return InitialSolverName(s); })
      .def_property_readonly("sample_size", &MinimalSampleSize)
      .def_property_readonly("uses_gravity", &UsesGravity)
      .def_static(
          "from_short_name",
          [](const std::string& name) {
            InitialSolver solver;
            if (!ParseInitialSolver(name, &solver)) {
              throw py::value_error("trigrav: unknown solver '" + name + "' (one of " +
                                    InitialSolverNames() + ")");
            }
            return solver;
          },
          py::arg("name"), "'3pt', '3pt-sextic', '4pt', '7pt-linear', '5pt' or '8pt'");
  BindTrifocal4ptOptions(m);

  m.def(
      "solve_trifocal_3pt",
      [](const py::object& x1, const py::object& x2, const py::object& x3, const py::object& g) {
        return SolveThreeView(
            x1, x2, x3, g, [](const Rays& r, auto* s) { SolveTrifocal3pt(r.x1, r.x2, r.x3, s); },
            [](const Rays& r, const auto& g, auto* s) {
              SolveTrifocal3pt(r.x1, r.x2, r.x3, g[0], g[1], g[2], s);
            });
      },
      py::arg("x1"), py::arg("x2"), py::arg("x3"), py::arg("gravity_in_cam") = py::none(),
      (std::string("Decoupled 3-point trifocal solver with known vertical direction: exactly 3 "
                   "triplets (x1, x2, x3: 3 x 3 rays, one row per triplet), best first.") +
       kGravityDoc)
          .c_str());
  m.def(
      "solve_trifocal_3pt_sextic",
      [](const py::object& x1, const py::object& x2, const py::object& x3, const py::object& g) {
        return SolveThreeView(
            x1, x2, x3, g,
            [](const Rays& r, auto* s) { SolveTrifocal3ptSextic(r.x1, r.x2, r.x3, s); },
            [](const Rays& r, const auto& g, auto* s) {
              SolveTrifocal3ptSextic(r.x1, r.x2, r.x3, g[0], g[1], g[2], s);
            });
      },
      py::arg("x1"), py::arg("x2"), py::arg("x3"), py::arg("gravity_in_cam") = py::none(),
      (std::string("The paper's 3-point system (sextic): exactly 3 triplets.") + kGravityDoc)
          .c_str());
  m.def(
      "solve_trifocal_4pt",
      [](const py::object& x1, const py::object& x2, const py::object& x3, const py::object& g,
         Trifocal4ptOptions options) {  // a copy: used without the GIL
        return SolveThreeView(
            x1, x2, x3, g,
            [&options](const Rays& r, auto* s) { SolveTrifocal4pt(r.x1, r.x2, r.x3, options, s); },
            [&options](const Rays& r, const auto& g, auto* s) {
              SolveTrifocal4pt(r.x1, r.x2, r.x3, g[0], g[1], g[2], options, s);
            });
      },
      py::arg("x1"), py::arg("x2"), py::arg("x3"), py::arg("gravity_in_cam") = py::none(),
      py::arg_v("options", Trifocal4ptOptions(), "Trifocal4ptOptions()"),
      (std::string("The paper's linear 4-point trifocal solver: 4 or more triplets.") + kGravityDoc)
          .c_str());
  m.def(
      "solve_trifocal_linear",
      [](const py::object& x1, const py::object& x2, const py::object& x3) {
        const Rays r = ToRays(x1, x2, x3);
        std::vector<ThreeViewPose> solutions;
        py::gil_scoped_release release;
        SolveTrifocalLinear(r.x1, r.x2, r.x3, &solutions);
        return solutions;
      },
      py::arg("x1"), py::arg("x2"), py::arg("x3"),
      "Normalised linear trifocal tensor, no gravity: 7 or more triplets of raw rays. At most one "
      "solution (a list).");
  m.def(
      "solve_essential_5pt",
      [](const py::object& x1, const py::object& x2) {
        const std::vector<Eigen::Vector3d> r1 = ToPoints3(x1, "x1"), r2 = ToPoints3(x2, "x2");
        std::vector<CameraPose> solutions;
        py::gil_scoped_release release;
        SolveEssential5pt(r1, r2, &solutions);
        return solutions;
      },
      py::arg("x1"), py::arg("x2"),
      "Nister's five-point relative pose of two views: exactly 5 rays each. Every real, "
      "cheirality-consistent CameraPose cam2_from_cam1, |t| = 1 (up to 10).");
  m.def(
      "solve_essential_8pt",
      [](const py::object& x1, const py::object& x2) {
        const std::vector<Eigen::Vector3d> r1 = ToPoints3(x1, "x1"), r2 = ToPoints3(x2, "x2");
        std::vector<CameraPose> solutions;
        py::gil_scoped_release release;
        SolveEssential8pt(r1, r2, &solutions);
        return solutions;
      },
      py::arg("x1"), py::arg("x2"),
      "Normalised eight-point relative pose of two views: 8 or more rays each. At most one "
      "CameraPose (a list), |t| = 1.");
  m.def(
      "combine_two_view_pairs",
      [](const py::object& x1, const py::object& x2, const py::object& x3,
         const std::vector<CameraPose>& pair12, const std::vector<CameraPose>& pair13) {
        const Rays r = ToRays(x1, x2, x3);
        std::vector<ThreeViewPose> poses;
        std::vector<double> residuals;
        {
          py::gil_scoped_release release;
          CombineTwoViewPairs(r.x1, r.x2, r.x3, pair12, pair13, &poses, &residuals);
        }
        return py::make_tuple(poses, residuals);
      },
      py::arg("x1"), py::arg("x2"), py::arg("x3"), py::arg("pair12"), py::arg("pair13"),
      "Three-view poses from two-view solutions of the pairs (1,2) and (1,3): every consistent "
      "combination, camera 3's centre rescaled by the view-1 depths. Returns (poses, "
      "residuals), the depth-ratio residual of each pose.");
}

}  // namespace trigrav::python
