"""trigrav.colmap from Python (ba/python/bind_colmap.cc, bind_nview.cc): COLMAP models in text and
binary, the read-only database reader, the gravity CSV, the model <-> N-view conversion and
refine_with_gravity, with numpy arrays; bad input raising ValueError / OSError naming the problem.
The inputs are written by the tests: a small model, and a synthetic database
(trigrav_pipeline.synthetic)."""

import math
import os

import numpy as np
import pytest

import trigrav
from trigrav_pipeline import database_subset, synthetic

if not hasattr(trigrav, "Database"):
    pytest.skip("the module was built without trigrav::colmap (SQLite3)", allow_module_level=True)

PINHOLE = trigrav.Camera("PINHOLE", [500.0, 500.0, 320.0, 240.0])


def rotation_y(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, 0.0, -s], [0.0, 1.0, 0.0], [s, 0.0, c]])


def make_model(num_images=5, num_points=60, seed=4, noise_px=0.3):
    """A sequence of PINHOLE images moving along x, each seeing every point (world y down);
    returns (model, exact gravity by name, true centres)."""
    rng = np.random.default_rng(seed)
    model = trigrav.Reconstruction()
    model.cameras = {1: trigrav.ColmapCamera(1, PINHOLE, 640, 480)}
    points = np.column_stack([rng.uniform(-3, 5, num_points), rng.uniform(-2, 2, num_points),
                              rng.uniform(6, 12, num_points)])
    images, gravity, centers = {}, {}, []
    tracks = [[] for _ in range(num_points)]
    for k in range(num_images):
        R = rotation_y(0.03 * k)
        center = np.array([0.5 * k, 0.02 * k, 0.1 * k])
        pose = trigrav.CameraPose(R, -R @ center)
        in_cam = pose.apply(points)
        pixels = PINHOLE.project(in_cam) + rng.normal(0, noise_px, (num_points, 2))
        name = f"im{k:02d}.png"
        images[k + 1] = trigrav.ColmapImage(k + 1, name, 1, pose, pixels,
                                            np.arange(num_points) + 1)
        gravity[name] = R @ np.array([0.0, 1.0, 0.0])
        centers.append(center)
        for p in range(num_points):
            tracks[p].append((k + 1, p))
    model.images = images
    model.points3D = {p + 1: trigrav.ColmapPoint3D(points[p], (128, 128, 128), 0.5, tracks[p])
                      for p in range(num_points)}
    return model, gravity, np.array(centers)


def assert_same_model(a, b):
    assert sorted(a.cameras) == sorted(b.cameras)
    for cid in a.cameras:
        assert a.cameras[cid].camera.params == b.cameras[cid].camera.params
        assert (a.cameras[cid].width, a.cameras[cid].height) == \
            (b.cameras[cid].width, b.cameras[cid].height)
    assert sorted(a.images) == sorted(b.images)
    for iid, image in a.images.items():
        other = b.images[iid]
        assert image.name == other.name and image.camera_id == other.camera_id
        np.testing.assert_allclose(image.cam_from_world.R, other.cam_from_world.R, atol=1e-12)
        np.testing.assert_allclose(image.cam_from_world.t, other.cam_from_world.t, atol=1e-12)
        np.testing.assert_allclose(image.points2D, other.points2D, atol=1e-9)
        np.testing.assert_array_equal(image.point3D_ids, other.point3D_ids)
    np.testing.assert_array_equal(a.point3D_ids, b.point3D_ids)
    np.testing.assert_allclose(a.points3D_xyz, b.points3D_xyz, atol=1e-12)
    for pid, point in a.points3D.items():
        np.testing.assert_array_equal(point.track, b.points3D[pid].track)
        np.testing.assert_array_equal(point.color, b.points3D[pid].color)


@pytest.fixture(scope="module")
def database(tmp_path_factory):
    folder = tmp_path_factory.mktemp("colmap_db")
    path, gravity = str(folder / "database.db"), str(folder / "gravity.csv")
    synthetic.write_synthetic_database(path, gravity, num_images=7, seed=3)
    return path, gravity


