"""Reading part of a COLMAP database without loading the rest: the verified matches of chosen
image pairs, and a check of the whole database's row shapes that reads no keypoint or match data.

trigrav's C++ reader (trigrav.Database, trigrav/colmap/database.h) reads every verified pair at
once (Database.read_two_view_geometries); a pipeline worker needs only the pairs of its own
triplets, so the rows of those pairs are selected here with the same checks as the C++ reader
(pair ids of two distinct images of the database, 2 columns, a blob of rows x 2 uint32, match
indices below each image's keypoint count) and returned as trigrav.TwoViewGeometry objects, which
trigrav.MatchGraph takes. tests/python/test_dask_pipeline.py checks that the result equals the C++
reader's for every pair. (A C++ Database::ReadTwoViewGeometries(pairs) would replace this file.)
"""

import sqlite3

import numpy as np

import trigrav

MAX_NUM_IMAGES = 2147483647  # COLMAP's kMaxNumImages: pair_id = MAX_NUM_IMAGES * id1 + id2


def connect_read_only(path):
    """An sqlite3 connection that cannot write (URI mode=ro), as the C++ reader opens it."""
    return sqlite3.connect(f"file:{path}?mode=ro", uri=True, check_same_thread=False)


def read_two_view_geometries(path, pairs):
    """trigrav.TwoViewGeometry of each pair (image ids, any order) that has verified matches, in
    increasing pair id order; pairs without matches are left out, as the C++ reader leaves them.
    ValueError naming the database and pair for a malformed row."""
    pair_ids = sorted({trigrav.pair_id(int(a), int(b)) for a, b in pairs})
    geometries = []
    with connect_read_only(path) as connection:
        image_ids = {int(a) for a, b in pairs} | {int(b) for a, b in pairs}
        num_keypoints = {}
        for image_id in image_ids:
            row = connection.execute("SELECT rows FROM keypoints WHERE image_id = ?",
                                     (image_id,)).fetchone()
            exists = connection.execute("SELECT 1 FROM images WHERE image_id = ?",
                                        (image_id,)).fetchone()
            if exists is not None:
                num_keypoints[image_id] = int(row[0]) if row is not None else 0
        for start in range(0, len(pair_ids), 500):
            chunk = pair_ids[start:start + 500]
            rows = connection.execute(
                "SELECT pair_id, rows, cols, data, config FROM two_view_geometries "
                f"WHERE rows > 0 AND pair_id IN ({','.join('?' * len(chunk))}) ORDER BY pair_id",
                chunk).fetchall()
            for pair_id, num_rows, cols, data, config in rows:
                id1, id2 = pair_id // MAX_NUM_IMAGES, pair_id % MAX_NUM_IMAGES
                where = f"{path}: two_view_geometry of images {id1} and {id2}"
                if id1 >= id2 or id1 not in num_keypoints or id2 not in num_keypoints:
                    raise ValueError(f"{where}: not a pair of distinct images of the database")
                if cols != 2:
                    raise ValueError(f"{where}: {cols} columns (2 expected)")
                if data is None or len(data) != 8 * num_rows:
                    raise ValueError(f"{where}: a blob of {0 if data is None else len(data)} "
                                     f"bytes, {8 * num_rows} expected")
                matches = np.frombuffer(data, dtype=np.uint32).reshape(num_rows, 2)
                bad = np.flatnonzero((matches[:, 0] >= num_keypoints[id1]) |
                                     (matches[:, 1] >= num_keypoints[id2]))
                if bad.size:
                    r = int(bad[0])
                    raise ValueError(
                        f"{where}: match {r} ({matches[r, 0]}, {matches[r, 1]}) beyond the "
                        f"keypoints ({num_keypoints[id1]}, {num_keypoints[id2]})")
                geometries.append(trigrav.TwoViewGeometry(int(id1), int(id2), int(config), matches))
    return geometries


def check_database_rows(path):
    """Checks the shapes of every keypoint and verified-match row from their metadata (rows,
    cols, blob length; no blob is read), so that a malformed database fails before any work is
    scheduled. Raises ValueError naming the database and the first bad row."""
    with connect_read_only(path) as connection:
        image_ids = {r[0] for r in connection.execute("SELECT image_id FROM images")}
        for image_id, rows, cols, size in connection.execute(
                "SELECT image_id, rows, cols, length(data) FROM keypoints"):
            where = f"{path}: keypoints of image {image_id}"
            if rows < 0 or cols not in (2, 4, 6):
                raise ValueError(f"{where}: {rows} x {cols} (2, 4 or 6 columns expected)")
            if (size or 0) != 4 * rows * cols:
                raise ValueError(f"{where}: a blob of {size or 0} bytes, {4 * rows * cols} "
                                 "expected")
        for pair_id, rows, cols, size in connection.execute(
                "SELECT pair_id, rows, cols, length(data) FROM two_view_geometries WHERE rows > 0"):
            id1, id2 = pair_id // MAX_NUM_IMAGES, pair_id % MAX_NUM_IMAGES
            where = f"{path}: two_view_geometry of images {id1} and {id2}"
            if pair_id < 0 or id1 >= id2 or id1 not in image_ids or id2 not in image_ids:
                raise ValueError(f"{where}: not a pair of distinct images of the database")
            if cols != 2:
                raise ValueError(f"{where}: {cols} columns (2 expected)")
            if (size or 0) != 8 * rows:
                raise ValueError(f"{where}: a blob of {size or 0} bytes, {8 * rows} expected")
