#!/usr/bin/python3
"""COLMAP alone against COLMAP with trigrav, on KITTI odometry sequences, in one command.

  /usr/bin/python3 examples/colmap/run_kitti_experiment.py --kitti_path KITTI \
      --build_dir build --work_dir /tmp/kitti_colmap [--sequences 00 02] [--frames 300]

Per sequence (work folder <work_dir>/<seq>/):
  front end   colmap feature_extractor (PINHOLE, one camera, the KITTI P0 intrinsics, CPU SIFT)
              and sequential_matcher (CPU)                          -> database.db
  (a)         colmap mapper with its defaults                       -> sparse_default/0, 1, ...
              and with --Mapper.init_max_forward_motion 1.0 --Mapper.init_min_tri_angle 4
                                                                    -> sparse_tuned/0, 1, ...
  gravity     make_gravity_csv, exact and with 0.1 deg noise (seed 1) -> gravity_*.csv
  (b)         triplet_initializer (consecutive triplets, exact gravity) -> triplet_model/,
              then colmap mapper --input_path triplet_model            -> sparse_triplet/
  (c)         gravity_bundle_adjuster on the largest model of (a), tuned (and default when it
              exists): yaw_only and gravity_prior, each with exact gravity (prior sigma 0.01 deg)
              and 0.1 deg gravity (prior sigma 0.1 deg)               -> ba_<base>_<model>_<g>/
  evaluation  largest sub-model of each variant against poses/<seq>.txt: registered images,
              absolute rotation error and ATE RMSE after Sim(3) alignment of the camera centres,
              relative pose errors of consecutive frames, run time.
Every stage logs to <stage>.log and writes <stage>.json (command, seconds, exit status); a stage
whose json (same command, newer than those of the stages it reads) and outputs exist is skipped
(--fresh redoes everything). A front end made by hand with
`/usr/bin/time -v colmap ... 2> extract.time` and `touch extract.done` (the same for match) is
reused: point --front_end_dir at its folder (<dir>/<seq>/database.db, extract.time, match.done ...);
its database is copied, never written. Results: <work_dir>/results.json and results.md (also on
stdout), the trajectory figure in --figures_dir. Needs numpy and matplotlib (Debian's python3).
"""

import argparse
import json
import os
import re
import shutil
import sqlite3
import subprocess
import sys
import time

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from kitti_experiment import colmap_model, evaluation, report  # noqa: E402

KITTI_CAMERA_PARAMS = "718.856,718.856,607.1928,185.2157"  # fx, fy, cx, cy of P0
TUNED_INIT = ["--Mapper.init_max_forward_motion", "1.0", "--Mapper.init_min_tri_angle", "4"]
NOISE_DEG = 0.1
NOISE_SEED = 1
# gravity_prior's sigma per gravity CSV: the IMU's for the noisy one; a small one for exact gravity
# (the prior then nearly fixes pitch and roll, as yaw_only does exactly).
GRAVITY = [("exact", 0.0, 0.01), ("noise0.1", NOISE_DEG, NOISE_DEG)]
ROTATION_MODELS = ["yaw_only", "gravity_prior"]


class Stages:
    """Runs the stages of one sequence in its work folder, each cached by <name>.json."""

    def __init__(self, work, seq, fresh):
        self.work, self.seq, self.fresh = work, seq, fresh
        self.env = dict(os.environ, QT_QPA_PLATFORM="offscreen")

    def path(self, *names):
        return os.path.join(self.work, *names)

    def cached(self, name, command, outputs, inputs):
        """The record of a stage run before with the same command (or a front end made with GNU
        time) whose outputs exist and whose input stages have not run since, else None."""
        record_path = self.path(name + ".json")
        if self.fresh or not os.path.isfile(record_path):
            return None
        if not all(os.path.exists(self.path(o)) for o in outputs):
            return None
        if any(os.path.getmtime(self.path(i + ".json")) > os.path.getmtime(record_path)
               for i in inputs):
            return None
        with open(record_path) as f:
            record = json.load(f)
        return record if record.get("gnu_time") or record["command"] == command else None

    def run(self, name, command, outputs, inputs=(), may_fail=False, nice=False, make_dirs=(),
            clean=True):
        """Runs `command` unless cached; returns its record. `inputs`: the stages whose outputs it
        reads (a newer record of one makes it run again). Removes the outputs first when clean (not
        for a stage that adds to its input, as the matcher to the database). A non-zero exit stops
        the experiment unless may_fail (the mapper failing to initialise is a result)."""
        if nice:
            command = ["nice", "-n", "5"] + command
        record = self.cached(name, command, outputs, inputs)
        if record is not None:
            print("[%s] %-28s cached (%.1f s)" % (self.seq, name, record["seconds"]), flush=True)
            return record
        for output in outputs if clean else []:
            target = self.path(output)
            if os.path.isdir(target) and not os.path.islink(target):
                shutil.rmtree(target)
            for path in (target, target + "-wal", target + "-shm"):  # SQLite's files too
                if os.path.lexists(path) and not os.path.isdir(path):
                    os.remove(path)
        for d in make_dirs:
            os.makedirs(self.path(d), exist_ok=True)
        log_path = self.path(name + ".log")
        start = time.monotonic()
        with open(log_path, "w") as log:
            status = subprocess.run(command, stdout=log, stderr=subprocess.STDOUT, env=self.env,
                                    cwd=self.work).returncode
        record = {"command": command, "seconds": time.monotonic() - start, "returncode": status}
        print("[%s] %-28s %s in %.1f s (log %s)"
              % (self.seq, name, "ok" if status == 0 else "exit %d" % status, record["seconds"],
                 log_path), flush=True)
        if status != 0 and not may_fail:
            sys.exit("%s failed (exit %d): %s\nsee %s" % (name, status, " ".join(command), log_path))
        with open(self.path(name + ".json"), "w") as f:
            json.dump(record, f, indent=1)
        return record