# --- models -------------------------------------------------------------------------------------


@pytest.mark.parametrize("model_format", [trigrav.ModelFormat.TEXT, trigrav.ModelFormat.BINARY])
def test_model_round_trip(tmp_path, model_format):
    model, _, _ = make_model()
    model.check()
    folder = str(tmp_path / "sparse")
    trigrav.write_model(model, folder, model_format)
    suffix = ".txt" if model_format == trigrav.ModelFormat.TEXT else ".bin"
    assert all(os.path.exists(os.path.join(folder, f + suffix))
               for f in ("cameras", "images", "points3D"))
    read = trigrav.read_model(folder)
    assert (read.num_cameras, read.num_images, read.num_points3D) == (1, 5, 60)
    assert_same_model(model, read)
    assert_same_model(model, trigrav.read_model(folder, model_format))
    # The other format replaces the set as a whole.
    other = trigrav.ModelFormat.BINARY if model_format == trigrav.ModelFormat.TEXT else \
        trigrav.ModelFormat.TEXT
    trigrav.write_model(read, folder, other)
    assert not os.path.exists(os.path.join(folder, "cameras" + suffix))
    assert_same_model(model, trigrav.read_model(folder))


def test_model_arrays_and_copies():
    model, _, _ = make_model()
    image = model.images[2]
    assert image.points2D.shape == (60, 2) and image.points2D.dtype == np.float64
    assert image.point3D_ids.dtype == np.int64
    image.point3D_ids = np.full(60, -1)
    assert (image.point3D_ids == -1).all()
    # Reading a dict entry gives a copy: assign the dict back to change the model.
    model.images[2].name = "changed.png"
    assert model.images[2].name == "im01.png"
    images = model.images
    images[2].name = "changed.png"
    model.images = images
    assert model.images[2].name == "changed.png"
    point = model.points3D[1]
    assert point.track.shape == (5, 2) and point.track.dtype == np.uint32
    assert point.color.dtype == np.uint8


def test_model_write_and_read_errors(tmp_path):
    model, _, _ = make_model()
    with pytest.raises(FileNotFoundError, match="no such folder"):
        trigrav.read_model(str(tmp_path / "missing"))
    bad = trigrav.Reconstruction()
    bad.cameras = model.cameras
    image = model.images[1]
    image.camera_id = 7
    bad.images = {1: image}
    with pytest.raises(ValueError, match="camera"):
        bad.check()
    with pytest.raises(ValueError, match="camera"):
        trigrav.write_model(bad, str(tmp_path / "bad"))
    assert not os.path.exists(tmp_path / "bad")
    # A folder holding something else is not replaced.
    other = tmp_path / "other"
    other.mkdir()
    (other / "notes.txt").write_text("mine")
    with pytest.raises(OSError, match="other"):
        trigrav.write_model(model, str(other))
    assert (other / "notes.txt").read_text() == "mine"
    with pytest.raises(OSError):
        trigrav.write_model(model, str(tmp_path / "a" / "b" / "c"))
    trigrav.write_model(model, str(tmp_path / "a" / "b" / "c"), create_parents=True)
    # A malformed record names the file.
    folder = tmp_path / "text"
    trigrav.write_model(model, str(folder), trigrav.ModelFormat.TEXT)
    (folder / "cameras.txt").write_text("1 PINHOLE 640 480 500 500\n")
    with pytest.raises(ValueError, match="cameras.txt"):
        trigrav.read_model(str(folder))
    (folder / "cameras.txt").unlink()
    with pytest.raises(FileNotFoundError, match="cameras.txt"):
        trigrav.read_model(str(folder), trigrav.ModelFormat.TEXT)
    with pytest.raises(ValueError, match="point3D_ids"):
        trigrav.ColmapImage(1, "a.png", 1, trigrav.CameraPose(), np.zeros((2, 2)), [0, -2])
    with pytest.raises(ValueError, match="track"):
        trigrav.ColmapPoint3D([0, 0, 1], track=np.zeros((2, 3), dtype=int))


