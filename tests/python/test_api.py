"""The Python-shaped API: options, results, solvers, cameras, gravity helpers, metrics (the type
stub is checked in test_stub.py)."""

import math
import os
import pydoc

import numpy as np
import pytest

import trigrav
from conftest import make_scene


def test_options_from_keywords_nest_and_print_readably():
    options = trigrav.InitializeAndRefineOptions(
        robust=trigrav.RobustThreeViewOptions(ransac=trigrav.RansacOptions(max_error=1.5, seed=7)),
        bundle_adjustment=trigrav.ThreeViewBundleAdjustmentOptions(gravity_sigma_deg=0.1))
    assert options.robust.ransac.max_error == 1.5 and options.robust.ransac.seed == 7
    assert options.bundle_adjustment.gravity_sigma_deg == 0.1
    options.robust.ransac.max_error = 3.0  # nested attributes are the options' own
    assert options.robust.ransac.max_error == 3.0
    text = repr(options)
    assert text.startswith("InitializeAndRefineOptions(robust=RobustThreeViewOptions(")
    assert "ransac=RansacOptions(max_error=3.0," in text
    assert "solver=InitialSolver.TRIFOCAL_3PT" in text
    assert "rotation_model=RotationModel.YAW_ONLY" in text
    assert repr(trigrav.RansacOptions()) == (
        "RansacOptions(max_error=2.0, confidence=0.9999, min_iterations=20, "
        "max_iterations=10000, seed=0, min_inlier_ratio=0.25, local_optimization=True, "
        "local_optimization_rounds=3, local_optimization_threshold_multiplier=3.0)")


def test_initialize_and_refine_result_recovers_the_truth(scene, observations):
    options = trigrav.InitializeAndRefineOptions(
        bundle_adjustment=trigrav.ThreeViewBundleAdjustmentOptions(compute_covariance=True))
    estimate = trigrav.initialize_and_refine(observations, options)
    assert estimate.success, estimate.message
    errors = trigrav.compute_three_view_pose_errors(scene.ground_truth, estimate.refined)
    assert errors.max_rotation_deg() < 0.2 and errors.max_translation_deg() < 1.0
    assert estimate.inliers.dtype == np.bool_ and estimate.inliers.shape == (len(observations),)
    assert estimate.inliers.sum() == estimate.num_inliers
    # Every triplet the scene made an outlier is rejected.
    assert not np.any(estimate.inliers & ~scene.is_inlier)
    assert math.isclose(np.linalg.norm(estimate.refined.cam2_from_cam1.center), 1.0)
    pose = estimate.refined.cam2_from_cam1
    np.testing.assert_allclose(pose.center, -pose.R.T @ pose.t, atol=1e-15)
    refinement = estimate.refinement
    assert refinement.covariance.shape == (7, 7)
    np.testing.assert_allclose(refinement.covariance, refinement.covariance.T)
    assert refinement.points_in_cam1.shape == (len(refinement.triplets), 3)
    assert refinement.residual_norms.shape == (len(refinement.triplets), 3)
    assert refinement.summary.success and refinement.summary.iterations > 0
    assert 0.0 < estimate.timings.total_s
    assert estimate.robust.ransac.num_inliers == estimate.robust.inliers.sum()


def test_verdict_gives_evidence_and_a_cause(scene, observations):
    estimate = trigrav.initialize_and_refine(observations)
    assert estimate.success and estimate.cause == trigrav.FailureCause.NONE
    assert estimate.robust.evidence.log10_nfa < -50
    assert 0 < estimate.robust.evidence.rotation_sigma_deg < 0.2
    assert 0 < estimate.robust.evidence.direction_sigma_deg < 1.25
    # Views 2 and 3 swapped: refused, with the cause named for a pipeline to act on.
    swapped = trigrav.ThreeViewObservations(
        pixels=[scene.pixels[0], scene.pixels[2], scene.pixels[1]], cameras=scene.camera,
        gravity_in_cam=scene.gravity_in_cam_measured)
    refused = trigrav.estimate_three_view_pose_robust(swapped)
    assert refused.cause == trigrav.FailureCause.VIEWS_OUT_OF_ORDER, refused.message
    assert len(refused.message) <= 210, refused.message
    # The figures behind it: the gravities fit the images only exchanged (the RANSAC failed, so
    # there is no pose to disagree with).
    gravity = refused.gravity
    assert gravity.measured and min(gravity.pair_inconsistency_deg) > 1.0
    assert max(gravity.swapped_pair_inconsistency_deg) < 1.0  # the bound for exact gravity
    assert list(gravity.direction_disagreement_deg) == [0.0, 0.0]
    # Too few triplets for a verdict.
    few = trigrav.ThreeViewObservations(
        pixels=[p[:10] for p in scene.pixels], cameras=scene.camera,
        gravity_in_cam=scene.gravity_in_cam_measured)
    estimate = trigrav.estimate_three_view_pose_robust(
        few, trigrav.RobustThreeViewOptions(max_pose_sigma_deg=math.inf))
    assert not estimate.success
    assert estimate.cause == trigrav.FailureCause.TOO_FEW_INLIERS
    assert "only 10 triplets given (min_inliers 15)" in estimate.message, estimate.message
    # min_inliers is an option: at 8 the 10 triplets go on to the other tests.
    lowered = trigrav.estimate_three_view_pose_robust(
        few, trigrav.RobustThreeViewOptions(min_inliers=8, max_pose_sigma_deg=math.inf))
    assert "triplets given" not in lowered.message, lowered.message


