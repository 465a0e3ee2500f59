"""Reads the images and points of a COLMAP sparse model (binary or text, COLMAP 3.8 layout).

Binary layout (COLMAP's src/base/reconstruction.cc, ReadImagesBinary / ReadPoints3DBinary):
  images.bin:   uint64 count, then per image: uint32 image_id, 4 double qvec (w, x, y, z),
                3 double tvec, uint32 camera_id, name (NUL-terminated), uint64 n2d,
                n2d x (double x, double y, int64 point3D_id)
  points3D.bin: uint64 count, then per point: uint64 id, 3 double xyz, 3 uint8 rgb, double error,
                uint64 track length, length x (uint32 image_id, uint32 point2D_idx)
Poses are cam_from_world: x_cam = R(q) x_world + t.
"""

import os
import struct

import numpy as np


def rotation_from_quaternion(w, x, y, z):
    """Rotation matrix of a unit quaternion (w, x, y, z), normalised first."""
    n = np.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])


class Model:
    """A sparse model: images {name: (R cam_from_world, t)}, point count, mean reprojection error."""

    def __init__(self, path, images, num_points, mean_reprojection_error):
        self.path = path
        self.images = images
        self.num_points = num_points
        self.mean_reprojection_error = mean_reprojection_error


def is_model_dir(path):
    return any(os.path.isfile(os.path.join(path, "images" + ext)) for ext in (".bin", ".txt"))


def _read_images_bin(path):
    images = {}
    with open(path, "rb") as f:
        (count,) = struct.unpack("<Q", f.read(8))
        for _ in range(count):
            values = struct.unpack("<I7dI", f.read(4 + 56 + 4))
            name = b""
            while True:
                c = f.read(1)
                if c in (b"\0", b""):
                    break
                name += c
            (num_points2d,) = struct.unpack("<Q", f.read(8))
            f.seek(24 * num_points2d, os.SEEK_CUR)
            images[name.decode()] = (rotation_from_quaternion(*values[1:5]), np.array(values[5:8]))
    return images


def _read_images_txt(path):
    images = {}
    with open(path) as f:
        lines = [line for line in f if line.strip() and not line.startswith("#")]
    for line in lines[0::2]:  # every image line is followed by its POINTS2D line
        fields = line.split()
        q = [float(v) for v in fields[1:5]]
        t = np.array([float(v) for v in fields[5:8]])
        images[" ".join(fields[9:])] = (rotation_from_quaternion(*q), t)
    return images


def _read_points_bin(path):
    errors = []
    with open(path, "rb") as f:
        (count,) = struct.unpack("<Q", f.read(8))
        for _ in range(count):
            _, _, _, _, _, _, _, error, track_length = struct.unpack("<Q3d3BdQ", f.read(8 + 24 + 3 + 8 + 8))
            f.seek(8 * track_length, os.SEEK_CUR)
            errors.append(error)
    return errors


def _read_points_txt(path):
    with open(path) as f:
        return [float(line.split()[7]) for line in f if line.strip() and not line.startswith("#")]


def read_model(path):
    """The model in folder `path` (images.bin/points3D.bin, or the .txt pair)."""
    if os.path.isfile(os.path.join(path, "images.bin")):
        images = _read_images_bin(os.path.join(path, "images.bin"))
        errors = _read_points_bin(os.path.join(path, "points3D.bin"))
    else:
        images = _read_images_txt(os.path.join(path, "images.txt"))
        errors = _read_points_txt(os.path.join(path, "points3D.txt"))
    mean_error = float(np.mean(errors)) if errors else float("nan")
    return Model(path, images, len(errors), mean_error)


def sub_models(output_path):
    """The model folders the mapper wrote to output_path: output_path itself (mapper continued from
    --input_path writes there) or its numbered sub-folders 0, 1, ... (a fresh mapper run)."""
    if not os.path.isdir(output_path):
        return []
    if is_model_dir(output_path):
        return [output_path]
    numbered = sorted((d for d in os.listdir(output_path) if d.isdigit()), key=int)
    return [os.path.join(output_path, d) for d in numbered
            if is_model_dir(os.path.join(output_path, d))]


def largest_model(output_path):
    """(largest model by registered images or None, number of sub-models)."""
    models = [read_model(p) for p in sub_models(output_path)]
    if not models:
        return None, 0
    return max(models, key=lambda m: len(m.images)), len(models)
