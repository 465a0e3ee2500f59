#!/usr/bin/python3
"""KITTI rows of gravity_pays: COLMAP 3.8 with fixed intrinsics, then gravity_pays on its models.

  /usr/bin/python3 examples/experiments/gravity_pays_kitti.py --kitti_path KITTI \
      --build_dir build --work_dir /tmp/gravity_pays_kitti [--sequences 00 02] [--frames 300] \
      [-- <more gravity_pays flags, e.g. --weak=false --imu_noise_deg=0.1>]

Per sequence, in <work_dir>/<seq>_<frames>/: the first --frames images linked into images/,
colmap feature_extractor (PINHOLE, one camera, KITTI's P0 intrinsics, CPU SIFT, --max_features),
sequential_matcher (overlap --overlap, no quadratic overlap) and mapper with the intrinsics held
fixed (--Mapper.ba_refine_focal_length 0, ba_refine_principal_point 0, ba_refine_extra_params 0)
-> sparse/0, 1, ... Each stage writes <stage>.log and, when it succeeds, <stage>.done with its wall
time; a stage whose .done exists is skipped (delete the folder to redo it). Then
<build_dir>/examples/experiments/gravity_pays runs with --kitti_models=<seq>=<largest model>,...
and the flags after `--`, and prints its table (synthetic scenarios first, then KITTI: exact and
0.1 deg gravity made from the ground truth, as make_gravity_csv does).
"""

import argparse
import os
import struct
import subprocess
import sys
import time

KITTI_CAMERA_PARAMS = "718.856,718.856,607.1928,185.2157"  # fx, fy, cx, cy of P0


def run_stage(work, name, command):
    done = os.path.join(work, name + ".done")
    if os.path.isfile(done):
        with open(done) as f:
            print("[%s] %-8s cached (%s s)" % (os.path.basename(work), name, f.read().strip()),
                  flush=True)
        return
    start = time.monotonic()
    with open(os.path.join(work, name + ".log"), "w") as log:
        status = subprocess.run(command, stdout=log, stderr=subprocess.STDOUT, cwd=work,
                                env=dict(os.environ, QT_QPA_PLATFORM="offscreen")).returncode
    seconds = time.monotonic() - start
    if status != 0:
        sys.exit("%s failed (exit %d), see %s" % (name, status,
                                                  os.path.join(work, name + ".log")))
    with open(done, "w") as f:
        f.write("%.1f\n" % seconds)
    print("[%s] %-8s ok in %.1f s" % (os.path.basename(work), name, seconds), flush=True)


def num_registered(model):
    """Images of a binary COLMAP model (the count at the head of images.bin)."""
    with open(os.path.join(model, "images.bin"), "rb") as f:
        return struct.unpack("<Q", f.read(8))[0]


def colmap_model(args, seq):
    work = os.path.abspath(os.path.join(args.work_dir, "%s_%d" % (seq, args.frames)))
    images = os.path.join(work, "images")
    os.makedirs(images, exist_ok=True)
    source = os.path.join(args.kitti_path, "sequences", seq, "image_0")
    names = sorted(n for n in os.listdir(source) if n.endswith(".png"))[:args.frames]
    if len(names) < args.frames:
        sys.exit("%s has fewer than --frames %d images" % (source, args.frames))
    for name in names:
        link = os.path.join(images, name)
        if not os.path.lexists(link):
            os.symlink(os.path.abspath(os.path.join(source, name)), link)
    database = os.path.join(work, "database.db")
    run_stage(work, "extract",
              ["colmap", "feature_extractor", "--database_path", database, "--image_path", images,
               "--ImageReader.camera_model", "PINHOLE", "--ImageReader.single_camera", "1",
               "--ImageReader.camera_params", KITTI_CAMERA_PARAMS, "--SiftExtraction.use_gpu",
               "0", "--SiftExtraction.max_num_features", str(args.max_features)])
    run_stage(work, "match",
              ["colmap", "sequential_matcher", "--database_path", database,
               "--SiftMatching.use_gpu", "0", "--SequentialMatching.overlap", str(args.overlap),
               "--SequentialMatching.quadratic_overlap", "0"])
    sparse = os.path.join(work, "sparse")
    os.makedirs(sparse, exist_ok=True)
    run_stage(work, "mapper",
              ["colmap", "mapper", "--database_path", database, "--image_path", images,
               "--output_path", sparse, "--Mapper.ba_refine_focal_length", "0",
               "--Mapper.ba_refine_principal_point", "0", "--Mapper.ba_refine_extra_params", "0"])
    models = [os.path.join(sparse, d) for d in sorted(os.listdir(sparse))
              if os.path.isfile(os.path.join(sparse, d, "images.bin"))]
    if not models:
        sys.exit("%s: the mapper made no model" % sparse)
    best = max(models, key=num_registered)
    print("[%s] largest of %d model(s): %s, %d of %d images" %
          (os.path.basename(work), len(models), best, num_registered(best), args.frames),
          flush=True)
    return best


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--kitti_path", required=True,
                        help="KITTI odometry folder (sequences/<seq>/image_0, poses/<seq>.txt)")
    parser.add_argument("--build_dir", required=True, help="trigrav build folder")
    parser.add_argument("--work_dir", required=True, help="work folder, one sub-folder per run")
    parser.add_argument("--sequences", nargs="+", default=["00", "02"])
    parser.add_argument("--frames", type=int, default=300, help="first N frames of each")
    parser.add_argument("--max_features", type=int, default=2048,
                        help="--SiftExtraction.max_num_features")
    parser.add_argument("--overlap", type=int, default=5, help="--SequentialMatching.overlap")
    parser.add_argument("gravity_pays_flags", nargs="*",
                        help="flags passed on to gravity_pays (after --)")
    args = parser.parse_args()
    if args.frames < 3:
        parser.error("--frames must be at least 3")
    tool = os.path.join(args.build_dir, "examples", "experiments", "gravity_pays")
    if not os.access(tool, os.X_OK):
        sys.exit("not built: %s (cmake --build %s --target gravity_pays)" % (tool, args.build_dir))
    models = ["%s=%s" % (seq, colmap_model(args, seq)) for seq in args.sequences]
    command = [tool, "--kitti_path=" + os.path.abspath(args.kitti_path),
               "--kitti_models=" + ",".join(models)] + args.gravity_pays_flags
    print(" ".join(command), flush=True)
    sys.exit(subprocess.run(command).returncode)


if __name__ == "__main__":
    main()
