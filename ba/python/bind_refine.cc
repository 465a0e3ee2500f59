// Bundle adjustment options and summary, the refine-only call, InitializeAndRefine and its batch
// form on a thread pool.

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <string>
#include <utility>
#include <vector>

#include "bindings.h"
#include "numpy_input.h"
#include "signal_watch.h"
#include "trigrav/ba/initialize_and_refine.h"
#include "trigrav/ba/refine_three_view_pose.h"
#include "trigrav/ba/three_view_bundle_adjustment.h"
#include "trigrav/ba/three_view_covariance.h"

namespace trigrav::python {
namespace {

using BundleOptions = ThreeViewBundleAdjustmentOptions;

// Both stages of InitializeAndRefine stop when the watch sees a signal.
void StopOnSignal(const SignalWatch& watch, InitializeAndRefineOptions* options) {
  options->robust.ransac.stop_requested = watch.StopRequested();
  options->bundle_adjustment.stop_requested = watch.StopRequested();
}

void BindBundleAdjustmentOptions(py::module_& m) {
  OptionsClass<BundleOptions> options(
      m, "ThreeViewBundleAdjustmentOptions",
      "Three-view bundle adjustment: rotation model, loss, sigmas, Ceres solver settings.");
  py::enum_<BundleOptions::Engine>(options.cls(), "Engine")
      .value("CERES", BundleOptions::Engine::kCeres, "ceres::Solve on the adjuster's problem")
      .value("CERES_POINTS_ELIMINATED", BundleOptions::Engine::kCeresPointsEliminated,
             "ceres::Solve on the pose blocks, each point eliminated by variable projection");
  py::enum_<BundleOptions::RotationModel>(options.cls(), "RotationModel")
      .value("YAW_ONLY", BundleOptions::RotationModel::kYawOnly,
             "pitch and roll as the gravity says; one yaw per camera")
      .value("GRAVITY_PRIOR", BundleOptions::RotationModel::kGravityPrior,
             "free rotations with a gravity prior of sigma gravity_sigma_deg");
  py::enum_<BundleOptions::LossType>(options.cls(), "LossType")
      .value("NONE", BundleOptions::LossType::kNone)
      .value("HUBER", BundleOptions::LossType::kHuber)
      .value("CAUCHY", BundleOptions::LossType::kCauchy);
  py::enum_<ceres::LinearSolverType>(options.cls(), "LinearSolverType",
                                     "Ceres' linear solver (ceres::LinearSolverType).")
      .value("DENSE_NORMAL_CHOLESKY", ceres::DENSE_NORMAL_CHOLESKY)
      .value("DENSE_QR", ceres::DENSE_QR)
      .value("SPARSE_NORMAL_CHOLESKY", ceres::SPARSE_NORMAL_CHOLESKY)
      .value("DENSE_SCHUR", ceres::DENSE_SCHUR)
      .value("SPARSE_SCHUR", ceres::SPARSE_SCHUR)
      .value("ITERATIVE_SCHUR", ceres::ITERATIVE_SCHUR)
      .value("CGNR", ceres::CGNR);
  options.Field("engine", &BundleOptions::engine, "Engine (CERES_POINTS_ELIMINATED)")
      .Field("rotation_model", &BundleOptions::rotation_model, "RotationModel (YAW_ONLY)")
      .Field("loss", &BundleOptions::loss, "LossType (HUBER)")
      .Field("loss_scale_px", &BundleOptions::loss_scale_px, "loss scale on pixel residuals (2)")
      .Field("pixel_sigma_px", &BundleOptions::pixel_sigma_px,
             "pixel noise weighting the gravity prior and scaling the covariance (1)")
      .Field("loss_scale_deg", &BundleOptions::loss_scale_deg, "the same for bearings (0.1)")
      .Field("bearing_sigma_deg", &BundleOptions::bearing_sigma_deg, "(0.05)")
      .Field("gravity_sigma_deg", &BundleOptions::gravity_sigma_deg,
             "IMU angular sigma of the gravity prior (0.5)")
      .Field("compute_covariance", &BundleOptions::compute_covariance,
             "also the refined pose's covariance (False)")
      .Field("max_num_iterations", &BundleOptions::max_num_iterations, "(50)")
      .Field("num_threads", &BundleOptions::num_threads, "Ceres threads per problem (1)")
      .Field("linear_solver_type", &BundleOptions::linear_solver_type,
             "LinearSolverType (DENSE_SCHUR)")
      .Field("function_tolerance", &BundleOptions::function_tolerance, "(1e-8)")
      .Field("gradient_tolerance", &BundleOptions::gradient_tolerance, "(1e-10)")
      .Field("parameter_tolerance", &BundleOptions::parameter_tolerance, "(1e-10)")
      .Finish(&BundleOptions::Check);
}

void BindRefinement(py::module_& m) {
  py::class_<ThreeViewBundleAdjustmentSummary>(m, "ThreeViewBundleAdjustmentSummary",
                                               "What a bundle adjustment did.")
      .def_readonly("success", &ThreeViewBundleAdjustmentSummary::success)
      .def_readonly("message", &ThreeViewBundleAdjustmentSummary::message)
      .def_readonly("engine", &ThreeViewBundleAdjustmentSummary::engine,
                    "the Engine that solved (CERES where CERES_POINTS_ELIMINATED solved problem())")
      .def_readonly("num_points", &ThreeViewBundleAdjustmentSummary::num_points)
      .def_readonly("num_residual_blocks", &ThreeViewBundleAdjustmentSummary::num_residual_blocks)
      .def_readonly("solve_s", &ThreeViewBundleAdjustmentSummary::solve_s, "wall-clock seconds")
      .def_property_readonly("initial_cost", &ThreeViewBundleAdjustmentSummary::InitialCost)
      .def_property_readonly("final_cost", &ThreeViewBundleAdjustmentSummary::FinalCost)
      .def_property_readonly("iterations", &ThreeViewBundleAdjustmentSummary::Iterations)
      .def("brief_report", &ThreeViewBundleAdjustmentSummary::BriefReport)
      .def(
          "full_report",
          [](const ThreeViewBundleAdjustmentSummary& s) { return s.ceres_summary.FullReport(); },
          "Ceres' full report")
      .def("__repr__", [](const ThreeViewBundleAdjustmentSummary& s) {
        return "ThreeViewBundleAdjustmentSummary(success=" +
               std::string(s.success ? "True" : "False") + ", " + s.BriefReport() + ")";
      });

  py::class_<ThreeViewRefinement>(m, "ThreeViewRefinement",
                                  "Result of a three-view bundle adjustment.")
      .def_readonly("pose", &ThreeViewRefinement::pose, "the refined pose, |C2| = 1")
      .def_property_readonly(
          "triplets",
          [](const ThreeViewRefinement& r) {
            return py::array_t<int>(r.triplets.size(), r.triplets.data());
          },
          "indices of the triplets in the problem")
      .def_property_readonly(
          "points_in_cam1", [](const ThreeViewRefinement& r) { return ToArray(r.points_in_cam1); },
          "refined points (one row per entry of triplets), camera 1's frame")
      .def_property_readonly(
          "residual_norms", [](const ThreeViewRefinement& r) { return ToArray(r.residual_norms); },
          "per entry of triplets: residual norms in views 1, 2, 3 (px; deg for bearings)")
      .def_readonly("residual_rms", &ThreeViewRefinement::residual_rms)
      .def_readonly("relative_scale", &ThreeViewRefinement::relative_scale, "|C3| / |C2|")
      .def_property_readonly(
          "covariance", [](const ThreeViewRefinement& r) { return r.covariance; },
          "7 x 7 (YAW_ONLY: yaw2, yaw3, u2 (2), C3 (3)) or 11 x 11 (GRAVITY_PRIOR: omega2, "
          "omega3, u2, C3); shape (0, 0) when not computed")
      .def_readonly("summary", &ThreeViewRefinement::summary)
      .def_readonly("build_s", &ThreeViewRefinement::build_s, "adjuster set-up, seconds")
      .def_readonly("covariance_s", &ThreeViewRefinement::covariance_s)
      .def("__repr__", [](const ThreeViewRefinement& r) {
        return "ThreeViewRefinement(success=" + std::string(r.summary.success ? "True" : "False") +
               ", triplets=" + std::to_string(r.triplets.size()) +
               ", residual_rms=" + std::string(py::repr(py::float_(r.residual_rms))) + ")";
      });

  m.def(
      "refine_three_view_pose",
      // Arguments by value: the call works on copies another Python thread cannot change.
      [](ThreeViewObservations observations, ThreeViewPose initial, const py::object& inliers,
         BundleOptions options) {
        const std::vector<char> mask = ToMask(inliers, "inliers");
        SignalWatch watch;
        options.stop_requested = watch.StopRequested();
        ThreeViewRefinement refinement;
        watch.Run(1, 1, [&](std::size_t) {
          refinement = RefineThreeViewPose(observations, initial, mask, options);
        });
        return refinement;
      },
      py::arg("observations"), py::arg("initial"), py::arg("inliers"),
      py::arg_v("options", BundleOptions(), "ThreeViewBundleAdjustmentOptions()"),
      "Refine-only: one three-view bundle adjustment of `initial` on the triplets whose inliers "
      "entry is set (bool array of len(observations)). ValueError for invalid input; a failure "
      "gives summary.success = False with the reason. The GIL is released; Ctrl-C raises "
      "KeyboardInterrupt within about 0.1 s (one solver iteration).");
  m.def(
      "three_view_pose_difference",
      [](BundleOptions::RotationModel model, const ThreeViewPose& pose,
         const ThreeViewPose& reference, const py::object& gravity_in_cam) {
        return Eigen::VectorXd(ThreeViewPoseDifference(
            model, pose, reference, ToThreeVectors(gravity_in_cam, "gravity_in_cam")));
      },
      py::arg("rotation_model"), py::arg("pose"), py::arg("reference"), py::arg("gravity_in_cam"),
      "pose - reference in the coordinates of the covariance of `rotation_model`, to first "
      "order.");
}

void BindInitializeAndRefine(py::module_& m) {
  OptionsClass<InitializeAndRefineOptions>(
      m, "InitializeAndRefineOptions",
      "initialize_and_refine: the robust estimate, then bundle adjustment of its inliers.")
      .Field("robust", &InitializeAndRefineOptions::robust, "RobustThreeViewOptions")
      .Field("refine", &InitializeAndRefineOptions::refine, "False stops after RANSAC (True)")
      .Field("reclassification_rounds", &InitializeAndRefineOptions::reclassification_rounds,
             "re-classify and refine again while the inlier set changes, up to this many times "
             "(1)")
      .Field("bundle_adjustment", &InitializeAndRefineOptions::bundle_adjustment,
             "ThreeViewBundleAdjustmentOptions")
      .Finish(&InitializeAndRefineOptions::Check);

  py::class_<ThreeViewEstimateTimings>(m, "ThreeViewEstimateTimings",
                                       "Wall-clock seconds of each stage of the C++ call.")
      .def_readonly("ransac_s", &ThreeViewEstimateTimings::ransac_s)
      .def_readonly("refinement_s", &ThreeViewEstimateTimings::refinement_s)
      .def_readonly("total_s", &ThreeViewEstimateTimings::total_s)
      .def_readonly("build_s", &ThreeViewEstimateTimings::build_s)
      .def_readonly("solve_s", &ThreeViewEstimateTimings::solve_s)
      .def_readonly("covariance_s", &ThreeViewEstimateTimings::covariance_s)
      .def_readonly("reclassification_s", &ThreeViewEstimateTimings::reclassification_s)
      .def("__repr__", [](const ThreeViewEstimateTimings& t) {
        const std::pair<const char*, double> fields[] = {
            {"ransac_s", t.ransac_s},
            {"refinement_s", t.refinement_s},
            {"total_s", t.total_s},
            {"build_s", t.build_s},
            {"solve_s", t.solve_s},
            {"covariance_s", t.covariance_s},
            {"reclassification_s", t.reclassification_s}};
        std::string repr = "ThreeViewEstimateTimings(";
        for (const auto& [name, value] : fields) {
          if (repr.back() != '(') repr += ", ";
          repr += std::string(name) + "=" + std::string(py::repr(py::float_(value)));
        }
        return repr + ")";
      });

  py::class_<ThreeViewEstimate>(m, "ThreeViewEstimate", "Result of initialize_and_refine.")
      .def_readonly("success", &ThreeViewEstimate::success)
      .def_readonly("message", &ThreeViewEstimate::message,
                    "why not, when not success; a note when the refinement fell back")
      .def_readonly("cause", &ThreeViewEstimate::cause, "FailureCause")
      .def_readonly("robust", &ThreeViewEstimate::robust,
                    "the RANSAC stage (RobustThreeViewEstimate): the RANSAC winner's pose and "
                    "inliers, statistics, gravity consistency, evidence")
      .def_readonly("refined", &ThreeViewEstimate::refined,
                    "the answer: the refined pose (the initial one if not refined)")
      .def_property_readonly(
          "inliers", [](const ThreeViewEstimate& e) { return MaskToArray(e.inliers); },
          "bool array: inliers of refined")
      .def_readonly("num_inliers", &ThreeViewEstimate::num_inliers)
      .def_readonly("refinement", &ThreeViewEstimate::refinement,
                    "the bundle adjustment that produced refined (covariance, residuals, summary)")
      .def_readonly("refinement_runs", &ThreeViewEstimate::refinement_runs)
      .def_readonly("timings", &ThreeViewEstimate::timings)
      .def("__repr__", [](const ThreeViewEstimate& e) {
        return "ThreeViewEstimate(success=" + std::string(e.success ? "True" : "False") +
               ", num_inliers=" + std::to_string(e.num_inliers) +
               ", message=" + std::string(py::repr(py::str(e.message))) + ")";
      });

  m.def(
      "initialize_and_refine",
      // Arguments by value: the call works on copies another Python thread cannot change.
      [](ThreeViewObservations observations, InitializeAndRefineOptions options) {
        SignalWatch watch;
        StopOnSignal(watch, &options);
        ThreeViewEstimate estimate;
        watch.Run(1, 1,
                  [&](std::size_t) { estimate = InitializeAndRefine(observations, options); });
        return estimate;
      },
      py::arg("observations"),
      py::arg_v("options", InitializeAndRefineOptions(), "InitializeAndRefineOptions()"),
      "Robust estimate (RANSAC over options.robust.solver) refined by three-view bundle "
      "adjustment on its inliers. ValueError for invalid observations or options; numerical "
      "failure gives success = False with a message. The same seed gives bit-identical "
      "results. The GIL is released; Ctrl-C raises KeyboardInterrupt within about 0.1 s.");
  m.def(
      "initialize_and_refine_batch",
      [](const py::sequence& batch, InitializeAndRefineOptions options, int num_threads,
         bool return_exceptions) {
        if (num_threads < 0) throw py::value_error("trigrav: num_threads must be >= 0");
        // Copies: the calls run without the GIL, while other Python threads may change the items.
        std::vector<ThreeViewObservations> items;
        items.reserve(py::len(batch));
        for (std::size_t i = 0; i < py::len(batch); ++i) {
          const py::object item = batch[i];
          if (!py::isinstance<ThreeViewObservations>(item)) {
            throw py::type_error("trigrav: batch[" + std::to_string(i) +
                                 "]: expected ThreeViewObservations, got " +
                                 std::string(py::str(py::type::of(item))));
          }
          items.push_back(item.cast<ThreeViewObservations>());
        }
        SignalWatch watch;
        StopOnSignal(watch, &options);
        std::vector<ThreeViewEstimate> estimates(items.size());
        std::vector<std::string> errors(items.size());
        watch.Run(items.size(), num_threads, [&](std::size_t i) {
          try {
            estimates[i] = InitializeAndRefine(items[i], options);
          } catch (const std::exception& e) {
            errors[i] = e.what();
          }
        });
        py::list results;
        std::string failed;
        for (std::size_t i = 0; i < items.size(); ++i) {
          if (errors[i].empty()) {
            results.append(py::cast(std::move(estimates[i])));
          } else if (return_exceptions) {
            results.append(py::reinterpret_steal<py::object>(
                PyObject_CallFunction(PyExc_ValueError, "s", errors[i].c_str())));
          } else {
            failed +=
                (failed.empty() ? "" : "; ") + ("batch[" + std::to_string(i) + "]: ") + errors[i];
          }
        }
        if (!failed.empty()) throw py::value_error("trigrav: " + failed);
        return results;
      },
      py::arg("batch"),
      py::arg_v("options", InitializeAndRefineOptions(), "InitializeAndRefineOptions()"),
      py::arg("num_threads") = 0, py::arg("return_exceptions") = false,
      "initialize_and_refine on each ThreeViewObservations of `batch` on num_threads worker "
      "threads (0: one per core; fewer when the system cannot create them), the GIL released. "
      "Returns the list of ThreeViewEstimate, equal to the serial calls. An invalid item raises "
      "ValueError naming every bad index, or with return_exceptions=True takes its place in the "
      "list as a ValueError instance. Ctrl-C raises KeyboardInterrupt within about 0.1 s.");
}

}  // namespace

void BindRefine(py::module_& m) {
  BindBundleAdjustmentOptions(m);
  BindRefinement(m);
  BindInitializeAndRefine(m);
}

}  // namespace trigrav::python