# --- gravity CSV --------------------------------------------------------------------------------


def test_gravity_csv_round_trip_and_errors(tmp_path):
    gravity = {"b.png": np.array([0.0, 2.0, 0.1]), "a.png": [0.01, 0.99, -0.02]}
    path = str(tmp_path / "gravity.csv")
    trigrav.write_gravity_csv(gravity, path)
    read = trigrav.read_gravity_csv(path)
    assert list(read) == ["a.png", "b.png"]
    np.testing.assert_array_equal(read["b.png"], [0.0, 2.0, 0.1])
    np.testing.assert_array_equal(trigrav.gravity_of_images(read, ["b.png", "a.png"]),
                                  [[0.0, 2.0, 0.1], [0.01, 0.99, -0.02]])
    with pytest.raises(ValueError, match="c.png"):
        trigrav.gravity_of_images(read, ["a.png", "c.png"])
    with pytest.raises(FileNotFoundError, match="gravity CSV"):
        trigrav.read_gravity_csv(str(tmp_path / "missing.csv"))
    (tmp_path / "bad.csv").write_text("image_name,gravity_x,gravity_y,gravity_z\na.png,1,2\n")
    with pytest.raises(ValueError, match="bad.csv:2"):
        trigrav.read_gravity_csv(str(tmp_path / "bad.csv"))
    with pytest.raises(ValueError, match="zero or non-finite"):
        trigrav.write_gravity_csv({"a.png": [0, 0, 0]}, str(tmp_path / "zero.csv"))
    assert not os.path.exists(tmp_path / "zero.csv")
    with pytest.raises(ValueError, match=r"gravity\['a.png'\]"):
        trigrav.write_gravity_csv({"a.png": [0, 1]}, str(tmp_path / "short.csv"))
    with pytest.raises(OSError):
        trigrav.write_gravity_csv(gravity, str(tmp_path / "no_folder" / "g.csv"))


# --- database -----------------------------------------------------------------------------------


def test_database_reads_numpy(database):
    path, _ = database
    with trigrav.Database(path) as db:
        cameras = db.read_cameras()
        images = db.read_images()
        keypoints = db.read_keypoints(images[0].image_id)
        geometries = db.read_two_view_geometries()
    assert db.closed
    assert [(c.camera_id, c.camera.model, c.width, c.height) for c in cameras] == \
        [(1, "PINHOLE", 640, 480)]
    assert [i.name for i in images] == [f"{k:06d}.png" for k in range(7)]
    assert keypoints.dtype == np.float64 and keypoints.ndim == 2 and keypoints.shape[1] == 2
    assert len(keypoints) > 20
    # The first two float32 columns of COLMAP's 6-column rows.
    assert np.array_equal(keypoints, keypoints.astype(np.float32).astype(np.float64))
    assert len(geometries) == 6 + 5 + 4  # each image with the next three
    g = geometries[0]
    assert (g.image_id1, g.image_id2, g.config) == (1, 2, 2)
    assert g.matches.dtype == np.uint32 and g.matches.shape[1] == 2
    assert trigrav.images_of_pair_id(trigrav.pair_id(2, 1)) == (1, 2)
    # The pipeline's partial reader gives the same geometries.
    pairs = [(i.image_id, j.image_id) for i in images for j in images if i.image_id < j.image_id]
    subset = database_subset.read_two_view_geometries(path, pairs)
    assert [(s.image_id1, s.image_id2, s.config) for s in subset] == \
        [(s.image_id1, s.image_id2, s.config) for s in geometries]
    for a, b in zip(subset, geometries):
        np.testing.assert_array_equal(a.matches, b.matches)
    assert len(database_subset.read_two_view_geometries(path, [(3, 2), (1, 7)])) == 1


