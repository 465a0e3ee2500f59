#!/usr/bin/python3
"""Height error and tilt error along the trajectory, per variant, from gravity_pays --profile_csv.

  /usr/bin/python3 examples/experiments/plot_gravity_pays.py profile.csv out.png [scenario]

One column of two panels per scenario (default: every scenario whose name contains "IMU 0.1 deg"):
height error (m) and tilt error (deg) against the image index, one line per variant.
"""

import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    wanted = sys.argv[3] if len(sys.argv) == 4 else "IMU 0.1 deg"
    data = {}  # scenario -> variant -> ([image], [height], [tilt])
    with open(sys.argv[1]) as f:
        for row in csv.DictReader(f):
            if wanted not in row["scenario"]:
                continue
            series = data.setdefault(row["scenario"], {}).setdefault(row["variant"], ([], [], []))
            series[0].append(int(row["image"]))
            series[1].append(float(row["height_error_m"]))
            series[2].append(float(row["tilt_error_deg"]))
    if not data:
        sys.exit("no scenario matching '%s' in %s" % (wanted, sys.argv[1]))
    figure, axes = plt.subplots(2, len(data), figsize=(5.5 * len(data), 6.5), squeeze=False)
    for column, (scenario, variants) in enumerate(data.items()):
        for variant, (image, height, tilt) in variants.items():
            axes[0][column].plot(image, height, label=variant, linewidth=1)
            axes[1][column].plot(image, tilt, label=variant, linewidth=0.6)
        axes[0][column].set_title(scenario, fontsize=9)
        axes[0][column].set_ylabel("height error (m)")
        axes[1][column].set_ylabel("tilt error (deg)")
        axes[1][column].set_xlabel("image")
        axes[1][column].set_yscale("log")
        axes[0][column].grid(alpha=0.3)
        axes[1][column].grid(alpha=0.3)
    axes[0][0].legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(sys.argv[2], dpi=110)
    print("wrote", sys.argv[2])


if __name__ == "__main__":
    main()
