"""The triplet stage on Dask (ba/python/trigrav_pipeline): its CSV equals triplet_initializer's on
a synthetic database written by the test (consecutive and connected triplets, through the command
and through run() on a LocalCluster of 2 worker processes); a worker killed mid-run changes
nothing in the output; a bad database or gravity CSV fails before any task is scheduled.

triplet_initializer: $TRIGRAV_TRIPLET_INITIALIZER (set by ctest), else the build's
examples/colmap/triplet_initializer; the comparisons are skipped without it."""

import os
import signal
import subprocess
import sys
import threading
import time

import pytest

import trigrav

if not hasattr(trigrav, "Database"):
    pytest.skip("the module was built without trigrav::colmap (SQLite3)", allow_module_level=True)
distributed = pytest.importorskip("distributed", reason="python3-distributed is not installed")

import trigrav_pipeline  # noqa: E402
from trigrav_pipeline import pipeline, synthetic  # noqa: E402

NUM_IMAGES = 12  # 10 consecutive triplets


def triplet_initializer():
    path = os.environ.get("TRIGRAV_TRIPLET_INITIALIZER") or os.path.join(
        os.path.dirname(os.path.dirname(os.path.abspath(trigrav.__file__))), "examples", "colmap",
        "triplet_initializer")
    if not os.access(path, os.X_OK):
        pytest.skip(f"triplet_initializer not found ({path}; set TRIGRAV_TRIPLET_INITIALIZER)")
    return path


def tool_csv(tmp_path, database, gravity, *flags):
    """triplet_initializer's CSV for the database with the given flags (its seed model in
    <tmp_path>/tool.csv.model)."""
    output = tmp_path / "tool.csv"
    completed = subprocess.run(
        [triplet_initializer(), f"--database_path={database}", f"--gravity_csv={gravity}",
         f"--output_csv={output}", f"--output_model_path={output}.model", "--threads=2", *flags],
        capture_output=True, text=True, timeout=120)
    assert completed.returncode in (0, 1), completed.stderr
    return output.read_text()


@pytest.fixture(scope="module")
def scene(tmp_path_factory):
    folder = tmp_path_factory.mktemp("pipeline")
    database, gravity = str(folder / "database.db"), str(folder / "gravity.csv")
    synthetic.write_synthetic_database(database, gravity, num_images=NUM_IMAGES, seed=5)
    return database, gravity


@pytest.fixture(scope="module")
def client():
    """A LocalCluster of 2 worker processes of one thread (the command's default cluster)."""
    import logging
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None, silence_logs=logging.ERROR)
    with distributed.Client(cluster) as c:
        yield c
    cluster.close()


def test_in_process_partitions_equal_the_tool(scene, tmp_path):
    """Without Dask: estimate_partition over three partitions, merged, is the tool's CSV."""
    database, gravity = scene
    the_plan = trigrav_pipeline.plan(database, gravity)
    assert len(the_plan.triplets) == NUM_IMAGES - 2
    header, rows = None, ""
    for part in trigrav_pipeline.partitions(the_plan, 4):
        text, summary = trigrav_pipeline.estimate_partition(database, part, the_plan.options)
        assert summary["num_triplets"] == len(part.triplets)
        part_header, part_rows = trigrav_pipeline.split_csv(text)
        header = header or part_header
        rows += part_rows
    expected = tool_csv(tmp_path, database, gravity)
    assert header + rows == expected
    assert expected.count(",trusted,") >= NUM_IMAGES - 3


def test_command_on_a_local_cluster_equals_the_tool(scene, tmp_path):
    """python3 -m trigrav_pipeline with its own LocalCluster of 2 worker processes."""
    database, gravity = scene
    output, model = tmp_path / "dask.csv", tmp_path / "seed"
    completed = subprocess.run(
        [sys.executable, "-m", "trigrav_pipeline", "--database_path", database, "--gravity_csv",
         gravity, "--output_csv", str(output), "--output_model_path", str(model), "--workers",
         "2", "--partition_size", "3", "--no_progress"],
        capture_output=True, text=True, timeout=120)
    assert completed.returncode == 0, completed.stderr
    assert f"{NUM_IMAGES - 2} triplets (consecutive)" in completed.stdout
    assert output.read_text() == tool_csv(tmp_path, database, gravity)
    assert not os.path.exists(str(output) + ".parts")
    # The seed model is the tool's.
    tool_model = trigrav.read_model(str(tmp_path / "tool.csv.model"))
    ours = trigrav.read_model(str(model))
    assert sorted(ours.images) == sorted(tool_model.images)
    assert ours.num_points3D == tool_model.num_points3D
    for image_id, image in ours.images.items():
        assert (image.cam_from_world.R == tool_model.images[image_id].cam_from_world.R).all()