def test_database_errors(database, tmp_path):
    path, gravity_csv = database
    with pytest.raises(FileNotFoundError, match="no such file"):
        trigrav.Database(str(tmp_path / "missing.db"))
    with pytest.raises(ValueError, match="gravity.csv"):
        trigrav.Database(gravity_csv)  # not an SQLite database
    db = trigrav.Database(path)
    with pytest.raises(ValueError, match="no image 99"):
        db.read_keypoints(99)
    db.close()
    with pytest.raises(ValueError, match="closed"):
        db.read_images()


def test_tracks_and_triplets(database):
    path, _ = database
    with trigrav.Database(path) as db:
        graph = trigrav.MatchGraph(db.read_two_view_geometries())
        ids = np.array([i.image_id for i in sorted(db.read_images(), key=lambda i: i.name)])
    assert graph.num_matches(1, 2) > 20 and graph.num_matches(1, 5) == 0
    np.testing.assert_array_equal(graph.neighbors(1), [2, 3, 4])
    matches = graph.matches(2, 1)
    assert graph.match(2, int(matches[0, 0]), 1) == matches[0, 1]
    triplets = trigrav.consecutive_triplets(ids)
    assert triplets.shape == (5, 3) and triplets.dtype == np.uint32
    tracks = trigrav.three_view_tracks(graph, triplets[0])
    assert tracks.shape[1] == 3 and len(tracks) > 20
    assert len(trigrav.three_view_tracks(graph, [1, 5, 7])) == 0
    connected = trigrav.connected_triplets(graph, ids, 10)
    assert connected.shape[1] == 3 and set(np.unique(connected)) == set(ids)
    with pytest.raises(ValueError, match="max_triplets"):
        trigrav.connected_triplets(graph, ids, 0)
    with pytest.raises(ValueError, match="expected 3 image ids"):
        trigrav.three_view_tracks(graph, [1, 2])


# --- N-view bundle adjustment -------------------------------------------------------------------


def test_refine_with_gravity_on_a_model():
    model, gravity, centers = make_model()
    nview_input = trigrav.to_nview(model, gravity)
    np.testing.assert_array_equal(nview_input.image_ids, [1, 2, 3, 4, 5])
    np.testing.assert_array_equal(nview_input.point_ids, np.arange(1, 61))
    reconstruction = nview_input.reconstruction
    assert reconstruction.num_observations == 300
    assert reconstruction.observation_pixels.shape == (300, 2)
    # Perturb the points; the poses stay (the gauge: image 0's pose, image 4's centre coordinate).
    rng = np.random.default_rng(1)
    start = reconstruction.points_in_world
    perturbed = start + rng.normal(0, 0.05, start.shape)
    reconstruction.points_in_world = perturbed
    options = trigrav.NViewBundleAdjustmentOptions(compute_covariance=True)
    summary, refined = trigrav.refine_with_gravity(reconstruction, options=options)
    assert summary.success, summary.message
    assert (summary.num_images, summary.num_points, summary.num_observations) == (5, 60, 300)
    assert summary.residual_rms_px.shape == (5,)
    assert len(summary.covariances) == 5 and summary.covariances[1].shape == (4, 4)
    np.testing.assert_allclose(np.linalg.norm(summary.gravity_in_world), 1.0)
    assert summary.final_cost < summary.initial_cost and summary.iterations > 0
    np.testing.assert_allclose(refined.centers[0], centers[0], atol=1e-9)
    # Near the noise (0.3 px per coordinate), far below the perturbation's residuals.
    assert 0.2 < np.median(summary.residual_rms_px) < 0.6
    assert np.abs(refined.points_in_world - start).mean() < \
        np.abs(perturbed - start).mean()
    back = trigrav.from_nview(model, nview_input, refined)
    assert back.num_points3D == 60
    assert all(0 <= p.error < 1.0 for p in back.points3D.values())
    # Yaw-only: every image's tilt exactly that of its gravity.
    summary, refined = trigrav.refine_with_gravity(
        reconstruction, trigrav.NViewBundleAdjustmentConfig(constant_points=True),
        trigrav.NViewBundleAdjustmentOptions(
            rotation_model=trigrav.ThreeViewBundleAdjustmentOptions.RotationModel.YAW_ONLY))
    assert summary.success, summary.message
    for k, image in enumerate(refined.images):
        g = image.cam_from_world.R @ summary.gravity_in_world
        np.testing.assert_allclose(g, refined.gravity_in_cam[k] /
                                   np.linalg.norm(refined.gravity_in_cam[k]), atol=1e-9)
    np.testing.assert_array_equal(reconstruction.points_in_world, perturbed)  # input unchanged