def gnu_time_record(path):
    """(wall time in s, command) from the output of GNU `time -v` (its "Elapsed (wall clock)"
    and "Command being timed" lines)."""
    seconds, command = None, None
    with open(path, errors="replace") as f:
        for line in f:
            match = re.search(r"Elapsed \(wall clock\) time.*: ([\d:.]+)\s*$", line)
            if match:
                seconds = 0.0
                for part in match.group(1).split(":"):
                    seconds = 60.0 * seconds + float(part)
            match = re.search(r'Command being timed: "(.*)"\s*$', line)
            if match:
                command = match.group(1)
    if seconds is None:
        sys.exit("%s: no 'Elapsed (wall clock) time' line of GNU time -v" % path)
    return seconds, command


def adopt_gnu_time_front_end(stages, source):
    """Uses a front end made with GNU time (extract.done / extract.time, match.done / match.time
    in `source`): copies its database into the work folder (unless source is that folder) and
    writes extract.json / match.json from the times. Returns False when it is not complete."""
    if not all(os.path.isfile(os.path.join(source, f))
               for f in ("database.db", "extract.done", "extract.time", "match.done",
                         "match.time")):
        return False
    if os.path.realpath(source) != os.path.realpath(stages.work):
        for suffix in ("", "-wal"):  # a database left in WAL mode needs its log as well
            if os.path.isfile(os.path.join(source, "database.db" + suffix)):
                shutil.copyfile(os.path.join(source, "database.db" + suffix),
                                stages.path("database.db" + suffix))
    for name in ("extract", "match"):
        seconds, command = gnu_time_record(os.path.join(source, name + ".time"))
        record = {"command": command, "gnu_time": os.path.join(source, name + ".time"),
                  "seconds": seconds, "returncode": 0}
        with open(stages.path(name + ".json"), "w") as f:
            json.dump(record, f, indent=1)
    print("[%s] front end reused from %s" % (stages.seq, source), flush=True)
    return True


def database_image_names(path):
    connection = sqlite3.connect("file:%s?mode=ro" % path, uri=True)
    try:
        return [row[0] for row in connection.execute("SELECT name FROM images")]
    finally:
        connection.close()


def image_folder(args, stages):
    """The folder of the first --frames images: KITTI's own when it holds exactly those, else a
    folder of links in the work folder."""
    source = os.path.join(args.kitti_path, "sequences", stages.seq, "image_0")
    names = sorted(n for n in os.listdir(source) if n.endswith(".png"))
    if args.frames > len(names):
        sys.exit("%s has %d images, fewer than --frames %d" % (source, len(names), args.frames))
    if args.frames == len(names):
        return os.path.abspath(source)
    folder = stages.path("images")
    if os.path.isdir(folder) and sorted(os.listdir(folder)) != names[:args.frames]:
        shutil.rmtree(folder)
    if not os.path.isdir(folder):
        os.makedirs(folder)
        for name in names[:args.frames]:
            os.symlink(os.path.abspath(os.path.join(source, name)), os.path.join(folder, name))
    return folder


