#!/usr/bin/env python3
"""Per-call overhead of the Python module and the speed-up of its batch call.

Overhead: each Python call of trigrav.initialize_and_refine is timed with time.perf_counter and
compared with the C++ call's own wall-clock time, estimate.timings.total_s (taken inside
InitializeAndRefine, from its first to its last statement), on synthetic scenes of --triplets
triplets. Two variants, interleaved call by call: "call" (observations built beforehand) and
"numpy round trip" (observations built from numpy arrays, then the call, then the refined pose and
the inlier mask read back as numpy arrays). Batch: initialize_and_refine_batch on --batch scenes
with num_threads 1 and 2, interleaved, --batch_repeats times.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/measure_overhead.py
"""

import argparse
import statistics
import time

import numpy as np

import trigrav


def quartiles(values):
    q = np.percentile(values, [25, 50, 75])
    return q[1], q[0], q[2]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--triplets", type=int, default=300)
    parser.add_argument("--scenes", type=int, default=20)
    parser.add_argument("--repeats", type=int, default=20, help="calls per scene and variant")
    parser.add_argument("--batch", type=int, default=40, help="scenes of the batch call")
    parser.add_argument("--batch_repeats", type=int, default=7)
    args = parser.parse_args()

    options = trigrav.InitializeAndRefineOptions(
        robust=trigrav.RobustThreeViewOptions(ransac=trigrav.RansacOptions(max_error=1.5, seed=1)))
    scene_options = trigrav.SyntheticSceneOptions(num_points=args.triplets, pixel_noise_px=0.5,
                                                  outlier_ratio=0.2)
    scenes = [trigrav.generate_synthetic_scene(scene_options, seed) for seed in range(args.scenes)]
    inputs = [([np.array(p) for p in s.pixels], s.camera, s.gravity_in_cam_measured)
              for s in scenes]

    relative = {"call": [], "numpy round trip": []}
    absolute = {"call": [], "numpy round trip": []}
    cpp_times = []
    for _ in range(args.repeats):
        for pixels, camera, gravity in inputs:
            observations = trigrav.ThreeViewObservations(pixels=pixels, cameras=camera,
                                                         gravity_in_cam=gravity)
            estimate = None  # the previous result is freed outside the timed region
            start = time.perf_counter()
            estimate = trigrav.initialize_and_refine(observations, options)
            elapsed = time.perf_counter() - start
            overhead = elapsed - estimate.timings.total_s
            absolute["call"].append(overhead)
            relative["call"].append(overhead / estimate.timings.total_s)
            cpp_times.append(estimate.timings.total_s)

            estimate = observations = None
            start = time.perf_counter()
            observations = trigrav.ThreeViewObservations(pixels=pixels, cameras=camera,
                                                         gravity_in_cam=gravity)
            estimate = trigrav.initialize_and_refine(observations, options)
            rotation, inliers = estimate.refined.cam2_from_cam1.R.copy(), estimate.inliers
            elapsed = time.perf_counter() - start
            overhead = elapsed - estimate.timings.total_s
            absolute["numpy round trip"].append(overhead)
            relative["numpy round trip"].append(overhead / estimate.timings.total_s)
            assert estimate.success and rotation.shape == (3, 3) and inliers.any()

    median, q1, q3 = quartiles(cpp_times)
    print(f"initialize_and_refine, {args.triplets} triplets, {args.scenes} scenes x "
          f"{args.repeats} calls per variant (interleaved)")
    print(f"  C++ call (timings.total_s): median {1e3 * median:.2f} ms "
          f"(quartiles {1e3 * q1:.2f}-{1e3 * q3:.2f})")
    for variant in relative:
        median, q1, q3 = quartiles(absolute[variant])
        r_median, r_q1, r_q3 = quartiles(relative[variant])
        print(f"  overhead, {variant}: median {1e6 * median:.1f} us = {100 * r_median:.2f} % of "
              f"the C++ call (quartiles {100 * r_q1:.2f}-{100 * r_q3:.2f} %)")

    batch_scenes = [trigrav.to_observations(trigrav.generate_synthetic_scene(scene_options, seed))
                    for seed in range(args.batch)]
    times = {1: [], 2: []}
    for _ in range(args.batch_repeats):
        for threads in times:
            start = time.perf_counter()
            trigrav.initialize_and_refine_batch(batch_scenes, options, num_threads=threads)
            times[threads].append(time.perf_counter() - start)
    print(f"initialize_and_refine_batch, {args.batch} scenes, {args.batch_repeats} runs each "
          f"(interleaved)")
    for threads, values in times.items():
        print(f"  num_threads={threads}: median {1e3 * statistics.median(values):.1f} ms "
              f"(min {1e3 * min(values):.1f}, max {1e3 * max(values):.1f})")
    print(f"  speed-up 2 vs 1 thread (ratio of medians): "
          f"{statistics.median(times[1]) / statistics.median(times[2]):.2f}")


if __name__ == "__main__":
    main()