def ground_plane_scene(seed):
    """Every point on the ground 1.5 m below camera 1 (y down), 3-40 m ahead; centres within 2 m,
    rotations within 10 deg; f = 500 px, 1 px noise, 20 % outliers, exact gravity."""
    rng = np.random.default_rng(seed)
    points = np.c_[rng.uniform(-15, 15, 300), np.full(300, 1.5), rng.uniform(3, 40, 300)]
    centers = [np.zeros(3)] + [np.r_[rng.uniform(-2, 2), rng.uniform(-0.3, 0.3), rng.uniform(-2, 2)]
                               for _ in range(2)]
    rng = np.random.default_rng(seed + 1000)

    def rotation(axis, deg):
        c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
        i, j = {"x": (1, 2), "y": (2, 0), "z": (0, 1)}[axis]
        r = np.eye(3)
        r[i, i], r[i, j], r[j, i], r[j, j] = c, -s, s, c
        return r

    rotations = [rotation("z", rng.uniform(-10, 10)) @ rotation("x", rng.uniform(-10, 10)) @
                 rotation("y", rng.uniform(-10, 10)) for _ in range(3)]
    pixels, keep = [], np.ones(len(points), bool)
    for r, c in zip(rotations, centers):
        x = (points - c) @ r.T
        p = 500.0 * x[:, :2] / x[:, 2:] + [320.0, 240.0] + rng.normal(0, 1.0, (len(points), 2))
        keep &= (x[:, 2] > 0) & (p[:, 0] > 0) & (p[:, 0] < 640) & (p[:, 1] > 0) & (p[:, 1] < 480)
        pixels.append(p)
    pixels = [p[keep] for p in pixels]
    for p in pixels:
        p[:60] = np.c_[rng.uniform(0, 640, 60), rng.uniform(0, 480, 60)]
    t = [-r @ c for r, c in zip(rotations, centers)]
    truth = trigrav.ThreeViewPose(*[trigrav.CameraPose(rotations[k] @ rotations[0].T, t[k])
                                    for k in (1, 2)])
    return truth, trigrav.ThreeViewObservations(
        pixels=pixels, cameras=trigrav.Camera.pinhole(500.0, 500.0, 320.0, 240.0),
        gravity_in_cam=np.array([r @ [0.0, 1.0, 0.0] for r in rotations]))


def test_a_ransac_pose_off_its_optimum_is_not_a_success():
    # Ground-plane scenes whose RANSAC pose lies 9-10 deg off the truth at a predicted direction
    # sigma of 0.8-1 deg: the pose is 5.9-6.6 deg off its inliers' optimum, so as the answer of a
    # call it is refused; with a refinement declared it is returned, and InitializeAndRefine,
    # whose refinement moves it, refuses it naming the geometry.
    options = trigrav.RobustThreeViewOptions(ransac=trigrav.RansacOptions(max_error=3, seed=7))
    for seed in (2, 18):
        truth, observations = ground_plane_scene(seed)
        refused = trigrav.estimate_three_view_pose_robust(observations, options)
        assert not refused.success
        assert refused.cause == trigrav.FailureCause.UNCERTAIN_POSE
        assert "inliers' optimum" in refused.message, refused.message
        options.refined_afterwards = True
        initial = trigrav.estimate_three_view_pose_robust(observations, options)
        options.refined_afterwards = False
        assert initial.success, initial.message
        errors = trigrav.compute_three_view_pose_errors(truth, initial.pose)
        assert errors.max_translation_deg() > 5.0
        assert initial.evidence.direction_offset_deg > 4.0
        assert initial.evidence.sigma_with_offset_deg() > 1.25
        refined = trigrav.initialize_and_refine(
            observations, trigrav.InitializeAndRefineOptions(robust=options))
        assert not refined.success
        assert refined.cause == trigrav.FailureCause.REFINEMENT_SHIFT
        assert "too weak a geometry" in refined.message, refined.message
    # Over 40 such scenes (the README's figure) one wrong success is left: seed 22, a RANSAC that
    # stopped on a wrong motion at its own optimum (98 inliers where the true motion has 146).
    wrong = []
    for seed in range(40):
        truth, observations = ground_plane_scene(seed)
        estimate = trigrav.estimate_three_view_pose_robust(observations, options)
        if estimate.success:
            errors = trigrav.compute_three_view_pose_errors(truth, estimate.pose)
            if max(errors.max_rotation_deg(), errors.max_translation_deg()) > 5.0:
                wrong.append(seed)
    assert wrong == [22], wrong


