"""Scale figures of the Dask triplet pipeline (README.md, "Scale"), on synthetic databases
(trigrav_pipeline.synthetic):

  small: 1 vs 2 worker processes (LocalCluster, one thread each) on a database of
         --small_images images (consecutive triplets), against the single-process calls on the
         same triplets: estimate_partition over all of them (the pipeline's own loop, no Dask) and
         initialize_and_refine_batch(num_threads=1 and 2) on observations built beforehand. Times
         are medians of --repeats runs; the cluster's start (and the workers' import of the pipeline)
         is timed apart. Peak memory: each
         worker process's ru_maxrss after its run (a fresh cluster per run).
  large: one run of --large_images images (100,000 triplets by default) on 2 worker processes:
         database size and writing time, the plan (client, before scheduling), the run, and the
         peak memory of the client and of each worker.

    PYTHONPATH=build/python /usr/bin/python3 -m trigrav_pipeline.measure_scale [--skip_large]
"""

import argparse
import logging
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

import trigrav

from . import pipeline, synthetic


def peak_rss_mb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def local_cluster(workers):
    from dask.distributed import Client, LocalCluster
    start = time.perf_counter()
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                           dashboard_address=None, silence_logs=logging.ERROR)
    client = Client(cluster)
    # The workers import the pipeline (and trigrav) once, as a long-running cluster has.
    client.run(lambda: __import__("trigrav_pipeline.pipeline"))
    return cluster, client, time.perf_counter() - start


def observations_of(the_plan):
    """The ThreeViewObservations of every estimated triplet, as estimate_partition builds them."""
    part = pipeline.partitions(the_plan, len(the_plan.triplets))[0]
    cameras = {cid: trigrav.Camera(m, p) for cid, (m, p) in part.cameras.items()}
    with trigrav.Database(the_plan.database_path) as database:
        keypoints = {i: database.read_keypoints(i) for i in part.images}
        graph = trigrav.MatchGraph(database.read_two_view_geometries())
    result = []
    for triplet in part.triplets:
        ids = [int(i) for i in triplet]
        tracks = trigrav.three_view_tracks(graph, ids)
        if len(tracks) >= the_plan.options.min_tracks:
            result.append(trigrav.ThreeViewObservations(
                pixels=[keypoints[ids[k]][tracks[:, k]] for k in range(3)],
                cameras=[cameras[part.images[i][1]] for i in ids],
                gravity_in_cam=[part.gravity[part.images[i][0]] for i in ids]))
    return result


def measure_small(folder, num_images, repeats):
    database, gravity = os.path.join(folder, "small.db"), os.path.join(folder, "small.csv")
    synthetic.write_synthetic_database(database, gravity, num_images=num_images, seed=11)
    the_plan = pipeline.plan(database, gravity)
    m = len(the_plan.triplets)
    estimator = the_plan.options.estimator_options()
    observations = observations_of(the_plan)
    tracks = statistics.mean(len(o) for o in observations)
    print(f"small database: {num_images} images, {m} triplets, {len(observations)} estimated, "
          f"{tracks:.1f} tracks per triplet")
    rows = []
    # Single process, no Dask.
    part = pipeline.partitions(the_plan, m)[0]
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        pipeline.estimate_partition(database, part, the_plan.options)
        times.append(time.perf_counter() - start)
    rows.append(("one process, estimate_partition (no Dask)", statistics.median(times), None,
                 None))
    for threads in (1, 2):
        times = []
        for _ in range(repeats):
            start = time.perf_counter()
            trigrav.initialize_and_refine_batch(observations, estimator, num_threads=threads)
            times.append(time.perf_counter() - start)
        rows.append((f"one process, initialize_and_refine_batch, {threads} thread(s)",
                     statistics.median(times), None, None))
    baseline = rows[1][1]
    for workers in (1, 2):
        times, starts, peaks = [], [], []
        for r in range(repeats):
            cluster, client, start_s = local_cluster(workers)
            try:
                output = os.path.join(folder, f"small_{workers}_{r}.csv")
                start = time.perf_counter()
                pipeline.run(database, gravity, output, client=client, progress=False)
                times.append(time.perf_counter() - start)
                starts.append(start_s)
                peaks.extend(v / 1024.0 for v in client.run(
                    lambda: resource.getrusage(resource.RUSAGE_SELF).ru_maxrss).values())
            finally:
                client.close()
                cluster.close()
        rows.append((f"Dask LocalCluster, {workers} worker process(es)", statistics.median(times),
                     statistics.median(starts), max(peaks)))
    print()
    print(f"| run ({m} triplets) | wall time (median of {repeats}) | per triplet | "
          f"vs batch, 1 thread | cluster start | peak RSS per worker |")
    print("|---|---|---|---|---|---|")
    for name, seconds, start_s, peak in rows:
        print(f"| {name} | {seconds:.2f} s | {1e3 * seconds / m:.2f} ms | "
              f"{'%+.2f ms' % (1e3 * (seconds - baseline) / m)} ({baseline / seconds:.2f}x) | "
              f"{'-' if start_s is None else '%.1f s' % start_s} | "
              f"{'-' if peak is None else '%.0f MB' % peak} |")
    one, two = rows[3][1], rows[4][1]
    print(f"\nspeed-up 1 -> 2 worker processes: {one / two:.2f}x")
    return rows


