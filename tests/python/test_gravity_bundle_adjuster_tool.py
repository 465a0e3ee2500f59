"""examples/colmap/gravity_bundle_adjuster end to end, checked through the bindings: the gravity
verdict names a flipped gravity and keeps the model, --upright writes a world whose +y is gravity,
--gravity_report_csv has one row per image, a model that the refinement would make worse (wrong
gravity taken as exact) is refused with the image named and nothing written, and yaw-only asked for
with 0.1-0.5 deg of IMU noise never writes a model worse than its input.

The tool: $TRIGRAV_GRAVITY_BUNDLE_ADJUSTER (set by ctest), else the build's."""

import csv
import math
import os
import subprocess

import numpy as np
import pytest

import trigrav

if not hasattr(trigrav, "Database"):
    pytest.skip("the module was built without trigrav::colmap (SQLite3)", allow_module_level=True)

PINHOLE = trigrav.Camera("PINHOLE", [500.0, 500.0, 320.0, 240.0])
NUM_IMAGES = 6


def adjuster():
    path = os.environ.get("TRIGRAV_GRAVITY_BUNDLE_ADJUSTER") or os.path.join(
        os.path.dirname(os.path.dirname(os.path.abspath(trigrav.__file__))), "examples", "colmap",
        "gravity_bundle_adjuster")
    if not os.access(path, os.X_OK):
        pytest.skip(f"gravity_bundle_adjuster not found ({path}; set "
                    "TRIGRAV_GRAVITY_BUNDLE_ADJUSTER)")
    return path


def rotation(axis, angle):
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + math.sin(angle) * k + (1 - math.cos(angle)) * k @ k


# A world tilted by 20 deg from the gravity-aligned one (+y down): --upright must undo it.
WORLD_FROM_UPRIGHT = rotation([1.0, 0.0, 0.5], math.radians(20.0))


def make_model(seed=7, noise_px=0.3):
    """Images moving along x, each seeing every point, in the tilted world; returns (model, exact
    gravity by name)."""
    rng = np.random.default_rng(seed)
    points_upright = np.column_stack([rng.uniform(-3, 5, 80), rng.uniform(-2, 2, 80),
                                      rng.uniform(6, 12, 80)])
    points = points_upright @ WORLD_FROM_UPRIGHT.T
    model = trigrav.Reconstruction()
    model.cameras = {1: trigrav.ColmapCamera(1, PINHOLE, 640, 480)}
    images, gravity = {}, {}
    tracks = [[] for _ in range(len(points))]
    for k in range(NUM_IMAGES):
        cam_from_upright = rotation([0.0, 1.0, 0.0], 0.03 * k)
        R = cam_from_upright @ WORLD_FROM_UPRIGHT.T
        center = WORLD_FROM_UPRIGHT @ np.array([0.5 * k, 0.02 * k, 0.1 * k])
        pose = trigrav.CameraPose(R, -R @ center)
        pixels = PINHOLE.project(pose.apply(points)) + rng.normal(0, noise_px, (len(points), 2))
        name = f"im{k:02d}.png"
        images[k + 1] = trigrav.ColmapImage(k + 1, name, 1, pose, pixels,
                                            np.arange(len(points)) + 1)
        gravity[name] = cam_from_upright @ np.array([0.0, 1.0, 0.0])
        for p in range(len(points)):
            tracks[p].append((k + 1, p))
    model.images = images
    model.points3D = {p + 1: trigrav.ColmapPoint3D(points[p], (128, 128, 128), 0.5, tracks[p])
                      for p in range(len(points))}
    return model, gravity


def run_tool(tmp_path, gravity, *flags):
    model, exact = make_model()
    model_path, gravity_path = tmp_path / "model", tmp_path / "gravity.csv"
    if not model_path.exists():
        trigrav.write_model(model, str(model_path))
    trigrav.write_gravity_csv(gravity if gravity is not None else exact, str(gravity_path))
    return subprocess.run([adjuster(), f"--input_path={model_path}",
                           f"--gravity_csv={gravity_path}", *flags],
                          capture_output=True, text=True, timeout=120)


def with_gravity_of_im02(transform):
    _, gravity = make_model()
    gravity["im02.png"] = transform(gravity["im02.png"])
    return gravity


def gravity_in_world(model, gravity):
    """Per image, R^T g (unit): the world's down direction that the image's gravity implies."""
    directions = {}
    for image in model.images.values():
        g = image.cam_from_world.R.T @ gravity[image.name]
        directions[image.name] = g / np.linalg.norm(g)
    return directions


