"""A COLMAP model against KITTI ground truth: Sim(3) alignment, absolute and relative errors.

Ground truth: poses/<seq>.txt, line k = frame k, row-major 3x4 [R | t] = world_from_cam of frame k.
Model: cam_from_world (R, t) per image; the frame of an image is the number in its file name.
"""

import os

import numpy as np


def read_kitti_poses(path):
    """world_from_cam rotations (N,3,3) and camera centres (N,3) of every frame."""
    rows = np.loadtxt(path, ndmin=2).reshape(-1, 3, 4)
    return rows[:, :, :3], rows[:, :, 3]


def frame_of(image_name):
    return int(os.path.splitext(os.path.basename(image_name))[0])


def umeyama_sim3(source, target):
    """(s, R, t) minimising sum ||target_i - (s R source_i + t)||^2 (Umeyama, PAMI 1991)."""
    mu_s, mu_t = source.mean(axis=0), target.mean(axis=0)
    xs, xt = source - mu_s, target - mu_t
    u, d, vt = np.linalg.svd(xt.T @ xs / len(source))
    sign = np.eye(3)
    if np.linalg.det(u) * np.linalg.det(vt) < 0:
        sign[2, 2] = -1
    rotation = u @ sign @ vt
    scale = np.trace(np.diag(d) @ sign) / (xs ** 2).sum(axis=1).mean()
    return scale, rotation, mu_t - scale * rotation @ mu_s


def rotation_alignment(target_rotations, source_rotations):
    """R minimising sum ||T_k - R S_k||_F^2 over rotations: the projection onto SO(3) of
    sum_k T_k S_k^T (the chordal L2 mean of T_k S_k^T; Hartley et al., IJCV 2013, Sec. 5.3)."""
    u, _, vt = np.linalg.svd(np.einsum("kij,klj->il", target_rotations, source_rotations))
    sign = np.diag([1.0, 1.0, np.linalg.det(u @ vt)])
    return u @ sign @ vt


def angle_deg(rotation):
    """Angle of a rotation matrix in degrees: atan2(sin, cos) with 2 sin = |vee(R - R^T)| and
    2 cos = trace(R) - 1, accurate at small angles (unlike arccos of the cosine)."""
    skew = rotation - rotation.T
    sine = 0.5 * np.linalg.norm([skew[2, 1], skew[0, 2], skew[1, 0]])
    return float(np.degrees(np.arctan2(sine, 0.5 * (np.trace(rotation) - 1.0))))


def direction_angle_deg(a, b):
    na, nb = np.linalg.norm(a), np.linalg.norm(b)
    if na == 0 or nb == 0:
        return float("nan")
    return float(np.degrees(np.arccos(np.clip(a @ b / (na * nb), -1.0, 1.0))))


def _median(values):
    return float(np.median(values)) if len(values) else float("nan")


def _mean(values):
    return float(np.mean(values)) if len(values) else float("nan")


def evaluate(model, gt_rotations, gt_centres):
    """Errors of `model` (colmap_model.Model) against the ground truth, as a dict.

    - Sim(3) (s, R_a, t_a) from the camera centres c_k = -R_k^T t_k to the true centres (Umeyama);
      ATE = RMSE of |C_k - (s R_a c_k + t_a)|.
    - absolute rotation error: angle of  R_gt,k^T R_o R_k^T  (R_k^T = world_from_cam), R_o the
      rotation that best aligns the orientations (rotation_alignment). Not the R_a of the centres:
      camera centres on a straight drive lie near a line and leave R_a's roll about it free
      (`centre_spread`, the ratio of the second to the first singular value of the centred
      positions, is near 0 then), which would count as rotation error.
    - relative pose of consecutive registered frames k, k+1: rotation error angle of
      R_rel^T R_rel,gt, and the angle between the translation directions of cam_{k+1}_from_cam_k
      (scale-free; needs no alignment).
    """
    frames, rotations, centres, translations = [], [], [], []
    for name, (r, t) in model.images.items():
        frame = frame_of(name)
        if frame >= len(gt_centres):
            raise ValueError("%s: frame %d beyond the ground truth's %d poses"
                             % (name, frame, len(gt_centres)))
        frames.append(frame)
        rotations.append(r)
        translations.append(t)
        centres.append(-r.T @ t)
    order = np.argsort(frames)
    frames = np.array(frames)[order]
    rotations = np.array(rotations)[order]
    translations = np.array(translations)[order]
    centres = np.array(centres)[order]
    result = {"registered": int(len(frames)), "num_points": int(model.num_points),
              "mean_reprojection_error_px": model.mean_reprojection_error}

    rel_rotation, rel_direction = [], []
    index = {f: i for i, f in enumerate(frames)}
    for i, f in enumerate(frames):
        j = index.get(f + 1)
        if j is None:
            continue
        r_rel = rotations[j] @ rotations[i].T  # cam_{k+1}_from_cam_k
        t_rel = translations[j] - r_rel @ translations[i]
        g0, g1 = gt_rotations[f], gt_rotations[f + 1]
        r_rel_gt = g1.T @ g0
        t_rel_gt = g1.T @ (gt_centres[f] - gt_centres[f + 1])
        rel_rotation.append(angle_deg(r_rel.T @ r_rel_gt))
        rel_direction.append(direction_angle_deg(t_rel, t_rel_gt))
    result.update({"rpe_pairs": len(rel_rotation),
                   "rpe_rotation_median_deg": _median(rel_rotation),
                   "rpe_translation_direction_median_deg": _median(rel_direction)})

    if len(frames) < 3:
        return result
    true_centres = gt_centres[frames]
    scale, r_align, t_align = umeyama_sim3(centres, true_centres)
    aligned = scale * centres @ r_align.T + t_align
    position_errors = np.linalg.norm(aligned - true_centres, axis=1)
    r_orient = rotation_alignment(gt_rotations[frames], rotations.transpose(0, 2, 1))
    rotation_errors = [angle_deg(gt_rotations[f].T @ r_orient @ r.T)
                       for f, r in zip(frames, rotations)]
    singular = np.linalg.svd(centres - centres.mean(axis=0), compute_uv=False)
    result.update({
        "ate_rmse_m": float(np.sqrt(np.mean(position_errors ** 2))),
        "rotation_median_deg": _median(rotation_errors),
        "rotation_mean_deg": _mean(rotation_errors),
        "centre_spread": float(singular[1] / singular[0]) if singular[0] > 0 else 0.0,
        "trajectory": {"frame": frames.tolist(), "x": aligned[:, 0].tolist(),
                       "z": aligned[:, 2].tolist(), "error_m": position_errors.tolist()},
    })
    return result
