"""python3 -m trigrav_pipeline: the triplet stage of a COLMAP database on a Dask cluster (README.md).

    python3 -m trigrav_pipeline --database_path db.db --gravity_csv gravity.csv \\
        --output_csv triplets.csv [--output_model_path seed] [--scheduler tcp://host:8786] \\
        [--workers 2] [triplet_initializer's options]

Exit status: 0 on success; 1 for bad input (a message names it, nothing is scheduled) or, with
--output_model_path, when no triplet is trusted (the CSV is written, no model); 2 for bad flags.
"""

import argparse
import sys

from . import pipeline


def parse(argv):
    defaults = pipeline.TripletOptions()
    parser = argparse.ArgumentParser(
        prog="python3 -m trigrav_pipeline",
        description="The triplet stage of a COLMAP database (triplet_initializer's per-triplet "
        "CSV) on a dask.distributed cluster: a LocalCluster of --workers processes, or the "
        "cluster of --scheduler.")
    add = parser.add_argument
    add("--database_path", required=True, help="COLMAP database (read-only)")
    add("--gravity_csv", required=True, help="gravity per image (image_name,gravity_x,...)")
    add("--output_csv", required=True, help="per-triplet CSV to write (triplet_initializer's)")
    add("--output_model_path", default=None,
        help="also the COLMAP binary model of the best trusted triplet (the tool's seed model)")
    add("--scheduler", default=None,
        help="address of a running dask scheduler (tcp://host:8786); default: a LocalCluster")
    add("--workers", type=int, default=2, help="worker processes of the LocalCluster (2)")
    add("--partition_size", type=int, default=0,
        help="triplets per task (0: about 8 tasks per worker, at most 500)")
    add("--no_progress", action="store_true", help="no progress bar")
    add("--triplets", default=defaults.triplets, choices=["consecutive", "connected"])
    add("--max_triplets", type=int, default=defaults.max_triplets)
    add("--min_tracks", type=int, default=defaults.min_tracks)
    add("--solver", default=defaults.solver)
    add("--threshold_px", type=float, default=defaults.threshold_px,
        help="inlier threshold (px), also the refinement's Huber scale (2)")
    add("--rotation_model", default=defaults.rotation_model, choices=sorted(pipeline.ROTATION_MODELS))
    add("--gravity_sigma_deg", type=float, default=defaults.gravity_sigma_deg)
    add("--engine", default=defaults.engine, choices=sorted(pipeline.ENGINES))
    add("--check_gravity", type=lambda text: text.lower() in ("1", "true", "yes"),
        default=defaults.check_gravity, help="true or false (true)")
    add("--seed", type=int, default=defaults.seed, help="RANSAC seed; triplet i uses seed + i (1)")
    args = parser.parse_args(argv)
    if args.workers < 1:
        parser.error("--workers must be >= 1")
    if args.partition_size < 0:
        parser.error("--partition_size must be >= 0")
    options = pipeline.TripletOptions(
        triplets=args.triplets, max_triplets=args.max_triplets, min_tracks=args.min_tracks,
        solver=args.solver, threshold_px=args.threshold_px, rotation_model=args.rotation_model,
        gravity_sigma_deg=args.gravity_sigma_deg, engine=args.engine,
        check_gravity=args.check_gravity, seed=args.seed)
    try:
        options.check()
    except ValueError as error:
        parser.error(str(error))
    return args, options


def main(argv=None):
    args, options = parse(sys.argv[1:] if argv is None else argv)
    try:
        report = pipeline.run(args.database_path, args.gravity_csv, args.output_csv, options,
                              scheduler=args.scheduler, workers=args.workers,
                              partition_size=args.partition_size,
                              progress=not args.no_progress,
                              output_model_path=args.output_model_path)
    except (ValueError, OSError) as error:
        print(f"error: {error}", file=sys.stderr)
        return 1
    print(f"{report.num_triplets} triplets ({options.triplets}): {report.num_success} estimated, "
          f"{report.num_trusted} trusted; CSV {args.output_csv}; {report.num_partitions} "
          f"partitions ({report.reused_partitions} reused), {report.seconds:.2f} s; worker "
          f"processes {' '.join(str(pid) for pid in sorted(report.worker_pids))}")
    if args.output_model_path is not None:
        if report.best is None:
            print(f"error: no trusted triplet; no model written (reasons in {args.output_csv})",
                  file=sys.stderr)
            return 1
        print(f"seed triplet {report.best[1]} ({report.best[0]} inliers): model "
              f"{args.output_model_path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