def measure_large(folder, num_images, workers):
    database, gravity = os.path.join(folder, "large.db"), os.path.join(folder, "large.csv")
    start = time.perf_counter()
    # In a child process, so that this process's peak memory is the pipeline client's.
    subprocess.run([sys.executable, "-m", "trigrav_pipeline.synthetic", "--database_path",
                    database, "--gravity_csv", gravity, "--num_images", str(num_images),
                    "--seed", "12"], check=True)
    write_s = time.perf_counter() - start
    size_mb = os.path.getsize(database) / 1e6
    start = time.perf_counter()
    the_plan = pipeline.plan(database, gravity)
    plan_s = time.perf_counter() - start
    m = len(the_plan.triplets)
    del the_plan
    cluster, client, start_s = local_cluster(workers)
    try:
        output = os.path.join(folder, "large_triplets.csv")
        report = pipeline.run(database, gravity, output, client=client, progress=True)
        worker_peaks = [v / 1024.0 for v in client.run(
            lambda: resource.getrusage(resource.RUSAGE_SELF).ru_maxrss).values()]
    finally:
        client.close()
        cluster.close()
    print(f"\nlarge database: {num_images} images, {size_mb:.0f} MB, written in {write_s:.0f} s")
    print(f"| triplets | partitions | plan (client) | run on {workers} worker processes | "
          f"per triplet | trusted | peak RSS client | peak RSS per worker |")
    print("|---|---|---|---|---|---|---|---|")
    print(f"| {m} | {report.num_partitions} | {plan_s:.1f} s | {report.seconds:.0f} s "
          f"(cluster start {start_s:.1f} s) | {1e3 * report.seconds / m:.2f} ms | "
          f"{report.num_trusted} | {peak_rss_mb():.0f} MB | "
          f"{', '.join('%.0f MB' % p for p in worker_peaks)} |")
    print(f"CSV: {os.path.getsize(output) / 1e6:.0f} MB")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--small_images", type=int, default=402)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--large_images", type=int, default=100002)
    parser.add_argument("--large_workers", type=int, default=2)
    parser.add_argument("--skip_small", action="store_true")
    parser.add_argument("--skip_large", action="store_true")
    parser.add_argument("--folder", default=None, help="scratch folder (default: a temporary one)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(dir=args.folder) as folder:
        if not args.skip_small:
            measure_small(folder, args.small_images, args.repeats)
        if not args.skip_large:
            measure_large(folder, args.large_images, args.large_workers)


if __name__ == "__main__":
    main()
