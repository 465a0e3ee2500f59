"""A synthetic COLMAP 3.8 database of a driving-like sequence, with its gravity CSV: test and
benchmark input for the triplet pipeline (trigrav itself reads databases and never writes them).

The camera (PINHOLE 500, 500, 320, 240; 640 x 480) moves forward along the world's z axis (1 unit
per frame) with a lateral and vertical wobble and a small yaw and pitch; the world's y axis points
down. Points fill a corridor along the path; each image sees those 4-16 units ahead that project
into it (about 50 with the default density). Keypoints are the projections plus Gaussian noise in
a shuffled order, stored as COLMAP stores them (float32, 6 columns: x, y and an affine shape).
Verified matches join each image to the next `overlap` images through their common points, with a
fraction of them replaced by wrong matches. Gravity is the world's +y seen from each camera.

    python3 -m trigrav_pipeline.synthetic --database_path db.db --gravity_csv g.csv --num_images 8
"""

import argparse
import math
import os
import sqlite3

import numpy as np

import trigrav

SCHEMA = """
CREATE TABLE cameras (camera_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL,
  model INTEGER NOT NULL, width INTEGER NOT NULL, height INTEGER NOT NULL, params BLOB,
  prior_focal_length INTEGER NOT NULL);
CREATE TABLE images (image_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL,
  name TEXT NOT NULL UNIQUE, camera_id INTEGER NOT NULL, prior_qw REAL, prior_qx REAL,
  prior_qy REAL, prior_qz REAL, prior_tx REAL, prior_ty REAL, prior_tz REAL,
  CONSTRAINT image_id_check CHECK(image_id >= 0 and image_id < 2147483647),
  FOREIGN KEY(camera_id) REFERENCES cameras(camera_id));
CREATE UNIQUE INDEX index_name ON images(name);
CREATE TABLE keypoints (image_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL,
  cols INTEGER NOT NULL, data BLOB,
  FOREIGN KEY(image_id) REFERENCES images(image_id) ON DELETE CASCADE);
CREATE TABLE descriptors (image_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL,
  cols INTEGER NOT NULL, data BLOB,
  FOREIGN KEY(image_id) REFERENCES images(image_id) ON DELETE CASCADE);
CREATE TABLE matches (pair_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL,
  cols INTEGER NOT NULL, data BLOB);
CREATE TABLE two_view_geometries (pair_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL,
  cols INTEGER NOT NULL, data BLOB, config INTEGER NOT NULL, F BLOB, E BLOB, H BLOB, qvec BLOB,
  tvec BLOB);
"""

WIDTH, HEIGHT = 640, 480
PINHOLE = (500.0, 500.0, 320.0, 240.0)
PINHOLE_MODEL_ID = 1  # COLMAP's id of PINHOLE


def rotation(yaw, pitch):
    """cam_from_world rotation: yaw about y (down), then pitch about x."""
    cy, sy, cp, sp = math.cos(yaw), math.sin(yaw), math.cos(pitch), math.sin(pitch)
    r_yaw = np.array([[cy, 0, -sy], [0, 1, 0], [sy, 0, cy]])
    r_pitch = np.array([[1, 0, 0], [0, cp, -sp], [0, sp, cp]])
    return r_pitch @ r_yaw