def test_command_with_a_scheduler_address_equals_the_tool(scene, tmp_path, client):
    """python3 -m trigrav_pipeline --scheduler <address>: the command is a client of a running
    cluster (here the module's LocalCluster, reached by its TCP address as a remote one would be)
    and runs its partitions on that cluster's workers."""
    database, gravity = scene
    output = tmp_path / "remote.csv"
    address = client.scheduler.address
    assert address.startswith("tcp://")
    completed = subprocess.run(
        [sys.executable, "-m", "trigrav_pipeline", "--database_path", database, "--gravity_csv",
         gravity, "--output_csv", str(output), "--scheduler", address, "--partition_size", "4",
         "--no_progress"],
        capture_output=True, text=True, timeout=120)
    assert completed.returncode == 0, completed.stderr
    assert output.read_text() == tool_csv(tmp_path, database, gravity)
    # The cluster's own worker processes ran the partitions (the command started none).
    ran = completed.stdout.split("worker processes ")[1].split()
    assert ran and {int(pid) for pid in ran} <= set(client.run(os.getpid).values())


@pytest.mark.parametrize("flags", [
    ("--triplets=connected",),
    ("--rotation_model=yaw_only", "--seed=7", "--max_triplets=6",
     "--min_tracks=30", "--check_gravity=false", "--engine=ceres"),
], ids=["connected", "options"])
def test_run_on_a_local_cluster_equals_the_tool(scene, tmp_path, client, flags):
    database, gravity = scene
    parsed = {f.split("=")[0][2:]: f.split("=")[1] for f in flags}
    options = trigrav_pipeline.TripletOptions(
        triplets=parsed.get("triplets", "consecutive"),
        rotation_model=parsed.get("rotation_model", "gravity_prior"),
        seed=int(parsed.get("seed", 1)),
        max_triplets=int(parsed.get("max_triplets", 0)),
        min_tracks=int(parsed.get("min_tracks", 20)),
        check_gravity=parsed.get("check_gravity", "true") == "true",
        engine=parsed.get("engine", trigrav_pipeline.TripletOptions().engine))
    output = tmp_path / "dask.csv"
    report = trigrav_pipeline.run(database, gravity, str(output), options, client=client,
                                  partition_size=2, progress=False)
    assert len(report.worker_pids) == 2  # both worker processes took partitions
    assert output.read_text() == tool_csv(tmp_path, database, gravity, *flags)


def test_bad_input_fails_before_scheduling(scene, tmp_path):
    database, gravity = scene

    class NoCluster:
        """Any use of the cluster fails the test."""
        def __getattr__(self, name):
            raise AssertionError(f"the cluster was used ({name}) before the input was checked")

    def run(database_path, gravity_csv, **options):
        return trigrav_pipeline.run(database_path, gravity_csv, str(tmp_path / "out.csv"),
                                    trigrav_pipeline.TripletOptions(**options),
                                    client=NoCluster(), progress=False)

    with pytest.raises(FileNotFoundError, match="missing.db"):
        run(str(tmp_path / "missing.db"), gravity)
    with pytest.raises(ValueError, match="gravity.csv"):
        run(gravity, gravity)  # not a database
    with pytest.raises(FileNotFoundError, match="missing.csv"):
        run(database, str(tmp_path / "missing.csv"))
    lines = open(gravity).read().splitlines()
    (tmp_path / "partial.csv").write_text("\n".join(lines[:5] + lines[6:]) + "\n")
    with pytest.raises(ValueError, match="000004.png"):  # the image without gravity is named
        run(database, str(tmp_path / "partial.csv"))
    (tmp_path / "malformed.csv").write_text("\n".join(lines[:3] + ["000002.png,0,1"]) + "\n")
    with pytest.raises(ValueError, match="malformed.csv:4"):
        run(database, str(tmp_path / "malformed.csv"))
    (tmp_path / "zero.csv").write_text("\n".join([lines[0], "000000.png,0,0,0"]) + "\n")
    with pytest.raises(ValueError, match="zero"):
        run(database, str(tmp_path / "zero.csv"))
    with pytest.raises(ValueError, match="min_tracks"):
        run(database, gravity, min_tracks=2)
    with pytest.raises(ValueError, match="unknown solver"):
        run(database, gravity, solver="9pt")
    # A database whose match row is malformed, or without COLMAP's tables.
    import shutil
    import sqlite3
    broken = str(tmp_path / "broken.db")
    shutil.copy(database, broken)
    with sqlite3.connect(broken) as connection:
        connection.execute("UPDATE two_view_geometries SET cols = 3 WHERE pair_id = ?",
                           (trigrav.pair_id(2, 3),))
    with pytest.raises(ValueError, match="images 2 and 3: 3 columns"):
        run(broken, gravity)
    with sqlite3.connect(broken) as connection:
        connection.execute("DROP TABLE two_view_geometries")
    with pytest.raises(ValueError, match="two_view_geometries"):
        run(broken, gravity)
    assert not os.path.exists(tmp_path / "out.csv")
    # The command says it on stderr, exit status 1, without starting a cluster.
    completed = subprocess.run(
        [sys.executable, "-m", "trigrav_pipeline", "--database_path", database, "--gravity_csv",
         str(tmp_path / "partial.csv"), "--output_csv", str(tmp_path / "out.csv")],
        capture_output=True, text=True, timeout=60)
    assert completed.returncode == 1 and "000004.png" in completed.stderr, completed.stderr
    completed = subprocess.run(
        [sys.executable, "-m", "trigrav_pipeline", "--database_path", database, "--gravity_csv",
         gravity, "--output_csv", str(tmp_path / "out.csv"), "--threshold_px", "-1"],
        capture_output=True, text=True, timeout=60)
    assert completed.returncode == 2 and "threshold_px" in completed.stderr


