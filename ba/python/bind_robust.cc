// RansacOptions, RobustThreeViewOptions, the RANSAC statistics and EstimateThreeViewPoseRobust.

#include <pybind11/stl.h>

#include <cmath>
#include <string>

#include "bindings.h"
#include "numpy_input.h"
#include "signal_watch.h"
#include "trigrav/initializers/ransac.h"
#include "trigrav/initializers/robust_three_view.h"

namespace trigrav::python {
namespace {

void BindRansacOptions(py::module_& m) {
  OptionsClass<RansacOptions>(m, "RansacOptions",
                              "Options of the RANSAC loop (MSAC scoring, adaptive stopping, "
                              "local optimisation). Errors in pixels (degrees for bearings: "
                              "RobustThreeViewOptions.max_bearing_error_deg).")
      .Field("max_error", &RansacOptions::max_error,
             "inlier threshold, px: the largest reprojection error over the three views (2)")
      .Field("confidence", &RansacOptions::confidence, "of an all-inlier sample (0.9999)")
      .Field("min_iterations", &RansacOptions::min_iterations, "(20)")
      .Field("max_iterations", &RansacOptions::max_iterations, "(10000)")
      .Field("seed", &RansacOptions::seed, "same seed, same data: bit-identical result (0)")
      .Field("min_inlier_ratio", &RansacOptions::min_inlier_ratio,
             "a best model below this inlier ratio is a failure (0.25); 0 turns it off")
      .Field("local_optimization", &RansacOptions::local_optimization, "(True)")
      .Field("local_optimization_rounds", &RansacOptions::local_optimization_rounds, "(3)")
      .Field("local_optimization_threshold_multiplier",
             &RansacOptions::local_optimization_threshold_multiplier, "(3)")
      .Finish(&RansacOptions::Check);
}

void BindRobustOptions(py::module_& m) {
  OptionsClass<RobustThreeViewOptions> options(
      m, "RobustThreeViewOptions",
      "The robust estimate: solver, RANSAC (ransac.max_error is the one inlier threshold), tilt "
      "correction and gravity check.");
  options.Field("solver", &RobustThreeViewOptions::solver, "InitialSolver (TRIFOCAL_3PT)")
      .Field("ransac", &RobustThreeViewOptions::ransac, "RansacOptions")
      .Field("max_bearing_error_deg", &RobustThreeViewOptions::max_bearing_error_deg,
             "inlier threshold for bearing observations, degrees (0.1)")
      .Field("max_tilt_correction_deg", &RobustThreeViewOptions::max_tilt_correction_deg,
             "bound on the relative tilt local optimisation may correct, degrees; "
             "TILT_CORRECTION_FROM_GRAVITY_SIGMA (-1, the default) derives it")
      .Field("max_gravity_inconsistency_deg",
             &RobustThreeViewOptions::max_gravity_inconsistency_deg,
             "how far a camera's gravity may be from what the images say, degrees; "
             "GRAVITY_CONSISTENCY_FROM_GRAVITY_SIGMA (-1, the default) derives it, inf skips it")
      .Field("check_gravity_after_success", &RobustThreeViewOptions::check_gravity_after_success,
             "compare with a gravity-free estimate also after a success (True)")
      .Field("max_pose_sigma_deg", &RobustThreeViewOptions::max_pose_sigma_deg,
             "largest predicted sigma of the rotations and centre directions for a success, "
             "degrees (1.25); inf: no test")
      .Field("min_inliers", &RobustThreeViewOptions::min_inliers,
             "fewest distinct inlier triplets of a success (15)")
      .Field("refined_afterwards", &RobustThreeViewOptions::refined_afterwards,
             "the caller refines the pose: judge its inliers' optimum alone (False)")
      .Finish(&RobustThreeViewOptions::Check);
  options.cls().attr("TILT_CORRECTION_FROM_GRAVITY_SIGMA") =
      RobustThreeViewOptions::kTiltCorrectionFromGravitySigma;
  options.cls().attr("GRAVITY_CONSISTENCY_FROM_GRAVITY_SIGMA") =
      RobustThreeViewOptions::kGravityConsistencyFromGravitySigma;
}

void BindResults(py::module_& m) {
  py::enum_<FailureCause>(m, "FailureCause", "Why an estimate is not a success.")
      .value("NONE", FailureCause::kNone, "a success")
      .value("TOO_FEW_TRIPLETS", FailureCause::kTooFewTriplets,
             "fewer triplets than the minimal sample, or no model")
      .value("BELOW_INLIER_FLOOR", FailureCause::kBelowInlierFloor,
             "no model explains ransac.min_inlier_ratio of the triplets")
      .value("TOO_FEW_INLIERS", FailureCause::kTooFewInliers, "fewer inliers than min_inliers")
      .value("CHANCE_CONSENSUS", FailureCause::kChanceConsensus,
             "as many inliers would fit by chance")
      .value("UNCERTAIN_POSE", FailureCause::kUncertainPose,
             "the inliers leave the pose uncertain (max_pose_sigma_deg)")
      .value("NO_PARALLAX", FailureCause::kNoParallax, "camera 2's centre is not observable")
      .value("PIXELS_VS_INTRINSICS", FailureCause::kPixelsVsIntrinsics,
             "pixels the intrinsics cannot produce")
      .value("VIEWS_OUT_OF_ORDER", FailureCause::kViewsOutOfOrder, "views 2 and 3 swapped")
      .value("CAMERA_GRAVITY", FailureCause::kCameraGravity,
             "a camera's gravity contradicts the images")
      .value("NOISY_GRAVITY", FailureCause::kNoisyGravity,
             "the gravity is noisier than the rotation model allows")
      .value("OTHER_MOTION", FailureCause::kOtherMotion,
             "a gravity-free model explains more and disagrees")
      .value("REFINEMENT_SHIFT", FailureCause::kRefinementShift,
             "the refinement moved the verified pose beyond 5 deg")
      .value("STOPPED", FailureCause::kStopped, "the call was interrupted (Ctrl-C)");

  py::class_<RansacStatistics>(m, "RansacStatistics", "What a RANSAC run did.")
      .def_readonly("num_inliers", &RansacStatistics::num_inliers)
      .def_readonly("iterations", &RansacStatistics::iterations, "samples drawn")
      .def_readonly("num_models_scored", &RansacStatistics::num_models_scored)
      .def_readonly("num_local_optimizations", &RansacStatistics::num_local_optimizations)
      .def_readonly("msac_cost", &RansacStatistics::msac_cost)
      .def("__repr__", [](const RansacStatistics& s) {
        return "RansacStatistics(num_inliers=" + std::to_string(s.num_inliers) +
               ", iterations=" + std::to_string(s.iterations) +
               ", num_models_scored=" + std::to_string(s.num_models_scored) +
               ", num_local_optimizations=" + std::to_string(s.num_local_optimizations) +
               ", msac_cost=" + std::string(py::repr(py::float_(s.msac_cost))) + ")";
      });

  py::class_<GravityConsistency>(m, "GravityConsistency",
                                 "What a gravity-free estimate says about the given gravity.")
      .def_readonly("measured", &GravityConsistency::measured)
      .def_readonly("num_inliers", &GravityConsistency::num_inliers)
      .def_readonly("pair_inconsistency_deg", &GravityConsistency::pair_inconsistency_deg,
                    "pairs (1,2), (1,3), (2,3)")
      .def_readonly("swapped_pair_inconsistency_deg",
                    &GravityConsistency::swapped_pair_inconsistency_deg,
                    "pairs (1,2), (1,3) with the gravities of views 2 and 3 exchanged")
      .def_readonly("rotation_disagreement_deg", &GravityConsistency::rotation_disagreement_deg,
                    "views 2 and 3")
      .def_readonly("direction_disagreement_deg", &GravityConsistency::direction_disagreement_deg,
                    "views 2 and 3: angle between the two estimates' centre directions")
      .def_readonly("inconsistent_camera", &GravityConsistency::inconsistent_camera,
                    "1, 2 or 3; 0 when none is named")
      .def("__repr__", [](const GravityConsistency& g) {
        return "GravityConsistency(measured=" + std::string(g.measured ? "True" : "False") +
               ", inconsistent_camera=" + std::to_string(g.inconsistent_camera) + ")";
      });

  py::class_<ConsensusEvidence>(m, "ConsensusEvidence",
                                "How much the RANSAC winner's consensus says.")
      .def_readonly("log10_nfa", &ConsensusEvidence::log10_nfa,
                    "log10 of the number of false alarms; below 0 for a success")
      .def_readonly("rotation_sigma_deg", &ConsensusEvidence::rotation_sigma_deg,
                    "predicted at a noise of the threshold / 3")
      .def_readonly("direction_sigma_deg", &ConsensusEvidence::direction_sigma_deg,
                    "of the centres' directions, predicted at a noise of the threshold / 3")
      .def_readonly("rotation_offset_deg", &ConsensusEvidence::rotation_offset_deg,
                    "the pose's offset from its inliers' least-squares optimum (Gauss-Newton step)")
      .def_readonly("direction_offset_deg", &ConsensusEvidence::direction_offset_deg,
                    "the centres' directions' offset from that optimum")
      .def("sigma_with_offset_deg", &ConsensusEvidence::SigmaWithOffsetDeg,
           "max of sigma + offset / 4 for the rotations and the directions")
      .def("__repr__", [](const ConsensusEvidence& e) {
        const auto number = [](double x) { return std::string(py::repr(py::float_(x))); };
        return "ConsensusEvidence(log10_nfa=" + number(e.log10_nfa) +
               ", rotation_sigma_deg=" + number(e.rotation_sigma_deg) +
               ", direction_sigma_deg=" + number(e.direction_sigma_deg) +
               ", rotation_offset_deg=" + number(e.rotation_offset_deg) +
               ", direction_offset_deg=" + number(e.direction_offset_deg) + ")";
      });

  py::class_<RobustThreeViewEstimate>(m, "RobustThreeViewEstimate",
                                      "Result of estimate_three_view_pose_robust.")
      .def_readonly("success", &RobustThreeViewEstimate::success)
      .def_readonly("message", &RobustThreeViewEstimate::message, "why not, when not success")
      .def_readonly("cause", &RobustThreeViewEstimate::cause, "FailureCause")
      .def_readonly("pose", &RobustThreeViewEstimate::pose, "|cam2_from_cam1.center| = 1")
      .def_property_readonly(
          "inliers", [](const RobustThreeViewEstimate& e) { return MaskToArray(e.inliers); },
          "bool array, one entry per triplet")
      .def_readonly("ransac", &RobustThreeViewEstimate::ransac)
      .def_readonly("gravity", &RobustThreeViewEstimate::gravity)
      .def_readonly("evidence", &RobustThreeViewEstimate::evidence)
      .def("__repr__", [](const RobustThreeViewEstimate& e) {
        return "RobustThreeViewEstimate(success=" + std::string(e.success ? "True" : "False") +
               ", num_inliers=" + std::to_string(e.ransac.num_inliers) +
               ", message=" + std::string(py::repr(py::str(e.message))) + ")";
      });
}

}  // namespace

void BindRobust(py::module_& m) {
  BindRansacOptions(m);
  BindRobustOptions(m);
  BindResults(m);
  m.def(
      "estimate_three_view_pose_robust",
      // Arguments by value: the call works on copies another Python thread cannot change.
      [](ThreeViewObservations observations, RobustThreeViewOptions options) {
        SignalWatch watch;
        options.ransac.stop_requested = watch.StopRequested();
        RobustThreeViewEstimate estimate;
        watch.Run(1, 1, [&](std::size_t) {
          estimate = EstimateThreeViewPoseRobust(observations, options);
        });
        return estimate;
      },
      py::arg("observations"),
      py::arg_v("options", RobustThreeViewOptions(), "RobustThreeViewOptions()"),
      "RANSAC over the chosen solver, every method scored by the three-view reprojection error "
      "(pixels; degrees for bearings). ValueError for invalid observations or options; "
      "numerical failure gives success = False with a message. The GIL is released; Ctrl-C "
      "raises KeyboardInterrupt within about 0.1 s.");
}

}  // namespace trigrav::python
