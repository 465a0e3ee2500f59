#!/usr/bin/env python3
"""trigrav on one KITTI triplet from Python, next to OpenCV's findEssentialMat (USAC_MAGSAC).

Detects SIFT in three frames of a KITTI odometry sequence (OpenCV), matches the pairs (1,2) and
(2,3) (Lowe's ratio test and a mutual check), chains the matches into triplets, and calls
trigrav.initialize_and_refine with each frame's gravity from the ground truth (the world y axis in
the camera, as the paper does on KITTI). Prints the errors of views 2 and 3 against the ground
truth next to OpenCV's five-point USAC_MAGSAC on the pairs (1,2) and (1,3) of the same tracks, and
saves a figure of the three frames with the inlier and outlier tracks.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/kitti_triplet.py \\
        --kitti_dir ../shared/data/kitti --sequence 00 --frames 100 101 102 --figure triplet.png

Exits with status 77 (a skip for ctest) when the KITTI folder is missing.
"""

import argparse
import os
import sys

import numpy as np

import trigrav

SKIP = 77


def read_camera(calib_path):
    """The rectified left camera from row P0 = K [I | 0] of calib.txt."""
    with open(calib_path) as f:
        for line in f:
            if line.startswith("P0:"):
                P = np.array(line.split()[1:], dtype=float).reshape(3, 4)
                return P[0, 0], P[1, 1], P[0, 2], P[1, 2]
    raise ValueError(f"{calib_path} has no row P0")


def read_world_from_cam(poses_path, frames):
    """4 x 4 world_from_cam of the frames (poses/XX.txt: one 3 x 4 [R | t] per line)."""
    lines = open(poses_path).read().split("\n")
    poses = []
    for frame in frames:
        pose = np.eye(4)
        pose[:3] = np.array(lines[frame].split(), dtype=float).reshape(3, 4)
        poses.append(pose)
    return poses


def sift(image, max_features):
    import cv2
    keypoints, descriptors = cv2.SIFT_create(nfeatures=max_features).detectAndCompute(image, None)
    return np.array([k.pt for k in keypoints], dtype=np.float64), descriptors


def match(descriptors_a, descriptors_b, ratio):
    """a -> b matches passing Lowe's ratio test in both directions and the mutual check."""
    import cv2
    matcher = cv2.BFMatcher(cv2.NORM_L2)

    def one_way(query, train):
        best = {}
        for pair in matcher.knnMatch(query, train, k=2):
            if len(pair) == 2 and pair[0].distance < ratio * pair[1].distance:
                best[pair[0].queryIdx] = pair[0].trainIdx
        return best

    forward, backward = one_way(descriptors_a, descriptors_b), one_way(descriptors_b, descriptors_a)
    return {a: b for a, b in forward.items() if backward.get(b) == a}


def opencv_pair(pixels_1, pixels_k, K, threshold_px):
    """cam_k_from_cam1 (R, t) of OpenCV's five-point USAC_MAGSAC and recoverPose, and its inliers."""
    import cv2
    E, mask = cv2.findEssentialMat(pixels_1, pixels_k, K, method=cv2.USAC_MAGSAC, prob=0.9999,
                                   threshold=threshold_px)
    if E is None or E.shape != (3, 3):
        return None
    _, R, t, mask = cv2.recoverPose(E, pixels_1, pixels_k, K, mask=mask)
    return R, t.ravel(), mask.ravel() > 0


