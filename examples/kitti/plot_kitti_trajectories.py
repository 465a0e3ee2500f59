#!/usr/bin/python3
"""Chained KITTI trajectories of kitti_triplets, one panel per method and stage, each camera centre
coloured by its position error after alignment (ATE) over the ground truth (grey), and below them
the position error of every selected trajectory against the frame.

  /usr/bin/python3 examples/kitti/plot_kitti_trajectories.py OUT/trajectories.csv kitti.png \
      [--select 3pt:raw,3pt:gravity-prior,5pt:raw] [--title "KITTI 00, frames 0-299"]

Top view: world x (right) against world z (forward) of the first frame's camera, in metres.
Needs Debian's python3-matplotlib (run with /usr/bin/python3).
"""

import argparse
import collections
import csv
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_trajectories(path):
    """{(method, stage): {"x": [...], "z": [...], "gt_x": [...], "gt_z": [...], "error": [...]}}"""
    trajectories = collections.OrderedDict()
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            t = trajectories.setdefault(
                (row["method"], row["stage"]), collections.defaultdict(list))
            t["frame"].append(int(row["frame"]))
            for key in ("x", "z", "gt_x", "gt_z"):
                t[key].append(float(row[key]))
            t["error"].append(float(row["error_m"]))
    return trajectories


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", help="trajectories.csv written by kitti_triplets")
    parser.add_argument("png", help="output image")
    parser.add_argument("--select", default="",
                        help="comma-separated method:stage panels (default: all)")
    parser.add_argument("--title", default="", help="figure title")
    args = parser.parse_args()

    trajectories = read_trajectories(args.csv)
    if args.select:
        keys = [tuple(item.split(":", 1)) for item in args.select.split(",")]
        missing = [k for k in keys if k not in trajectories]
        if missing:
            parser.error("not in %s: %s" % (args.csv, ", ".join(":".join(k) for k in missing)))
    else:
        keys = list(trajectories)
    if not keys:
        parser.error("%s has no trajectories" % args.csv)

    max_error = max(max(trajectories[k]["error"]) for k in keys)
    columns = min(4, len(keys))
    rows = int(math.ceil(len(keys) / columns))
    fig = plt.figure(figsize=(4.0 * columns + 1.0, 4.2 * rows + 3.0))
    grid = fig.add_gridspec(rows + 1, columns, height_ratios=[4.2] * rows + [2.6], hspace=0.35)
    for i, key in enumerate(keys):
        ax = fig.add_subplot(grid[i // columns, i % columns])
        t = trajectories[key]
        ate = math.sqrt(sum(e * e for e in t["error"]) / len(t["error"]))
        ax.plot(t["gt_x"], t["gt_z"], color="0.75", linewidth=5, label="ground truth")
        points = ax.scatter(t["x"], t["z"], c=t["error"], cmap="plasma", vmin=0.0,
                            vmax=max_error, s=5, zorder=3, label="estimate")
        ax.set_title("%s, %s: ATE %.2f m" % (key[0], key[1], ate), fontsize=10)
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("z (m)")
        ax.grid(True, linewidth=0.3)
        if i == 0:
            ax.legend(loc="best", fontsize=8)
    fig.colorbar(points, ax=fig.axes, shrink=0.6, label="position error after alignment (m)")
    errors = fig.add_subplot(grid[rows, :])
    for key in keys:
        t = trajectories[key]
        errors.plot(t["frame"], t["error"], linewidth=1.2, label="%s, %s" % key)
    errors.set_xlabel("frame")
    errors.set_ylabel("position error (m)")
    errors.grid(True, linewidth=0.3)
    errors.legend(loc="upper left", fontsize=8, ncol=min(4, len(keys)))
    if args.title:
        fig.suptitle(args.title)
    fig.savefig(args.png, dpi=110)


if __name__ == "__main__":
    main()