def test_a_killed_worker_changes_nothing(scene, tmp_path, client):
    """One worker process is killed (SIGKILL) while it runs a partition; the scheduler runs the
    lost partition again, and the CSV equals the fault-free run's."""
    database, gravity = scene
    expected_path = tmp_path / "fault_free.csv"
    trigrav_pipeline.run(database, gravity, str(expected_path), client=client, partition_size=2,
                         progress=False)
    output = tmp_path / "with_fault.csv"
    outcome = {}

    def run_in_background():
        try:
            outcome["report"] = trigrav_pipeline.run(
                database, gravity, str(output), client=client, partition_size=1, progress=False,
                delay_s=0.5)
        except BaseException as error:  # reported by the main thread
            outcome["error"] = error

    thread = threading.Thread(target=run_in_background)
    thread.start()
    victim = None
    deadline = time.time() + 30
    while victim is None and time.time() < deadline:
        busy = {address: [str(k) for k in keys if "trigrav-triplets" in str(k)]
                for address, keys in client.processing().items()}
        busy = {address: keys for address, keys in busy.items() if keys}
        if busy:
            address, lost = next(iter(busy.items()))
            victim = client.run(os.getpid, workers=[address])[address]
        else:
            time.sleep(0.05)
    assert victim is not None, "no worker started a partition"
    os.kill(victim, signal.SIGKILL)
    thread.join(timeout=120)
    assert not thread.is_alive()
    assert "error" not in outcome, outcome.get("error")
    report = outcome["report"]
    # The partitions the killed worker held were run again by another process.
    lost_partitions = [int(key.rsplit("-", 1)[1]) for key in lost]
    assert all(report.partition_pids[p] != victim for p in lost_partitions), \
        (victim, lost_partitions, report.partition_pids)
    assert output.read_text() == expected_path.read_text()


def test_parts_are_reused_after_an_interrupted_run(scene, tmp_path, client):
    """Finished partitions survive a failed run and are not estimated again."""
    database, gravity = scene
    output = str(tmp_path / "out.csv")
    the_plan = trigrav_pipeline.plan(database, gravity)
    parts = trigrav_pipeline.partitions(the_plan, 3)
    store = pipeline.PartStore(output, the_plan.fingerprint(), len(parts))
    text, summary = trigrav_pipeline.estimate_partition(database, parts[1], the_plan.options)
    store.write(1, text, summary)
    report = trigrav_pipeline.run(database, gravity, output, client=client, partition_size=3,
                                  progress=False)
    assert report.reused_partitions == 1
    fresh = str(tmp_path / "fresh.csv")
    trigrav_pipeline.run(database, gravity, fresh, client=client, partition_size=3,
                         progress=False)
    assert open(output).read() == open(fresh).read()


def test_real_kitti_database_equals_the_tool(tmp_path, client):
    """The database ctest colmap_walkthrough_kitti makes from KITTI frames, when it is there."""
    from test_colmap_bindings import kitti_database
    database, gravity = kitti_database(tmp_path)
    output = tmp_path / "kitti.csv"
    trigrav_pipeline.run(database, gravity, str(output), client=client, partition_size=1,
                         progress=False)
    assert output.read_text() == tool_csv(tmp_path, database, gravity)
