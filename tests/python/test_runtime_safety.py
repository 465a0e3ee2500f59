"""The bindings keep their word at run time: calls work on copies while the GIL is released, Ctrl-C
ends long calls and batches promptly, a batch names every bad item (or returns its error in
place), and a system that cannot create the threads asked for slows a batch down without killing
the interpreter."""

import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np
import pytest

import trigrav
from conftest import make_scene, observations_from_numpy


def pose_bytes(estimate):
    pose = estimate.refined
    return pose.cam2_from_cam1.R.tobytes() + pose.cam3_from_cam1.t.tobytes()


def test_a_call_is_not_disturbed_by_another_thread_reassigning_its_input():
    # The same triplets in two orders: two valid inputs with different (bit-exact) answers.
    observations = observations_from_numpy(make_scene(1, num_points=150))
    pixels_a = [np.array(p) for p in observations.pixels]
    pixels_b = [p[::-1].copy() for p in pixels_a]
    expected = set()
    for pixels in (pixels_a, pixels_b):
        observations.pixels = pixels
        estimate = trigrav.initialize_and_refine(observations)
        assert estimate.success, estimate.message
        expected.add(pose_bytes(estimate))
    assert len(expected) == 2
    stop = threading.Event()

    def reassign():
        while not stop.is_set():
            for pixels in (pixels_b, pixels_a):
                observations.pixels = pixels

    writer = threading.Thread(target=reassign)
    writer.start()
    try:
        for _ in range(40):
            assert pose_bytes(trigrav.initialize_and_refine(observations)) in expected
            batch = trigrav.initialize_and_refine_batch([observations] * 4, num_threads=2)
            assert all(pose_bytes(e) in expected for e in batch)
    finally:
        stop.set()
        writer.join()


class Interrupted(Exception):
    pass


def seconds_to_interrupt(call, delay_s):
    """Runs call() with a SIGALRM after delay_s whose handler raises; returns the seconds from the
    signal to the exception reaching Python (None if call returned first)."""
    fired = {}

    def handler(signum, frame):
        fired["at"] = time.monotonic()
        raise Interrupted()

    previous = signal.signal(signal.SIGALRM, handler)
    signal.setitimer(signal.ITIMER_REAL, delay_s)
    try:
        call()
        return None
    except Interrupted:
        return time.monotonic() - fired["at"]
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(signal.SIGALRM, previous)


# An interrupt must end a call long before the call would have ended: the signal's exception
# arrives within half the time the call still had to run. The latency itself (about one
# solver iteration) is measured by examples/python/measure_interrupt.py, not asserted here.
def test_ctrl_c_ends_a_batch_promptly():
    scenes = [observations_from_numpy(make_scene(seed, num_points=400)) for seed in range(8)]
    start = time.monotonic()
    trigrav.initialize_and_refine_batch(scenes * 2, num_threads=2)
    # Enough copies for about 3 s.
    batch = scenes * max(2, int(3.0 / (time.monotonic() - start) * 2))
    full_s = 3.0
    latency = seconds_to_interrupt(
        lambda: trigrav.initialize_and_refine_batch(batch, num_threads=2), 0.3)
    assert latency is not None and latency < 0.5 * (full_s - 0.3), (latency, full_s)


def test_ctrl_c_ends_a_long_call_in_ransac_and_in_the_refinement():
    observations = observations_from_numpy(make_scene(1, num_points=200000))
    timings = trigrav.initialize_and_refine(observations).timings
    assert timings.ransac_s > 0.5 and timings.refinement_s > 1.0, timings
    # Within RANSAC, within the refinement; then RANSAC alone.
    for delay_s, call_s, call in (
            (0.1, timings.total_s, lambda: trigrav.initialize_and_refine(observations)),
            (timings.ransac_s + 0.2, timings.total_s,
             lambda: trigrav.initialize_and_refine(observations)),
            (0.1, timings.ransac_s, lambda: trigrav.estimate_three_view_pose_robust(observations))):
        latency = seconds_to_interrupt(call, delay_s)
        assert latency is not None and latency < 0.5 * (call_s - delay_s), (delay_s, latency)
    # The module answers normally after an interrupt.
    assert trigrav.initialize_and_refine(observations_from_numpy(make_scene(3))).success


def test_a_batch_names_every_bad_item_or_returns_each_error_in_place(scene, observations):
    bad = observations_from_numpy(scene)
    bad.gravity_in_cam = np.zeros((3, 3))
    batch = [observations, bad, observations, bad]
    with pytest.raises(ValueError, match=r"batch\[1\]: .*gravity.*; batch\[3\]: .*gravity"):
        trigrav.initialize_and_refine_batch(batch, num_threads=2)
    results = trigrav.initialize_and_refine_batch(batch, num_threads=2, return_exceptions=True)
    assert [type(r).__name__ for r in results] == [
        "ThreeViewEstimate", "ValueError", "ThreeViewEstimate", "ValueError"]
    assert results[0].success and "gravity" in str(results[1])
    assert pose_bytes(results[2]) == pose_bytes(trigrav.initialize_and_refine(observations))


CAPPED_BATCH = textwrap.dedent("""
    import resource, sys, warnings
    sys.path.insert(0, {tests!r})
    import trigrav
    from conftest import make_scene, observations_from_numpy
    batch = [observations_from_numpy(make_scene(seed, num_points=100)) for seed in range(12)]
    serial = [trigrav.initialize_and_refine(o) for o in batch]
    with open("/proc/self/status") as status:
        vm = next(int(line.split()[1]) for line in status if line.startswith("VmSize:")) * 1024
    # Room for about two more 8 MB thread stacks: most of the 16 threads cannot be created.
    resource.setrlimit(resource.RLIMIT_AS, (vm + (24 << 20), resource.RLIM_INFINITY))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        estimates = trigrav.initialize_and_refine_batch(batch, num_threads=16)
    resource.setrlimit(resource.RLIMIT_AS, (resource.RLIM_INFINITY, resource.RLIM_INFINITY))
    same = all(a.refined.cam2_from_cam1.R.tobytes() == b.refined.cam2_from_cam1.R.tobytes()
               and a.success == b.success for a, b in zip(estimates, serial))
    print("same" if same else "different", "|", "; ".join(str(w.message) for w in caught))
""")


def test_a_batch_goes_on_when_threads_cannot_be_created():
    tests = os.path.dirname(os.path.abspath(__file__))
    env = dict(os.environ, MALLOC_ARENA_MAX="1", OPENBLAS_NUM_THREADS="1")
    run = subprocess.run([sys.executable, "-c", CAPPED_BATCH.format(tests=tests)], env=env,
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr[-2000:]
    assert run.stdout.startswith("same |"), run.stdout + run.stderr[-2000:]
    assert "could create" in run.stdout and "RuntimeWarning" not in run.stderr, run.stdout


def test_a_masked_array_is_refused_not_silently_unmasked(scene, observations):
    pixels = [np.ma.masked_array(np.array(p), mask=False) for p in scene.pixels]
    pixels[1].mask[0] = True
    with pytest.raises(ValueError, match=r"pixels.*masked array"):
        observations.pixels = pixels
    with pytest.raises(ValueError, match=r"inliers: a masked array"):
        trigrav.refine_three_view_pose(observations, trigrav.initialize_and_refine(observations).refined,
                                       np.ma.masked_array(np.ones(len(observations), bool)))
