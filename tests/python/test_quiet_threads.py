"""num_threads above the core count prints nothing and changes nothing.

Ceres 2.1 bounds num_threads to the core count with a glog warning on stderr on every solve; the
library hands Ceres the bounded count (ba/src/shared_solver_options.h). A child process runs the
calls so that output at the file-descriptor level (glog writes there, not to sys.stderr) is caught.
"""

import os
import subprocess
import sys

CHILD = """
import sys
import numpy as np
import trigrav

cores, many = int(sys.argv[1]), int(sys.argv[2])
scene = trigrav.generate_synthetic_scene(trigrav.SyntheticSceneOptions(num_points=100), 3)
observations = trigrav.to_observations(scene)
Engine = trigrav.ThreeViewBundleAdjustmentOptions.Engine
for engine in (Engine.CERES, Engine.CERES_POINTS_ELIMINATED):
    poses = []
    for num_threads in (cores, many):
        options = trigrav.ThreeViewBundleAdjustmentOptions(engine=engine, num_threads=num_threads)
        refinement = trigrav.refine_three_view_pose(observations, scene.ground_truth,
                                                    scene.is_inlier, options)
        assert refinement.summary.success, refinement.summary.message
        poses.append(refinement.pose)
    for view in ("cam2_from_cam1", "cam3_from_cam1"):
        assert np.array_equal(getattr(poses[0], view).t, getattr(poses[1], view).t), engine
        assert np.array_equal(getattr(poses[0], view).R, getattr(poses[1], view).R), engine
"""


def test_num_threads_above_the_core_count_prints_nothing():
    cores = os.cpu_count() or 1
    many = max(64, 2 * cores)
    child = subprocess.run([sys.executable, "-c", CHILD, str(cores), str(many)],
                           capture_output=True, text=True, timeout=300)
    assert child.returncode == 0, child.stderr
    assert child.stdout == ""
    assert child.stderr == ""