def save_figure(path, images, pixels, inliers, frames):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure, axes = plt.subplots(3, 1, figsize=(12, 11))
    for k, axis in enumerate(axes):
        axis.imshow(images[k], cmap="gray")
        for mask, color, label in ((~inliers, "red", "outlier"), (inliers, "lime", "inlier")):
            # Each track through its three pixels, and the frame's own pixel marked.
            tracks = np.stack([p[mask] for p in pixels], axis=1)  # N x 3 x 2
            for track in tracks:
                axis.plot(track[:, 0], track[:, 1], color=color, linewidth=0.6)
            axis.scatter(pixels[k][mask, 0], pixels[k][mask, 1], s=4, color=color,
                         label=f"{label} ({mask.sum()})")
        axis.set_title(f"frame {frames[k]}")
        axis.set_axis_off()
    axes[0].legend(loc="upper right")
    figure.tight_layout()
    figure.savefig(path, dpi=90)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--kitti_dir", required=True)
    parser.add_argument("--sequence", default="00")
    parser.add_argument("--frames", type=int, nargs=3, default=[100, 101, 102])
    parser.add_argument("--threshold_px", type=float, default=1.5,
                        help="RANSAC threshold of trigrav and OpenCV (px)")
    parser.add_argument("--max_features", type=int, default=4000)
    parser.add_argument("--ratio", type=float, default=0.8)
    parser.add_argument("--figure", default="kitti_triplet.png")
    args = parser.parse_args()

    sequence_dir = os.path.join(args.kitti_dir, "sequences", args.sequence)
    poses_path = os.path.join(args.kitti_dir, "poses", args.sequence + ".txt")
    if not os.path.isdir(sequence_dir) or not os.path.isfile(poses_path):
        print(f"skipped: no KITTI sequence {args.sequence} in {args.kitti_dir}")
        return SKIP
    import cv2

    frames = args.frames
    fx, fy, cx, cy = read_camera(os.path.join(sequence_dir, "calib.txt"))
    K = np.array([[fx, 0, cx], [0, fy, cy], [0, 0, 1]])
    images = [cv2.imread(os.path.join(sequence_dir, "image_0", f"{f:06d}.png"),
                         cv2.IMREAD_GRAYSCALE) for f in frames]
    if any(image is None for image in images):
        raise SystemExit(f"cannot read the images of frames {frames} in {sequence_dir}")
    features = [sift(image, args.max_features) for image in images]
    matches_12 = match(features[0][1], features[1][1], args.ratio)
    matches_23 = match(features[1][1], features[2][1], args.ratio)
    tracks = [(i1, i2, matches_23[i2]) for i1, i2 in sorted(matches_12.items())
              if i2 in matches_23]
    # Pixels as OpenCV gives them, with KITTI's P0, for trigrav and OpenCV alike (as the C++ tool
    # examples/kitti does); COLMAP's half-pixel convention would move cx, cy by 0.5 px.
    pixels = [np.array([features[k][0][track[k]] for track in tracks]) for k in range(3)]
    print(f"KITTI {args.sequence}, frames {frames}: {len(features[0][0])}, "
          f"{len(features[1][0])}, {len(features[2][0])} SIFT features, {len(tracks)} triplets")

    world_from_cam = read_world_from_cam(poses_path, frames)
    cam_from_world = [np.linalg.inv(T) for T in world_from_cam]
    # Gravity (down) in camera k: the world y axis of KITTI's first camera frame.
    gravity = np.array([T[:3, :3] @ [0.0, 1.0, 0.0] for T in cam_from_world])
    truth = [cam_from_world[k] @ world_from_cam[0] for k in (1, 2)]
    ground_truth = trigrav.ThreeViewPose(trigrav.CameraPose(truth[0][:3, :3], truth[0][:3, 3]),
                                         trigrav.CameraPose(truth[1][:3, :3], truth[1][:3, 3]))

    observations = trigrav.ThreeViewObservations(
        pixels=pixels, cameras=trigrav.Camera.pinhole(fx, fy, cx, cy), gravity_in_cam=gravity)
    options = trigrav.InitializeAndRefineOptions(
        robust=trigrav.RobustThreeViewOptions(
            ransac=trigrav.RansacOptions(max_error=args.threshold_px, seed=1)),
        bundle_adjustment=trigrav.ThreeViewBundleAdjustmentOptions(loss_scale_px=1.0))
    estimate = trigrav.initialize_and_refine(observations, options)
    if not estimate.success:
        raise SystemExit(f"trigrav: no pose: {estimate.message}")

    print(f"\n{'method':<34}{'view':>5}{'rotation (deg)':>16}{'translation (deg)':>19}"
          f"{'inliers':>9}")
    errors = trigrav.compute_three_view_pose_errors(ground_truth, estimate.robust.pose)
    refined = trigrav.compute_three_view_pose_errors(ground_truth, estimate.refined)
    rows = [("trigrav 3pt RANSAC", errors, estimate.robust.ransac.num_inliers),
            ("trigrav initialize_and_refine", refined, estimate.num_inliers)]
    for name, e, inliers in rows:
        for view in (0, 1):
            print(f"{name:<34}{view + 2:>5}{e.rotation_deg[view]:>16.3f}"
                  f"{e.translation_deg[view]:>19.3f}{inliers:>9}")
    for view, k in ((0, 1), (1, 2)):
        result = opencv_pair(pixels[0], pixels[k], K, args.threshold_px)
        if result is None:
            print(f"{'OpenCV USAC_MAGSAC (1,%d)' % (k + 1):<34}{k + 1:>5}  no pose")
            continue
        R, t, inliers = result
        R_true, t_true = truth[view][:3, :3], truth[view][:3, 3]
        print(f"{'OpenCV USAC_MAGSAC (1,%d)' % (k + 1):<34}{k + 1:>5}"
              f"{trigrav.rotation_error_deg(R_true, R):>16.3f}"
              f"{trigrav.direction_error_deg(-R_true.T @ t_true, -R.T @ t):>19.3f}"
              f"{inliers.sum():>9}")
    print(f"relative scale |log(s / s_true)|: trigrav {refined.relative_scale:.4f} "
          f"(OpenCV's pairs have no common scale)")
    print(f"trigrav: {1e3 * estimate.timings.total_s:.1f} ms "
          f"(RANSAC {1e3 * estimate.timings.ransac_s:.1f} ms)")

    save_figure(args.figure, images, pixels, estimate.inliers, frames)
    print(f"figure: {args.figure}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