def test_gravity_verdict_names_a_flipped_gravity_and_upright():
    model, gravity, _ = make_model(num_images=6)
    gravity["im02.png"] = -gravity["im02.png"]
    nview_input = trigrav.to_nview(model, gravity)
    summary, refined = trigrav.refine_with_gravity(
        nview_input.reconstruction, options=trigrav.NViewBundleAdjustmentOptions(
            rotation_model=trigrav.ThreeViewBundleAdjustmentOptions.RotationModel.GRAVITY_PRIOR))
    assert summary.success, summary.message
    assert summary.gravity_disagreement_deg.shape == (6,)
    assert summary.gravity_disagreement_deg[2] > 170
    np.testing.assert_array_equal(summary.gravity_used, [True, True, False, True, True, True])
    assert summary.gravity_used.dtype == np.bool_
    assert "gravity left out of image(s) 2 " in summary.message, summary.message
    # The images-dominated solve moves the consistent images (the flipped prior does not stall it).
    assert (summary.gravity_disagreement_deg[[0, 1, 3, 4, 5]] > 0).all()
    assert 0.005 < summary.estimated_gravity_sigma_deg < 0.1
    assert f"IMU sigma estimated at {summary.estimated_gravity_sigma_deg:.6g} deg" in \
        summary.message, summary.message
    assert summary.observations_per_image.tolist() == [60] * 6
    assert summary.images_losing_observations.tolist() == []
    assert summary.rotation_model == \
        trigrav.ThreeViewBundleAdjustmentOptions.RotationModel.GRAVITY_PRIOR
    assert (summary.residual_rms_px < 0.6).all()
    # Upright: +y along the world's gravity; every consistent image's gravity points along it.
    upright = trigrav.upright_reconstruction(refined, summary.gravity_in_world)
    for k, image in enumerate(upright.images):
        if k != 2:
            g = image.cam_from_world.R.T @ upright.gravity_in_cam[k]
            np.testing.assert_allclose(g / np.linalg.norm(g), [0, 1, 0], atol=1e-3)
    with pytest.raises(ValueError):
        trigrav.upright_reconstruction(refined, [0, 0, 0])
    # Without the verdict the arrays are empty.
    summary, _ = trigrav.refine_with_gravity(
        trigrav.to_nview(*make_model()[:2]).reconstruction,
        options=trigrav.NViewBundleAdjustmentOptions(check_gravity=False))
    assert summary.gravity_disagreement_deg.shape == (0,)
    assert math.isnan(summary.estimated_gravity_sigma_deg)


def test_nview_errors():
    model, gravity, _ = make_model()
    del gravity["im03.png"]
    with pytest.raises(ValueError, match="im03.png"):
        trigrav.to_nview(model, gravity)
    with pytest.raises(ValueError, match="max_num_iterations"):
        trigrav.NViewBundleAdjustmentOptions(max_num_iterations=-1)
    with pytest.raises(TypeError, match="unexpected keyword"):
        trigrav.NViewBundleAdjustmentOptions(sigma=1)
    model, gravity, _ = make_model()
    reconstruction = trigrav.to_nview(model, gravity).reconstruction
    with pytest.raises(ValueError, match="reference_image"):
        trigrav.refine_with_gravity(reconstruction,
                                    trigrav.NViewBundleAdjustmentConfig(reference_image=9))
    with pytest.raises(ValueError, match="differ in length"):
        trigrav.NViewReconstruction([PINHOLE], [], np.zeros((1, 3)), [0], [0, 0], [[1, 2]])
    images = reconstruction.images
    images[1].gravity_in_cam = [0, 0, 0]
    reconstruction.images = images
    with pytest.raises(ValueError, match="gravity"):
        reconstruction.check()
    with pytest.raises(ValueError, match="gravity"):
        trigrav.refine_with_gravity(reconstruction)


