#!/usr/bin/python3
"""Plots the CSVs of paper_experiments like the paper's figures (Debian python3-matplotlib):

    paper_stability.png  densities of log10 rotation / translation errors, 5000 noise-free scenes
    paper_noise.png      median errors against image noise (minimal samples)
    paper_imu.png        median errors against IMU pitch and roll noise at 1 px (minimal samples)

(The 20-triplet experiment is plotted by examples/initialize_and_refine/plot_raw_vs_refined.py.)

    /usr/bin/python3 plot_paper_experiments.py <csv folder> <png folder>
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

DPI = 64
PALETTE = plt.rcParams["axes.prop_cycle"].by_key()["color"]


def methods_and_styles(rows):
    """The methods of a CSV in its row order (kInitialSolvers, then the paper's 4-point variant),
    one colour each; the paper's two methods drawn thicker."""
    methods = list(dict.fromkeys(r["method"] for r in rows))
    styles = {m: dict(color=c) for m, c in zip(methods, PALETTE)}
    for m in ("3pt", "4pt"):
        if m in styles:
            styles[m]["linewidth"] = 2.2
    return methods, styles


def read(folder, name):
    with open(os.path.join(folder, name + ".csv")) as f:
        return list(csv.DictReader(f))


def plot_stability(folder, out):
    rows = read(folder, "stability_histogram")
    methods, styles = methods_and_styles(rows)
    figure, axes = plt.subplots(1, 2, figsize=(11, 3.8))
    for ax, quantity in zip(axes, ["rotation", "translation"]):
        for method in methods:
            sel = [r for r in rows if r["method"] == method and r["quantity"] == quantity]
            x = [(float(r["log10_lo"]) + float(r["log10_hi"])) / 2 for r in sel]
            ax.plot(x, [float(r["density"]) for r in sel], label=method, **styles[method])
        ax.set_xlim(-16.5, -4)
        ax.set_xlabel(f"log10 {quantity} error (deg)")
        ax.set_ylabel("density")
        ax.set_title(f"numerical stability: {quantity}, noise-free")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    figure.tight_layout()
    figure.savefig(os.path.join(out, "paper_stability.png"), dpi=DPI)


def median_panels(axes, rows, x_column, title):
    methods, styles = methods_and_styles(rows)
    for ax, (metric, name) in zip(axes, [("rotation_deg", "rotation"), ("translation_deg", "translation")]):
        for method in methods:
            sel = sorted((r for r in rows if r["method"] == method), key=lambda r: float(r[x_column]))
            ax.plot([float(r[x_column]) for r in sel], [float(r[metric]) for r in sel], marker="o",
                    markersize=3, label=method, **styles[method])
        ax.set_ylabel(f"median {name} error (deg)")
        ax.set_title(title)
        ax.grid(alpha=0.3)


def plot_noise(folder, out):
    rows = read(folder, "noise")
    figure, axes = plt.subplots(1, 2, figsize=(11, 3.8))
    median_panels(axes, rows, "noise_px", "image noise, minimal samples")
    for ax in axes:
        ax.set_xlabel("image noise sigma (px)")
    axes[0].legend(fontsize=7)
    figure.tight_layout()
    figure.savefig(os.path.join(out, "paper_noise.png"), dpi=DPI)


def plot_imu(folder, out):
    figure, axes = plt.subplots(2, 2, figsize=(11, 7))
    for column, (name, x_column) in enumerate([("pitch", "pitch_deg"), ("roll", "roll_deg")]):
        rows = read(folder, name)
        median_panels([axes[0][column], axes[1][column]], rows, x_column,
                      f"IMU {name} noise at 1 px, minimal samples")
        axes[1][column].set_xlabel(f"IMU {name} noise sigma (deg)")
    axes[0][0].legend(fontsize=7)
    figure.tight_layout()
    figure.savefig(os.path.join(out, "paper_imu.png"), dpi=DPI)


def main(folder, out):
    os.makedirs(out, exist_ok=True)
    plot_stability(folder, out)
    plot_noise(folder, out)
    plot_imu(folder, out)
    print(f"wrote paper_stability, paper_noise, paper_imu PNGs to {out}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