def front_end(args, stages, images):
    if not stages.fresh and not os.path.isfile(stages.path("match.json")):
        for source in ([os.path.join(args.front_end_dir, stages.seq)] if args.front_end_dir
                       else []) + [stages.work]:
            if adopt_gnu_time_front_end(stages, source):
                break
        else:
            if args.front_end_dir:
                sys.exit("%s: front end not finished (needs database.db, extract.done/.time, "
                         "match.done/.time)" % os.path.join(args.front_end_dir, stages.seq))
    database = stages.path("database.db")
    extract = ["colmap", "feature_extractor", "--database_path", database, "--image_path", images,
               "--ImageReader.camera_model", "PINHOLE", "--ImageReader.single_camera", "1",
               "--ImageReader.camera_params", KITTI_CAMERA_PARAMS, "--SiftExtraction.use_gpu", "0"]
    if args.max_features:
        extract += ["--SiftExtraction.max_num_features", str(args.max_features)]
    times = {"extract_seconds": stages.run("extract", extract, ["database.db"])["seconds"]}
    match = ["colmap", "sequential_matcher", "--database_path", database,
             "--SiftMatching.use_gpu", "0", "--SequentialMatching.overlap", str(args.overlap),
             "--SequentialMatching.quadratic_overlap", str(args.quadratic_overlap)]
    times["match_seconds"] = stages.run("match", match, ["database.db"], ["extract"], clean=False)["seconds"]
    in_database = len(database_image_names(database))
    if in_database != args.frames:
        sys.exit("%s holds %d images, not --frames %d" % (database, in_database, args.frames))
    return times


def mapper(stages, name, images, extra, output, inputs=("match",)):
    command = ["colmap", "mapper", "--database_path", stages.path("database.db"),
               "--image_path", images, "--output_path", stages.path(output)] + extra
    return stages.run(name, command, [output], inputs, may_fail=True, nice=True,
                      make_dirs=[output])


def variant_row(stages, label, output, seconds, frames, ground_truth):
    model, num_models = colmap_model.largest_model(stages.path(output))
    row = {"variant": label, "frames": frames, "seconds": seconds, "num_models": num_models,
           "model_path": model.path if model else None}
    if model is None:
        row["failed"] = "no model"
        return row
    row.update(evaluation.evaluate(model, *ground_truth))
    return row


