"""Shared helpers of the Python tests: synthetic scenes drawn by the module itself."""

import numpy as np
import pytest

import trigrav


def make_scene(seed, num_points=120, distortion=(0.0, 0.0, 0.0, 0.0), outlier_ratio=0.2):
    options = trigrav.SyntheticSceneOptions(
        num_points=num_points, pixel_noise_px=0.5, outlier_ratio=outlier_ratio,
        opencv_distortion=list(distortion))
    return trigrav.generate_synthetic_scene(options, seed)


def observations_from_numpy(scene):
    """The scene rebuilt from numpy arrays, as a user would."""
    return trigrav.ThreeViewObservations(
        pixels=[np.array(p) for p in scene.pixels], cameras=scene.camera,
        gravity_in_cam=scene.gravity_in_cam_measured)


@pytest.fixture
def scene():
    return make_scene(3)


@pytest.fixture
def observations(scene):
    return observations_from_numpy(scene)