def write_synthetic_database(database_path, gravity_csv, num_images=8, seed=1,
                             points_per_unit=6.0, noise_px=0.5, outlier_ratio=0.05, overlap=3,
                             image_name_format="{:06d}.png"):
    """Writes the database (which must not exist) and the gravity CSV; returns the number of
    images. The same arguments give the same files."""
    if os.path.exists(database_path):
        raise FileExistsError(f"{database_path} exists")
    rng = np.random.default_rng(seed)
    fx, fy, cx, cy = PINHOLE
    length = num_images + 20.0
    num_points = int(points_per_unit * length)
    points = np.column_stack([rng.uniform(-6, 6, num_points), rng.uniform(-3, 2, num_points),
                              rng.uniform(0, length, num_points)])
    points = points[np.argsort(points[:, 2])]
    frames = np.arange(num_images, dtype=float)
    centers = np.column_stack([0.3 * np.sin(frames / 5), 0.05 * np.sin(frames / 3), frames])
    yaws = 0.02 * np.sin(frames / 7)
    pitches = 0.01 * np.cos(frames / 4)

    connection = sqlite3.connect(database_path)
    connection.executescript(SCHEMA)
    params = np.array(PINHOLE, dtype=np.float64).tobytes()
    connection.execute("INSERT INTO cameras VALUES (1, ?, ?, ?, ?, 1)",
                       (PINHOLE_MODEL_ID, WIDTH, HEIGHT, params))
    visible = []  # per image: point indices in keypoint order
    gravity_lines = ["image_name,gravity_x,gravity_y,gravity_z"]
    image_rows, keypoint_rows = [], []
    for k in range(num_images):
        R = rotation(yaws[k], pitches[k])
        lo, hi = np.searchsorted(points[:, 2], [centers[k, 2] + 4, centers[k, 2] + 16])
        index = np.arange(lo, hi)
        in_cam = (points[index] - centers[k]) @ R.T
        u = fx * in_cam[:, 0] / in_cam[:, 2] + cx
        v = fy * in_cam[:, 1] / in_cam[:, 2] + cy
        inside = (in_cam[:, 2] > 1) & (u > 1) & (u < WIDTH - 1) & (v > 1) & (v < HEIGHT - 1)
        order = rng.permutation(np.flatnonzero(inside))
        index, u, v = index[order], u[order], v[order]
        visible.append(index)
        pixels = np.column_stack([u, v]) + rng.normal(0, noise_px, (len(index), 2))
        keypoints = np.zeros((len(index), 6), dtype=np.float32)
        keypoints[:, :2] = pixels
        keypoints[:, 2] = keypoints[:, 5] = 2.0  # an isotropic affine shape, as SIFT's
        name = image_name_format.format(k)
        image_rows.append((k + 1, name))
        keypoint_rows.append((k + 1, len(index), 6, keypoints.tobytes()))
        g = R @ np.array([0.0, 1.0, 0.0])
        gravity_lines.append(f"{name},{g[0]:.17g},{g[1]:.17g},{g[2]:.17g}")
    connection.executemany("INSERT INTO images (image_id, name, camera_id) VALUES (?, ?, 1)",
                           image_rows)
    connection.executemany("INSERT INTO keypoints VALUES (?, ?, ?, ?)", keypoint_rows)
    geometry_rows = []
    for k in range(num_images):
        for d in range(1, overlap + 1):
            if k + d >= num_images:
                break
            _, in_k, in_l = np.intersect1d(visible[k], visible[k + d], assume_unique=True,
                                           return_indices=True)
            matches = np.column_stack([in_k, in_l]).astype(np.uint32)
            wrong = rng.random(len(matches)) < outlier_ratio
            matches[wrong, 1] = rng.integers(0, len(visible[k + d]), int(wrong.sum()))
            pair = trigrav.pair_id(k + 1, k + d + 1)
            geometry_rows.append((pair, len(matches), 2, matches.tobytes(), 2))
    connection.executemany(
        "INSERT INTO two_view_geometries (pair_id, rows, cols, data, config) VALUES (?, ?, ?, ?, ?)",
        geometry_rows)
    connection.commit()
    connection.close()
    with open(gravity_csv, "w") as f:
        f.write("\n".join(gravity_lines) + "\n")
    return num_images


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--database_path", required=True)
    parser.add_argument("--gravity_csv", required=True)
    parser.add_argument("--num_images", type=int, default=8)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    write_synthetic_database(args.database_path, args.gravity_csv, args.num_images, args.seed)


if __name__ == "__main__":
    main()