def test_flipped_gravity_is_dropped_and_named_and_upright_puts_gravity_on_y(tmp_path):
    flipped = with_gravity_of_im02(lambda g: -g)
    report = tmp_path / "report.csv"
    result = run_tool(tmp_path, flipped, f"--output_path={tmp_path / 'upright'}", "--upright",
                      f"--gravity_report_csv={report}")
    assert result.returncode == 0, result.stderr
    assert "gravity dropped for im02.png (1" in result.stdout, result.stdout  # 17x or 180 deg
    assert "IMU sigma estimated from the data" in result.stdout
    with open(report) as f:
        rows = list(csv.DictReader(f))
    assert [row["image_name"] for row in rows] == [f"im{k:02d}.png" for k in range(NUM_IMAGES)]
    for row in rows:
        dropped = row["image_name"] == "im02.png"
        assert row["gravity_used"] == ("0" if dropped else "1")
        assert (float(row["gravity_disagreement_deg"]) > 170) == dropped
        assert int(row["observations"]) == 80
        assert float(row["rms_after_px"]) < 0.6 and float(row["rms_before_px"]) < 0.6
    # Upright: every consistent image's gravity points along +y of the written world ...
    _, exact = make_model()
    upright = trigrav.read_model(str(tmp_path / "upright"))
    for name, direction in gravity_in_world(upright, exact).items():
        np.testing.assert_allclose(direction, [0.0, 1.0, 0.0], atol=2e-3, err_msg=name)
    # ... while without --upright the world stays the input's, tilted by 20 deg.
    result = run_tool(tmp_path, flipped, f"--output_path={tmp_path / 'kept'}")
    assert result.returncode == 0, result.stderr
    kept = trigrav.read_model(str(tmp_path / "kept"))
    for name, direction in gravity_in_world(kept, exact).items():
        np.testing.assert_allclose(direction, WORLD_FROM_UPRIGHT @ [0.0, 1.0, 0.0], atol=2e-3,
                                   err_msg=name)


@pytest.mark.parametrize("error", ["flipped", "10 deg"])
def test_wrong_gravity_taken_as_exact_is_refused_and_nothing_written(tmp_path, error):
    wrong = with_gravity_of_im02(
        (lambda g: -g) if error == "flipped"
        else (lambda g: rotation([1.0, 0.0, 0.0], math.radians(10.0)) @ g))
    output, report = tmp_path / "refined", tmp_path / "report.csv"
    result = run_tool(tmp_path, wrong, f"--output_path={output}", "--rotation_model=yaw_only",
                      "--check_gravity=false", "--gravity_sigma_deg=0.1",
                      f"--gravity_report_csv={report}")
    assert result.returncode == 1, result.stdout
    assert "im02.png" in result.stderr and "nothing written" in result.stderr, result.stderr
    assert not output.exists() and not report.exists()
    assert sorted(os.listdir(tmp_path)) == ["gravity.csv", "model"]
    # The verdict (the default) keeps the image and the model.
    result = run_tool(tmp_path, wrong, f"--output_path={output}", "--rotation_model=yaw_only")
    assert result.returncode == 0, result.stderr
    assert "gravity dropped for im02.png" in result.stdout, result.stdout


def test_sigma_from_data_needs_the_verdict(tmp_path):
    result = run_tool(tmp_path, None, f"--output_path={tmp_path / 'out'}",
                      "--check_gravity=false")
    assert result.returncode == 2
    assert "--gravity_sigma_deg=0 (from the data) needs --check_gravity" in result.stderr
    assert not (tmp_path / "out").exists()


def with_imu_noise(noise_deg, seed=3):
    """Every image's gravity tilted by a random angle of sigma noise_deg about a random axis."""
    rng = np.random.default_rng(seed)
    _, gravity = make_model()
    for name, g in gravity.items():
        axis = np.cross(g, rng.normal(size=3))
        gravity[name] = rotation(axis, math.radians(noise_deg) * abs(rng.normal())) @ g
    return gravity


@pytest.mark.parametrize("noise_deg", [0.1, 0.5])
def test_yaw_only_with_imu_noise_never_writes_a_worse_model(tmp_path, noise_deg):
    noisy = with_imu_noise(noise_deg)
    report = tmp_path / "report.csv"
    # Defaults: the verdict refuses exact tilts and solves the prior; every image improves.
    result = run_tool(tmp_path, noisy, f"--output_path={tmp_path / 'refined'}",
                      "--rotation_model=yaw_only", f"--gravity_report_csv={report}")
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith("gravity bundle adjustment (gravity_prior"), result.stdout
    with open(report) as f:
        for row in csv.DictReader(f):
            assert float(row["rms_after_px"]) <= float(row["rms_before_px"]), row
    # Without the verdict, yaw-only at 0.5 deg degrades an image: refused, nothing written.
    if noise_deg == 0.5:
        output = tmp_path / "forced"
        result = run_tool(tmp_path, noisy, f"--output_path={output}", "--rotation_model=yaw_only",
                          "--check_gravity=false", "--gravity_sigma_deg=0.5")
        assert result.returncode == 1
        assert "worse than the input: image im0" in result.stderr, result.stderr
        assert not output.exists()
