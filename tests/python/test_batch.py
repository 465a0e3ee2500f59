"""initialize_and_refine_batch equals the serial calls, for any number of threads."""

import numpy as np

import trigrav
from conftest import make_scene, observations_from_numpy


def assert_same_estimate(a, b):
    assert a.success == b.success and a.message == b.message
    assert a.num_inliers == b.num_inliers
    np.testing.assert_array_equal(a.inliers, b.inliers)
    for pose_a, pose_b in ((a.refined, b.refined), (a.robust.pose, b.robust.pose)):
        for cam_a, cam_b in ((pose_a.cam2_from_cam1, pose_b.cam2_from_cam1),
                             (pose_a.cam3_from_cam1, pose_b.cam3_from_cam1)):
            assert cam_a.R.tobytes() == cam_b.R.tobytes()
            assert cam_a.t.tobytes() == cam_b.t.tobytes()


def test_batch_equals_serial_runs():
    batch = [observations_from_numpy(make_scene(seed, num_points=80)) for seed in range(7)]
    # One scene that fails (pure outliers): failures come back in place too.
    batch.append(observations_from_numpy(make_scene(99, num_points=40, outlier_ratio=1.0)))
    options = trigrav.InitializeAndRefineOptions(
        robust=trigrav.RobustThreeViewOptions(ransac=trigrav.RansacOptions(seed=4)))
    serial = [trigrav.initialize_and_refine(observations, options) for observations in batch]
    assert sum(estimate.success for estimate in serial) == 7 and not serial[-1].success
    for threads in (1, 2, 3, 0):
        estimates = trigrav.initialize_and_refine_batch(batch, options, num_threads=threads)
        assert len(estimates) == len(batch)
        for estimate, reference in zip(estimates, serial):
            assert_same_estimate(estimate, reference)
    assert trigrav.initialize_and_refine_batch([], options, num_threads=2) == []


def test_calls_release_the_gil():
    """A Python thread runs while another is inside a call. With a switch interval of 100 s the
    interpreter never takes the GIL from a thread, so the main thread, woken by the worker just
    before its call, can only run during the call if the call released the GIL."""
    import sys
    import threading

    batch = [observations_from_numpy(make_scene(seed, num_points=300)) for seed in range(8)]
    calls = [lambda: trigrav.initialize_and_refine_batch(batch, num_threads=1),
             lambda: [trigrav.initialize_and_refine(o) for o in batch][-1]]
    interval = sys.getswitchinterval()
    sys.setswitchinterval(100.0)
    try:
        for call in calls:
            started, state = threading.Event(), {"finished": False}

            def work():
                started.set()
                call()
                state["finished"] = True

            worker = threading.Thread(target=work)
            worker.start()
            started.wait()
            ran_during_call = not state["finished"]
            worker.join()
            assert ran_during_call
    finally:
        sys.setswitchinterval(interval)