def test_both_engines_reach_the_same_optimum(scene, observations):
    Engine = trigrav.ThreeViewBundleAdjustmentOptions.Engine

    def refine(engine):
        options = trigrav.InitializeAndRefineOptions(
            bundle_adjustment=trigrav.ThreeViewBundleAdjustmentOptions(engine=engine))
        return trigrav.initialize_and_refine(observations, options)

    ceres, eliminated = refine(Engine.CERES), refine(Engine.CERES_POINTS_ELIMINATED)
    assert ceres.success and eliminated.success
    assert ceres.refinement.summary.engine == Engine.CERES
    assert eliminated.refinement.summary.engine == Engine.CERES_POINTS_ELIMINATED
    assert np.array_equal(ceres.inliers, eliminated.inliers)
    assert math.isclose(eliminated.refinement.summary.final_cost,
                        ceres.refinement.summary.final_cost, rel_tol=1e-8)
    # At the default tolerances each engine stops within about 1e-7 of the optimum.
    for view in ("cam2_from_cam1", "cam3_from_cam1"):
        np.testing.assert_allclose(getattr(eliminated.refined, view).R,
                                   getattr(ceres.refined, view).R, atol=1e-6)
    timings = eliminated.timings
    assert 0.0 < timings.solve_s <= timings.refinement_s <= timings.total_s
    assert "engine=Engine.CERES" in repr(
        trigrav.ThreeViewBundleAdjustmentOptions(engine=Engine.CERES))


def test_every_solver_finds_the_true_pose():
    scene = make_scene(2, num_points=8, outlier_ratio=0.0)
    truth = scene.ground_truth
    gravity = scene.gravity_in_cam_measured
    # Noise-free rays for the minimal solvers.
    exact = trigrav.generate_synthetic_scene(trigrav.SyntheticSceneOptions(num_points=8), 2)
    rays = exact.rays

    def best_error(solutions):
        return min(trigrav.compute_three_view_pose_errors(exact.ground_truth, s).max_angle_deg()
                   for s in solutions)

    three = [r[:3] for r in rays]
    assert best_error(trigrav.solve_trifocal_3pt(*three, gravity_in_cam=exact.gravity_in_cam_measured)) < 1e-6
    assert best_error(trigrav.solve_trifocal_3pt_sextic(*three, gravity_in_cam=exact.gravity_in_cam_measured)) < 1e-6
    assert best_error(trigrav.solve_trifocal_4pt(*[r[:4] for r in rays], gravity_in_cam=exact.gravity_in_cam_measured)) < 1e-6
    assert trigrav.Trifocal4ptOptions().recovery == trigrav.Trifocal4ptRecovery.LEAST_SQUARES_IF_MINIMAL
    enforced = trigrav.Trifocal4ptOptions(recovery=trigrav.Trifocal4ptRecovery.ENFORCED)
    assert best_error(trigrav.solve_trifocal_4pt(*[r[:4] for r in rays], gravity_in_cam=exact.gravity_in_cam_measured,
                                                 options=enforced)) < 1e-6
    assert best_error(trigrav.solve_trifocal_linear(*rays)) < 1e-6
    aligned = [trigrav.align_rays(a, r[:3]) for a, r in zip(exact.gravity_alignment_measured, rays)]
    upright = trigrav.solve_trifocal_3pt(*aligned)
    unaligned = [trigrav.ThreeViewPose(
        trigrav.unalign_pose(s.cam2_from_cam1, exact.gravity_alignment_measured[0], exact.gravity_alignment_measured[1]),
        trigrav.unalign_pose(s.cam3_from_cam1, exact.gravity_alignment_measured[0], exact.gravity_alignment_measured[2]))
        for s in upright]
    assert best_error(unaligned) < 1e-6
    pair12 = trigrav.solve_essential_5pt(rays[0][:5], rays[1][:5])
    pair13 = trigrav.solve_essential_8pt(rays[0], rays[2])
    assert len(pair13) == 1
    poses, residuals = trigrav.combine_two_view_pairs(*rays, pair12, pair13)
    assert len(poses) == len(residuals) and best_error(poses) < 1e-6
    assert truth is not None and gravity.shape == (3, 3)


