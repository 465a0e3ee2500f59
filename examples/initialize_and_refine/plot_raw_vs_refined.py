#!/usr/bin/python3
"""Plots the CSV of refinement_benchmark: median rotation and translation errors, raw (dashed) vs
refined (solid), against image noise and against IMU noise, per initial solver and rotation model.

    /usr/bin/python3 examples/plot_refinement.py refinement.csv refinement.png  (Debian python3-matplotlib)
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(csv_path, png_path):
    rows = list(csv.DictReader(open(csv_path)))
    solvers = list(dict.fromkeys(r["solver"] for r in rows))
    colours = dict(zip(solvers, plt.rcParams["axes.prop_cycle"].by_key()["color"]))
    figure, axes = plt.subplots(2, 3, figsize=(14, 7.5))
    panels = [  # (x column, fixed column and value, rotation model, title)
        ("noise_px", ("imu_deg", "0"), "yaw-only", "image noise (0.5-2 px), exact IMU, yaw-only"),
        ("imu_deg", ("noise_px", "1"), "yaw-only", "IMU noise at 1 px, yaw-only"),
        ("imu_deg", ("noise_px", "1"), "gravity-prior", "IMU noise at 1 px, gravity prior"),
    ]
    for column, (x_name, fixed, model, title) in enumerate(panels):
        for row, (metric, label) in enumerate(
            [("rotation_deg", "rotation error (deg)"), ("translation_deg", "translation error (deg)")]
        ):
            ax = axes[row][column]
            for solver in solvers:
                selected = [
                    r
                    for r in rows
                    if r["solver"] == solver
                    and r["model"] == model
                    and (r[fixed[0]] == fixed[1] or (x_name == "imu_deg" and r["imu_deg"] == "0"))
                ]
                if x_name == "imu_deg":
                    selected = [r for r in selected if r["noise_px"] == "1"]
                else:  # noise-free errors (~1e-14 deg) are in the CSV; they would flatten the plot
                    selected = [r for r in selected if float(r["noise_px"]) > 0]
                selected.sort(key=lambda r: float(r[x_name]))
                xs = [float(r[x_name]) for r in selected]
                ax.plot(xs, [float(r["raw_" + metric]) for r in selected], "--",
                        color=colours[solver], alpha=0.7)
                ax.plot(xs, [float(r["refined_" + metric]) for r in selected], "-o", markersize=3,
                        color=colours[solver], label=solver)
            ax.set_yscale("log")
            ax.set_xlabel("image noise (px)" if x_name == "noise_px" else "IMU pitch/roll noise (deg)")
            ax.set_ylabel(label)
            ax.grid(True, which="both", alpha=0.3)
            if row == 0:
                ax.set_title(title)
    axes[0][0].legend(title="solid: refined, dashed: raw", fontsize=8)
    figure.tight_layout()
    figure.savefig(png_path, dpi=64)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
