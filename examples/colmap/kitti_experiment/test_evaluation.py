#!/usr/bin/python3
"""Checks of the evaluation on KITTI-like poses with known errors:
  /usr/bin/python3 -m unittest discover -s examples/colmap/kitti_experiment -p 'test_*.py'
"""

import os
import struct
import sys
import tempfile
import unittest

import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from kitti_experiment import colmap_model, evaluation  # noqa: E402


def rotation_about(axis, angle_deg):
    """Rodrigues' formula."""
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    a = np.radians(angle_deg)
    return np.eye(3) + np.sin(a) * k + (1 - np.cos(a)) * k @ k


def quaternion_of(r):
    """(w, x, y, z) of a rotation matrix with trace > -1."""
    w = np.sqrt(1.0 + np.trace(r)) / 2.0
    return w, (r[2, 1] - r[1, 2]) / (4 * w), (r[0, 2] - r[2, 0]) / (4 * w), \
        (r[1, 0] - r[0, 1]) / (4 * w)


def driving_ground_truth(frames=30):
    """world_from_cam rotations and centres of a car driving forward (+z) while turning."""
    rotations = np.array([rotation_about([0, 1, 0], 1.5 * k) for k in range(frames)])
    centres = np.array([[0.02 * k * k, 0.01 * k, 0.8 * k] for k in range(frames)])
    return rotations, centres


def model_of(gt_rotations, gt_centres, frames, scale, r_sim, t_sim):
    """A COLMAP-convention model (cam_from_world) whose world = the ground truth's mapped by the
    inverse of x -> scale r_sim x + t_sim, so aligning it back is exact."""
    images = {}
    for f in frames:
        r_wc = r_sim.T @ gt_rotations[f]  # world_from_cam in the model's world
        c = r_sim.T @ (gt_centres[f] - t_sim) / scale
        images["%06d.png" % f] = (r_wc.T, -r_wc.T @ c)
    return colmap_model.Model("synthetic", images, 0, float("nan"))


class EvaluationTest(unittest.TestCase):
    def setUp(self):
        self.gt = driving_ground_truth()
        self.similarity = (3.7, rotation_about([0.3, -1.0, 0.5], 40.0), np.array([5.0, -2.0, 1.0]))

    def test_exact_model_after_similarity_has_no_error(self):
        model = model_of(*self.gt, range(30), *self.similarity)
        result = evaluation.evaluate(model, *self.gt)
        self.assertEqual(result["registered"], 30)
        self.assertEqual(result["rpe_pairs"], 29)
        for key in ("ate_rmse_m", "rotation_median_deg", "rotation_mean_deg",
                    "rpe_rotation_median_deg", "rpe_translation_direction_median_deg"):
            self.assertLess(result[key], 1e-6, key)

    def test_known_errors(self):
        # cameras turned by +2 and -2 deg in turn about the axis of the drive's turn (y): the
        # best alignment is the identity (the errors cancel), absolute errors are 2 deg, those
        # of consecutive frames 4 deg; one centre displaced by 1 m in a 30-frame model.
        rotations, centres = self.gt
        turned = np.array([r @ rotation_about([0, 1, 0], 2.0 if k % 2 else -2.0)
                           for k, r in enumerate(rotations)])
        model = model_of(turned, centres, range(30), *self.similarity)
        result = evaluation.evaluate(model, rotations, centres)
        self.assertAlmostEqual(result["rotation_median_deg"], 2.0, places=6)
        self.assertAlmostEqual(result["rotation_mean_deg"], 2.0, places=6)
        self.assertAlmostEqual(result["rpe_rotation_median_deg"], 4.0, places=6)
        self.assertLess(result["ate_rmse_m"], 1e-9)

        moved = centres.copy()
        moved[10] += [1.0, 0.0, 0.0]
        model = model_of(rotations, moved, range(30), *self.similarity)
        result = evaluation.evaluate(model, rotations, centres)
        # least squares spreads the 1 m error: RMSE between 1/sqrt(30) * (1 - 1/30) and 1/sqrt(30)
        self.assertGreater(result["ate_rmse_m"], 0.9 / np.sqrt(30))
        self.assertLess(result["ate_rmse_m"], 1.0 / np.sqrt(30))

    def test_gaps_leave_out_pairs(self):
        model = model_of(*self.gt, [0, 1, 2, 5, 6, 9], *self.similarity)
        result = evaluation.evaluate(model, *self.gt)
        self.assertEqual(result["registered"], 6)
        self.assertEqual(result["rpe_pairs"], 3)

    def test_binary_and_text_models_read_alike(self):
        model = model_of(*self.gt, range(5), *self.similarity)
        with tempfile.TemporaryDirectory() as folder:
            with open(os.path.join(folder, "images.bin"), "wb") as f:
                f.write(struct.pack("<Q", 5))
                for image_id, (name, (r, t)) in enumerate(sorted(model.images.items()), 1):
                    f.write(struct.pack("<I7dI", image_id, *quaternion_of(r), *t, 1))
                    f.write(name.encode() + b"\0" + struct.pack("<Q", 1) +
                            struct.pack("<2dq", 1.0, 2.0, -1))
            with open(os.path.join(folder, "points3D.bin"), "wb") as f:
                f.write(struct.pack("<Q", 2))
                for point_id, error in ((1, 0.5), (2, 1.5)):
                    f.write(struct.pack("<Q3d3BdQ", point_id, 0, 0, 1, 0, 0, 0, error, 1))
                    f.write(struct.pack("<II", 1, 0))
            read = colmap_model.read_model(folder)
            self.assertEqual(colmap_model.sub_models(folder), [folder])
        self.assertEqual(read.num_points, 2)
        self.assertAlmostEqual(read.mean_reprojection_error, 1.0)
        self.assertEqual(sorted(read.images), sorted(model.images))
        for name, (r, t) in model.images.items():
            np.testing.assert_allclose(read.images[name][0], r, atol=1e-12)
            np.testing.assert_allclose(read.images[name][1], t, atol=1e-12)


if __name__ == "__main__":
    unittest.main()
