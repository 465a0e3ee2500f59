"""The module's results are bit-identical to the C++ calls on the same inputs.

The inputs are written as hexadecimal floats for trigrav_python_cpp_reference (cpp_reference.cc),
which runs the same calls in C++ and prints every number as a hexadecimal float.
"""

import os
import subprocess

import numpy as np
import pytest

import trigrav
from conftest import make_scene

SEED = 11


def run_cpp(tmp_path, observations):
    camera = observations.cameras[0]
    lines = ["camera %s %d %s" % (camera.model, len(camera.params),
                                  " ".join(float(p).hex() for p in camera.params)),
             "gravity " + " ".join(float(g).hex() for g in observations.gravity_in_cam.ravel()),
             "seed %d" % SEED, "triplets %d" % len(observations)]
    pixels = observations.pixels
    for n in range(len(observations)):
        lines.append(" ".join(float(x).hex() for k in range(3) for x in pixels[k][n]))
    path = tmp_path / "input.txt"
    path.write_text("\n".join(lines) + "\n")
    output = subprocess.run([os.environ["TRIGRAV_CPP_REFERENCE"], str(path)], check=True,
                            capture_output=True, text=True).stdout
    results = {}
    for line in output.splitlines():
        name, *values = line.split(" ")
        results.setdefault(name, []).append(values)
    return results


def floats(values):
    return np.array([float.fromhex(v) for v in values])


def pose_numbers(pose):
    return np.concatenate([pose.cam2_from_cam1.R.ravel(), pose.cam2_from_cam1.t,
                           pose.cam3_from_cam1.R.ravel(), pose.cam3_from_cam1.t])


def mask_string(mask):
    return "".join("1" if m else "0" for m in mask)


def assert_identical(python_values, cpp_values):
    python_values = np.asarray(python_values, dtype=np.float64)
    assert python_values.shape == cpp_values.shape
    # == on the bits: NaN would fail, and so would -0.0 against 0.0 (tobytes).
    assert python_values.tobytes() == cpp_values.tobytes()


@pytest.mark.parametrize("distortion", [(0.0, 0.0, 0.0, 0.0), (-0.2, 0.05, 0.001, -0.002)],
                         ids=["pinhole", "opencv"])
def test_results_equal_the_cpp_calls_bit_for_bit(tmp_path, distortion):
    scene = make_scene(5, num_points=150, distortion=distortion)
    # The pixels pass through a Fortran-ordered float64 array: layout must not matter.
    observations = trigrav.ThreeViewObservations(
        pixels=[np.asfortranarray(p) for p in scene.pixels], cameras=scene.camera,
        gravity_in_cam=scene.gravity_in_cam_measured)
    cpp = run_cpp(tmp_path, observations)

    options = trigrav.InitializeAndRefineOptions(
        robust=trigrav.RobustThreeViewOptions(ransac=trigrav.RansacOptions(max_error=1.5,
                                                                           seed=SEED)),
        bundle_adjustment=trigrav.ThreeViewBundleAdjustmentOptions(
            rotation_model=trigrav.ThreeViewBundleAdjustmentOptions.RotationModel.GRAVITY_PRIOR,
            compute_covariance=True))
    estimate = trigrav.initialize_and_refine(observations, options)
    assert estimate.success and cpp["ir_success"] == [["1"]]
    assert [[str(estimate.num_inliers)]] == cpp["ir_num_inliers"]
    assert_identical(pose_numbers(estimate.robust.pose), floats(cpp["ir_initial"][0]))
    assert_identical(pose_numbers(estimate.refined), floats(cpp["ir_refined"][0]))
    assert mask_string(estimate.inliers) == cpp["ir_inliers"][0][0]
    assert estimate.refinement.covariance.shape == (11, 11)
    assert_identical(estimate.refinement.covariance.ravel(order="F"),
                     floats(cpp["ir_covariance"][0]))

    robust = trigrav.estimate_three_view_pose_robust(
        observations, trigrav.RobustThreeViewOptions(ransac=trigrav.RansacOptions(seed=SEED)))
    assert robust.success and cpp["robust_success"] == [["1"]]
    assert_identical(pose_numbers(robust.pose), floats(cpp["robust_pose"][0]))
    assert mask_string(robust.inliers) == cpp["robust_inliers"][0][0]
    refinement = trigrav.refine_three_view_pose(observations, robust.pose, robust.inliers)
    assert refinement.summary.success
    assert_identical(pose_numbers(refinement.pose), floats(cpp["refine_pose"][0]))
    assert_identical([refinement.residual_rms], floats(cpp["refine_rms"][0]))

    camera = observations.cameras[0]
    rays = [camera.unproject(p[:3]) for p in observations.pixels]
    assert_identical(rays[0][0], floats(cpp["rays_3pt"][0]))
    solutions = trigrav.solve_trifocal_3pt(*rays, gravity_in_cam=observations.gravity_in_cam)
    assert len(solutions) > 0 and [[str(len(solutions))]] == cpp["solver_3pt_count"]
    for solution, values in zip(solutions, cpp["solver_3pt"]):
        assert_identical(pose_numbers(solution), floats(values))