def test_options_reprs_and_defaults():
    options = trigrav.NViewBundleAdjustmentOptions()
    assert options.gravity_sigma_deg == 0.1 and options.max_num_iterations == 100
    assert options.linear_solver_type == \
        trigrav.ThreeViewBundleAdjustmentOptions.LinearSolverType.SPARSE_SCHUR
    assert repr(options).startswith("NViewBundleAdjustmentOptions(rotation_model=")
    config = trigrav.NViewBundleAdjustmentConfig(constant_images=[1, 2])
    assert config.constant_images == [1, 2] and config.scale_image == -1
    assert options.check_gravity and options.gravity_sigma_from_data
    assert trigrav.NViewBundleAdjustmentOptions.VERDICT_GRAVITY_SIGMA_DEG == 10.0
    with pytest.raises(ValueError, match="max_gravity_disagreement_sigmas"):
        trigrav.NViewBundleAdjustmentOptions(max_gravity_disagreement_sigmas=0)


# --- the real database CI makes from KITTI frames (when there) ---------------------------------


def kitti_database(tmp_path):
    """A snapshot (in tmp_path) of the database and gravity CSV of ctest colmap_walkthrough_kitti
    (five KITTI 00 frames through the real COLMAP), if it has run in this build, or of
    TRIGRAV_KITTI_DATABASE / TRIGRAV_KITTI_GRAVITY_CSV. The snapshot (SQLite's backup: a
    consistent copy) keeps a walkthrough running meanwhile from changing the input under the
    test; a database without verified matches yet is skipped."""
    import shutil
    import sqlite3
    build = os.path.dirname(os.path.dirname(os.path.abspath(trigrav.__file__)))
    database = os.environ.get("TRIGRAV_KITTI_DATABASE") or \
        os.path.join(build, "tests", "colmap_walkthrough_kitti", "database.db")
    gravity = os.environ.get("TRIGRAV_KITTI_GRAVITY_CSV") or \
        os.path.join(os.path.dirname(database), "gravity.csv")
    if not (os.path.isfile(database) and os.path.isfile(gravity)):
        pytest.skip(f"no KITTI database at {database} (ctest colmap_walkthrough_kitti makes it)")
    copy, gravity_copy = str(tmp_path / "kitti.db"), str(tmp_path / "kitti_gravity.csv")
    try:
        with database_subset.connect_read_only(database) as source, \
                sqlite3.connect(copy) as target:
            source.backup(target)
        shutil.copy(gravity, gravity_copy)
        with trigrav.Database(copy) as db:
            usable = len(db.read_two_view_geometries()) > 0
        trigrav.read_gravity_csv(gravity_copy)
    except (sqlite3.Error, OSError, ValueError) as error:
        pytest.skip(f"the KITTI database at {database} is not usable now: {error}")
    if not usable:
        pytest.skip(f"the KITTI database at {database} has no verified matches (yet)")
    return copy, gravity_copy


def test_real_kitti_database(tmp_path):
    path, gravity_csv = kitti_database(tmp_path)
    gravity = trigrav.read_gravity_csv(gravity_csv)
    with trigrav.Database(path) as db:
        images = db.read_images()
        assert len(images) >= 3 and all(i.name in gravity for i in images)
        assert db.read_cameras()[0].camera.model == "PINHOLE"
        assert all(len(db.read_keypoints(i.image_id)) > 100 for i in images)
        geometries = db.read_two_view_geometries()
    subset = database_subset.read_two_view_geometries(
        path, [(g.image_id1, g.image_id2) for g in geometries])
    assert len(subset) == len(geometries)
    for a, b in zip(subset, geometries):
        np.testing.assert_array_equal(a.matches, b.matches)
