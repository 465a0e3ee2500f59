#!/usr/bin/python3
"""Plots a CSV of initialize_and_refine_synthetic (Debian python3-matplotlib): median rotation and
translation errors of the RANSAC estimate (raw, dashed) and of its refinement (solid), per method.

    --experiment=sweep     against image noise (exact IMU, yaw-only) and against IMU noise at 1 px
                           (yaw-only; gravity prior), log scale
    --experiment=sample20  20 triplets each: against image noise, IMU pitch noise and IMU roll
                           noise at 1 px (the optional peer rows are not plotted)

    /usr/bin/python3 plot_raw_vs_refined.py <sweep.csv or sample20.csv> <png>
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

DPI = 64
PALETTE = plt.rcParams["axes.prop_cycle"].by_key()["color"]


def in_csv_order(rows, column):
    """The methods of a CSV in its row order, which follows kInitialSolvers (one colour each)."""
    return list(dict.fromkeys(r[column] for r in rows))

METRICS = [("rotation_deg", "rotation error (deg)"), ("translation_deg", "translation error (deg)")]


def plot_sweep(rows, png_path):
    solvers = in_csv_order(rows, "solver")
    colours = dict(zip(solvers, PALETTE))
    figure, axes = plt.subplots(2, 3, figsize=(14, 7.5))
    panels = [  # (x column, rotation model, title)
        ("noise_px", "yaw-only", "image noise (0.5-2 px), exact IMU, yaw-only"),
        ("imu_deg", "yaw-only", "IMU noise at 1 px, yaw-only"),
        ("imu_deg", "gravity-prior", "IMU noise at 1 px, gravity prior"),
    ]
    for column, (x_name, model, title) in enumerate(panels):
        for row, (metric, label) in enumerate(METRICS):
            ax = axes[row][column]
            for solver in solvers:
                selected = [r for r in rows if r["solver"] == solver and r["model"] == model]
                if x_name == "imu_deg":  # 1 px, IMU noise 0 (from the image noise rows) to 1 deg
                    selected = [r for r in selected if r["noise_px"] == "1"]
                else:  # exact IMU; the noise-free errors (~1e-14 deg) would flatten the plot
                    selected = [r for r in selected if r["imu_deg"] == "0" and float(r["noise_px"]) > 0]
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
    figure.savefig(png_path, dpi=DPI)


def plot_sample20(rows, png_path):
    # trigrav's methods (those with a refined stage; the peers have only their raw estimate)
    solvers = [m for m in in_csv_order(rows, "method")
               if any(r["method"] == m and r["stage"] == "refined" for r in rows)]
    colours = dict(zip(solvers, PALETTE))
    panels = [("noise_px", lambda r: r["pitch_deg"] == "0" and r["roll_deg"] == "0", "image noise (px)"),
              ("pitch_deg", lambda r: r["noise_px"] == "1" and r["roll_deg"] == "0", "IMU pitch noise (deg), 1 px"),
              ("roll_deg", lambda r: r["noise_px"] == "1" and r["pitch_deg"] == "0", "IMU roll noise (deg), 1 px")]
    figure, axes = plt.subplots(2, 3, figsize=(14, 7))
    for column, (x_name, keep, xlabel) in enumerate(panels):
        for row, (metric, label) in enumerate(METRICS):
            ax = axes[row][column]
            for solver in solvers:
                for stage, style in [("raw", "--"), ("refined", "-")]:
                    selected = sorted((r for r in rows if r["method"] == solver and r["stage"] == stage
                                       and keep(r)), key=lambda r: float(r[x_name]))
                    ax.plot([float(r[x_name]) for r in selected], [float(r[metric]) for r in selected],
                            style, marker="o", markersize=3, color=colours[solver],
                            label=f"{solver} {stage}")
            ax.set_xlabel(xlabel)
            ax.set_ylabel(f"median {label}")
            ax.set_title("20 triplets: raw (dashed), refined (solid)")
            ax.grid(alpha=0.3)
    axes[0][0].legend(fontsize=6, ncol=2)
    figure.tight_layout()
    figure.savefig(png_path, dpi=DPI)


def main(csv_path, png_path):
    with open(csv_path) as f:
        rows = list(csv.DictReader(f))
    if rows and "stage" in rows[0]:
        plot_sample20(rows, png_path)
    else:
        plot_sweep(rows, png_path)
    print(f"wrote {png_path}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
