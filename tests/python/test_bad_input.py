"""Bad input raises ValueError naming the problem (shapes, dtypes, NaN, zero gravity, options)."""

import numpy as np
import pytest

import trigrav
from conftest import observations_from_numpy


def with_pixels(scene, view, pixels):
    all_pixels = [np.array(p) for p in scene.pixels]
    all_pixels[view] = pixels
    return trigrav.ThreeViewObservations(pixels=all_pixels, cameras=scene.camera,
                                         gravity_in_cam=scene.gravity_in_cam_measured)


@pytest.mark.parametrize("bad, message", [
    (lambda p: p[:, :1], r"pixels\[1\]: expected an N x 2 array of real numbers, got shape \(120, 1\)"),
    (lambda p: p.ravel(), r"pixels\[1\]: .*got shape \(240,\)"),
    (lambda p: p[None], r"pixels\[1\]: .*got shape \(1, 120, 2\)"),
    (lambda p: p.astype(np.complex128), r"pixels\[1\]: .*got dtype complex128"),
    (lambda p: p.astype(str), r"pixels\[1\]: .*got dtype <U"),
    (lambda p: p.astype(object), r"pixels\[1\]: .*got dtype object"),
    (lambda p: p > 0, r"pixels\[1\]: .*got dtype bool"),
    (lambda p: None, r"pixels\[1\]: .*got None"),
])
def test_bad_pixel_arrays_name_the_view_and_what_they_got(scene, bad, message):
    with pytest.raises(ValueError, match=message):
        with_pixels(scene, 1, bad(np.array(scene.pixels[1])))


def test_real_dtypes_are_converted(scene):
    for dtype in (np.float32, np.int32, np.uint16):
        pixels = np.array(scene.pixels[2]).astype(dtype)
        observations = with_pixels(scene, 2, pixels)
        assert observations.pixels[2].dtype == np.float64
        np.testing.assert_array_equal(observations.pixels[2], pixels.astype(np.float64))


def test_nan_pixel_is_rejected_by_every_call(scene):
    pixels = np.array(scene.pixels[0])
    pixels[7, 1] = np.nan
    observations = with_pixels(scene, 0, pixels)
    for call in (lambda: observations.check(), lambda: trigrav.initialize_and_refine(observations),
                 lambda: trigrav.estimate_three_view_pose_robust(observations)):
        with pytest.raises(ValueError, match=r"trigrav: .*pixel"):
            call()


def test_zero_and_nan_gravity_are_rejected(observations):
    gravity = observations.gravity_in_cam
    gravity[2] = 0.0
    observations.gravity_in_cam = gravity
    with pytest.raises(ValueError, match=r"gravity"):
        trigrav.initialize_and_refine(observations)
    gravity[2] = [0.0, np.nan, 0.0]
    observations.gravity_in_cam = gravity
    with pytest.raises(ValueError, match=r"gravity"):
        trigrav.initialize_and_refine(observations)


def test_wrong_gravity_shapes(observations):
    with pytest.raises(ValueError, match=r"gravity_in_cam: expected three 3-vectors .*got shape \(2, 3\)"):
        observations.gravity_in_cam = np.ones((2, 3))
    with pytest.raises(ValueError, match=r"gravity_in_cam: .*got shape \(3,\)"):
        trigrav.solve_trifocal_3pt(np.ones((3, 3)), np.ones((3, 3)), np.ones((3, 3)),
                                   gravity_in_cam=np.ones(3))


def test_unset_camera_and_sizes_that_differ(scene):
    observations = trigrav.ThreeViewObservations(pixels=scene.pixels,
                                                 gravity_in_cam=scene.gravity_in_cam_measured)
    with pytest.raises(ValueError, match=r"ThreeViewObservations: .*camera"):
        trigrav.initialize_and_refine(observations)
    with pytest.raises(ValueError, match=r"ThreeViewObservations: .*size"):
        trigrav.initialize_and_refine(with_pixels(scene, 2, np.array(scene.pixels[2])[:-1]))
    with pytest.raises(ValueError, match=r"pixels: expected three arrays"):
        trigrav.ThreeViewObservations(pixels=scene.pixels[:2])
    with pytest.raises(ValueError, match=r"cameras\[1\]: expected a Camera"):
        trigrav.ThreeViewObservations(cameras=[scene.camera, "PINHOLE", scene.camera])