def test_cameras_from_colmap_round_trip():
    camera = trigrav.Camera("OPENCV", [700, 710, 320, 240, -0.2, 0.05, 0.001, -0.002])
    assert camera.model == "OPENCV" and camera.params == [700, 710, 320, 240, -0.2, 0.05, 0.001, -0.002]
    assert camera.focal_x == 700 and not camera.is_pinhole
    assert repr(camera) == "Camera('OPENCV', [700, 710, 320, 240, -0.20000000000000001, 0.050000000000000003, 0.001, -0.002])"
    points = np.array([[0.3, -0.2, 4.0], [-1.0, 0.5, 6.0]])
    rays = camera.unproject(camera.project(points))
    np.testing.assert_allclose(rays, points / points[:, 2:], atol=1e-10)
    assert trigrav.CAMERA_MODELS == ("SIMPLE_PINHOLE", "PINHOLE", "SIMPLE_RADIAL", "RADIAL",
                                     "OPENCV", "OPENCV_FISHEYE")
    assert trigrav.Camera.pinhole(500, 500, 320, 240).model == "PINHOLE"


def test_gravity_helpers_and_metrics():
    g = np.array([0.1, 0.9, -0.2])
    alignment = trigrav.gravity_alignment_from_gravity(g)
    np.testing.assert_allclose(alignment @ g, [0, np.linalg.norm(g), 0], atol=1e-15)
    np.testing.assert_allclose(trigrav.gravity_in_camera(alignment), g / np.linalg.norm(g), atol=1e-15)
    R = trigrav.rotation_about_y(0.1)
    assert math.isclose(trigrav.rotation_error_deg(np.eye(3), R), math.degrees(0.1))
    split = trigrav.split_rotation_error_deg(np.eye(3), R, [0, 1, 0])
    assert math.isclose(split.yaw_deg, math.degrees(0.1)) and split.tilt_deg < 1e-12
    assert math.isclose(trigrav.direction_error_deg([1, 0, 0], [0, 1, 0]), 90.0)
    pitch_roll = trigrav.gravity_alignment_from_pitch_roll(0.0, 0.0)
    np.testing.assert_array_equal(pitch_roll, np.eye(3))
    pose = trigrav.CameraPose(R, [1, 2, 3])
    np.testing.assert_allclose((pose * pose.inverse()).R, np.eye(3), atol=1e-15)
    np.testing.assert_allclose(pose.apply(np.zeros((1, 3))), [[1, 2, 3]])


def test_three_view_errors_mark_the_outliers(scene, observations):
    errors = trigrav.three_view_errors(observations, scene.ground_truth)
    assert errors.shape == (len(observations),)
    assert np.all(errors[scene.is_inlier] < 3.0) and np.all(errors[~scene.is_inlier] > 3.0)


def test_bearings_work_like_pixels(scene):
    bearings = trigrav.to_bearing_observations(scene)
    assert bearings.has_bearings() and len(bearings.bearings[0]) == len(scene.pixels[0])
    estimate = trigrav.initialize_and_refine(bearings)
    assert estimate.success
    assert trigrav.compute_three_view_pose_errors(scene.ground_truth, estimate.refined).max_angle_deg() < 1.0


def test_help_shows_signatures_and_docstrings():
    text = pydoc.render_doc(trigrav.initialize_and_refine, renderer=pydoc.plaintext)
    assert "initialize_and_refine(observations: trigrav.ThreeViewObservations" in text
    assert "Robust estimate" in text
    assert "N x 2" in trigrav.ThreeViewObservations.__init__.__doc__


def test_root_readme_python_snippet_runs_as_written(capsys):
    readme = os.path.join(os.path.dirname(__file__), "..", "..", "README.md")
    section = open(readme).read().split("\n## Python\n", 1)[1]
    snippet = section.split("```python\n", 1)[1].split("```", 1)[0]
    exec(compile(snippet, "README.md", "exec"), {})
    printed = capsys.readouterr().out
    assert printed.startswith("ThreeViewEstimate(success=True")
    assert "ThreeViewPoseErrors(rotation_deg=" in printed