def run_sequence(args, seq, tools):
    work = os.path.join(args.work_dir, seq)
    os.makedirs(work, exist_ok=True)
    stages = Stages(work, seq, args.fresh)
    images = image_folder(args, stages)
    times = front_end(args, stages, images)
    poses_path = os.path.join(args.kitti_path, "poses", seq + ".txt")
    ground_truth = evaluation.read_kitti_poses(poses_path)
    rows = []

    def add(label, output, seconds):
        row = variant_row(stages, label, output, seconds, args.frames, ground_truth)
        rows.append(row)
        return row

    bases = []
    if "a" in args.parts or "c" in args.parts:
        for base, extra in (("default", []), ("tuned", TUNED_INIT)):
            record = mapper(stages, "mapper_" + base, images, extra, "sparse_" + base)
            row = add("COLMAP %s" % base, "sparse_" + base, record["seconds"])
            if row.get("model_path"):
                bases.append((base, row["model_path"]))

    if "b" in args.parts or "c" in args.parts:
        for tag, noise, _ in GRAVITY:
            stages.run("gravity_" + tag,
                       [tools["make_gravity_csv"], "--poses_path", poses_path, "--image_path",
                        images, "--output_path", stages.path("gravity_%s.csv" % tag),
                        "--noise_deg", str(noise), "--seed", str(NOISE_SEED)],
                       ["gravity_%s.csv" % tag])

    if "b" in args.parts:
        initializer = stages.run(
            "triplet_initializer",
            [tools["triplet_initializer"], "--database_path",
             stages.path("database.db"), "--gravity_csv", stages.path("gravity_exact.csv"),
             "--output_csv", stages.path("triplets.csv"), "--output_model_path",
             stages.path("triplet_model"), "--triplets", "consecutive"],
            ["triplets.csv", "triplet_model"], ["match", "gravity_exact"], nice=True)
        record = mapper(stages, "mapper_triplet", images,
                        ["--input_path", stages.path("triplet_model")], "sparse_triplet",
                        ("match", "triplet_initializer"))
        add("trigrav triplet + COLMAP", "sparse_triplet",
            initializer["seconds"] + record["seconds"])

    if "c" in args.parts:
        for base, model_path in sorted(bases, key=lambda b: b[0] != "tuned"):
            for rotation_model in ROTATION_MODELS:
                for tag, _, sigma in GRAVITY:
                    name = "ba_%s_%s_%s" % (base, rotation_model, tag)
                    command = [tools["gravity_bundle_adjuster"], "--input_path", model_path,
                               "--gravity_csv", stages.path("gravity_%s.csv" % tag),
                               "--output_path", stages.path(name),
                               "--rotation_model", rotation_model]
                    if rotation_model == "gravity_prior":
                        command += ["--gravity_sigma_deg", str(sigma)]
                    record = stages.run(name, command, [name],
                                        ["mapper_" + base, "gravity_" + tag], nice=True)
                    gravity = "exact" if tag == "exact" else "%g deg" % NOISE_DEG
                    prior = " (sigma %g deg)" % sigma if rotation_model == "gravity_prior" else ""
                    add("%s + BA %s, %s gravity%s" % (base, rotation_model, gravity, prior), name,
                        record["seconds"])

    order = {"COLMAP": 0, "trigrav": 1}
    rows.sort(key=lambda r: order.get(r["variant"].split()[0], 2))
    return {"frames": args.frames, "front_end": times, "variants": rows}, ground_truth[1]


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--kitti_path", required=True,
                        help="KITTI odometry folder (sequences/<seq>/image_0, poses/<seq>.txt)")
    parser.add_argument("--build_dir", required=True,
                        help="trigrav build folder (tools in <build_dir>/examples/colmap/)")
    parser.add_argument("--work_dir", required=True, help="work folder, one sub-folder per sequence")
    parser.add_argument("--sequences", nargs="+", default=["00", "02"])
    parser.add_argument("--frames", type=int, default=300, help="first N frames of each sequence")
    parser.add_argument("--parts", default="a,b,c",
                        help="comma-separated variants to run: a (COLMAP), b (triplet seed), "
                             "c (gravity BA, needs a)")
    parser.add_argument("--front_end_dir", default="",
                        help="reuse a finished front end: <dir>/<seq>/database.db with GNU time "
                             "files extract.time, match.time and markers extract.done, match.done")
    parser.add_argument("--max_features", type=int, default=2048,
                        help="SIFT features per image, --SiftExtraction.max_num_features "
                             "(0: COLMAP's default, 8192, which makes CPU matching ~16x slower)")
    parser.add_argument("--overlap", type=int, default=5,
                        help="--SequentialMatching.overlap: each image is matched with this many "
                             "next ones (COLMAP's default 10)")
    parser.add_argument("--quadratic_overlap", type=int, choices=(0, 1), default=0,
                        help="--SequentialMatching.quadratic_overlap (COLMAP's default 1)")
    parser.add_argument("--figures_dir", default=os.path.join(here, "figures"))
    parser.add_argument("--fresh", action="store_true", help="redo every stage")
    args = parser.parse_args()
    args.parts = set(args.parts.split(","))
    if not args.parts <= {"a", "b", "c"}:
        parser.error("--parts: a, b, c")
    if args.frames < 3:
        parser.error("--frames must be at least 3")

    needed = (["make_gravity_csv"] if args.parts & {"b", "c"} else []) + \
        (["triplet_initializer"] if "b" in args.parts else []) + \
        (["gravity_bundle_adjuster"] if "c" in args.parts else [])
    tools = {t: os.path.abspath(os.path.join(args.build_dir, "examples", "colmap", t))
             for t in needed}
    missing = [p for p in tools.values() if not os.access(p, os.X_OK)]
    if missing:
        sys.exit("not built: %s (cmake --build %s --target %s)"
                 % (", ".join(missing), args.build_dir, " ".join(needed)))
    if shutil.which("colmap") is None:
        sys.exit("colmap not found on PATH")

    args.work_dir = os.path.abspath(args.work_dir)
    results = {"command": sys.argv, "sequences": {}}
    centres = {}
    for seq in args.sequences:
        results["sequences"][seq], centres[seq] = run_sequence(args, seq, tools)

    table = report.markdown(results)
    with open(os.path.join(args.work_dir, "results.json"), "w") as f:
        json.dump(results, f, indent=1)
    with open(os.path.join(args.work_dir, "results.md"), "w") as f:
        f.write(table + "\n")
    os.makedirs(args.figures_dir, exist_ok=True)
    png = os.path.join(args.figures_dir, "kitti_experiment_trajectories.png")
    report.plot(results, centres, png)
    print()
    print(table)
    print("results: %s, %s; figure: %s" % (os.path.join(args.work_dir, "results.json"),
                                          os.path.join(args.work_dir, "results.md"), png))


if __name__ == "__main__":
    main()
