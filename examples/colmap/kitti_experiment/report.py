"""The experiment's markdown table and trajectory figure."""

import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLUMNS = [
    ("variant", "variant"),
    ("sub-models", "num_models"),
    ("registered", "registered_of"),
    ("rot. median (deg)", "rotation_median_deg"),
    ("rot. mean (deg)", "rotation_mean_deg"),
    ("ATE RMSE (m)", "ate_rmse_m"),
    ("RPE rot. median (deg)", "rpe_rotation_median_deg"),
    ("RPE dir. median (deg)", "rpe_translation_direction_median_deg"),
    ("reproj. (px)", "mean_reprojection_error_px"),
    ("time (s)", "seconds"),
]


def _cell(row, key):
    if key == "registered_of":
        return "%d / %d" % (row.get("registered", 0), row["frames"])
    value = row.get(key)
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    if isinstance(value, float):
        if key == "seconds":
            return "%.0f" % value if value >= 10 else "%.1f" % value
        return "%.3f" % value if abs(value) < 10 else "%.1f" % value
    return str(value)


def markdown(results):
    """One table per sequence, then the front end's times."""
    lines = []
    for seq, sequence in results["sequences"].items():
        lines.append("KITTI %s, frames 0-%d (front end: feature_extractor %s s, sequential_matcher "
                     "%s s)" % (seq, sequence["frames"] - 1,
                                _cell(sequence["front_end"], "extract_seconds"),
                                _cell(sequence["front_end"], "match_seconds")))
        lines.append("")
        lines.append("| " + " | ".join(title for title, _ in COLUMNS) + " |")
        lines.append("|" + "|".join("---" for _ in COLUMNS) + "|")
        for row in sequence["variants"]:
            if row.get("failed"):
                cells = [row["variant"], "0", "0 / %d" % row["frames"]] + ["-"] * (len(COLUMNS) - 4)
                cells.append(_cell(row, "seconds"))
                cells[3] = "failed: %s" % row["failed"]
            else:
                cells = [_cell(row, key) for _, key in COLUMNS]
            lines.append("| " + " | ".join(cells) + " |")
        lines.append("")
    return "\n".join(lines)


def plot(results, ground_truth, png_path):
    """Per sequence, a column: top view (x right, z forward of frame 0's camera, metres) of the
    ground truth and every variant after its Sim(3) alignment; below it each camera's position
    error after that alignment against the frame."""
    sequences = list(results["sequences"].items())
    fig, axes = plt.subplots(2, len(sequences), figsize=(6.5 * len(sequences), 9.0),
                             squeeze=False, gridspec_kw={"height_ratios": [2, 1]})
    for column, (seq, sequence) in enumerate(sequences):
        top, error = axes[0][column], axes[1][column]
        centres = ground_truth[seq][:sequence["frames"]]
        top.plot(centres[:, 0], centres[:, 2], color="0.6", linewidth=4, label="ground truth")
        for row in sequence["variants"]:
            trajectory = row.get("trajectory")
            if not trajectory:
                continue
            label = "%s (%d)" % (row["variant"], row["registered"])
            style = "--" if "BA" in row["variant"] else "-"
            line, = top.plot(trajectory["x"], trajectory["z"], style, linewidth=1.2, label=label)
            error.plot(trajectory["frame"], trajectory["error_m"], style, linewidth=1.0,
                       color=line.get_color())
        top.set_title("KITTI %s, frames 0-%d" % (seq, sequence["frames"] - 1))
        top.set_xlabel("x (m)")
        top.set_ylabel("z (m)")
        top.set_aspect("equal", adjustable="datalim")
        top.grid(True, linewidth=0.3)
        top.legend(fontsize=7, loc="best")
        error.set_xlabel("frame")
        error.set_ylabel("position error after Sim(3) alignment (m)")
        error.grid(True, linewidth=0.3)
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)
    plt.close(fig)