def test_bad_options_raise_at_construction_and_at_the_call(observations):
    with pytest.raises(ValueError, match=r"RansacOptions: max_error must be positive"):
        trigrav.RansacOptions(max_error=-1.0)
    with pytest.raises(ValueError, match=r"confidence"):
        trigrav.RansacOptions(confidence=float("nan"))
    with pytest.raises(TypeError, match=r"unexpected keyword argument 'max_eror'"):
        trigrav.RansacOptions(max_eror=1.0)
    options = trigrav.InitializeAndRefineOptions()
    options.bundle_adjustment.gravity_sigma_deg = 0.0  # attributes are checked by the call
    with pytest.raises(ValueError, match=r"gravity_sigma_deg"):
        trigrav.initialize_and_refine(observations, options)


def test_cameras_solvers_and_masks(observations):
    with pytest.raises(ValueError, match=r"unknown|model"):
        trigrav.Camera("PINHOLE_FANCY", [1, 1, 1, 1])
    with pytest.raises(ValueError, match=r"param"):
        trigrav.Camera("OPENCV", [500, 500, 320])
    with pytest.raises(ValueError, match=r"3 triplets|exactly 3"):
        trigrav.solve_trifocal_3pt(np.ones((4, 3)), np.ones((4, 3)), np.ones((4, 3)))
    with pytest.raises(ValueError, match=r"x2: expected an N x 3 array"):
        trigrav.solve_essential_5pt(np.ones((5, 3)), np.ones((5, 2)))
    estimate = trigrav.initialize_and_refine(observations)
    with pytest.raises(ValueError, match=r"inliers|mask"):
        trigrav.refine_three_view_pose(observations, estimate.refined, estimate.inliers[:-1])
    with pytest.raises(ValueError, match=r"inliers: expected a 1-D bool array .*float64"):
        trigrav.refine_three_view_pose(observations, estimate.refined,
                                       estimate.inliers.astype(float))
    with pytest.raises(ValueError, match=r"inliers: .*integers other than 0 and 1"):
        trigrav.refine_three_view_pose(observations, estimate.refined,
                                       np.arange(len(estimate.inliers)))
    assert trigrav.refine_three_view_pose(
        observations, estimate.refined, estimate.inliers.astype(np.uint8)).summary.success
    not_a_rotation = trigrav.ThreeViewPose(
        trigrav.CameraPose(2.0 * np.asarray(estimate.refined.cam2_from_cam1.R),
                           estimate.refined.cam2_from_cam1.t),
        estimate.refined.cam3_from_cam1)
    refused = trigrav.refine_three_view_pose(observations, not_a_rotation, estimate.inliers)
    assert not refused.summary.success
    assert "R is not a rotation" in refused.summary.message, refused.summary.message
    with pytest.raises(ValueError, match=r"points_in_cam\[0\] is not in front"):
        observations.cameras[0].project(np.array([[0.0, 0.0, -1.0]]))


def test_batch_names_the_bad_item(scene, observations):
    with pytest.raises(TypeError, match=r"batch\[1\]: expected ThreeViewObservations"):
        trigrav.initialize_and_refine_batch([observations, 5])
    bad = observations_from_numpy(scene)
    bad.gravity_in_cam = np.zeros((3, 3))
    with pytest.raises(ValueError, match=r"batch\[2\]: trigrav: .*gravity"):
        trigrav.initialize_and_refine_batch([observations, observations, bad], num_threads=2)
    with pytest.raises(ValueError, match=r"num_threads"):
        trigrav.initialize_and_refine_batch([observations], num_threads=-1)
