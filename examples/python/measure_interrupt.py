"""How long Ctrl-C takes to end trigrav's long Python calls: the seconds from a signal (SIGALRM
with a handler that raises, as SIGINT's raises KeyboardInterrupt) to the exception, for
initialize_and_refine interrupted within its RANSAC and within its refinement, and for a batch.
Prints the median and the range over --repetitions interrupts at evenly spread moments of each
stage, per scene size."""

import argparse
import signal
import statistics
import time

import trigrav


class Interrupted(Exception):
    pass


def latency_s(call, delay_s):
    fired = {}

    def handler(signum, frame):
        fired["at"] = time.monotonic()
        raise Interrupted()

    previous = signal.signal(signal.SIGALRM, handler)
    signal.setitimer(signal.ITIMER_REAL, delay_s)
    try:
        call()
        return None  # finished before the signal
    except Interrupted:
        return time.monotonic() - fired["at"]
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(signal.SIGALRM, previous)


def scene(num_points, seed=1):
    options = trigrav.SyntheticSceneOptions(num_points=num_points, pixel_noise_px=0.5,
                                            outlier_ratio=0.2)
    return trigrav.to_observations(trigrav.generate_synthetic_scene(options, seed))


def summary(name, values):
    values = [v for v in values if v is not None]
    if not values:
        return f"{name}: the call always finished first"
    return (f"{name}: median {1e3 * statistics.median(values):.0f} ms "
            f"(range {1e3 * min(values):.0f}-{1e3 * max(values):.0f} ms, {len(values)} interrupts)")


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--sizes", type=int, nargs="+", default=[10000, 100000, 300000],
                        help="triplets per call (10000 100000 300000)")
    parser.add_argument("--repetitions", type=int, default=5, help="interrupts per stage (5)")
    parser.add_argument("--threads", type=int, default=2, help="threads of the batch (2)")
    args = parser.parse_args()
    for size in args.sizes:
        observations = scene(size)
        timings = trigrav.initialize_and_refine(observations).timings
        print(f"{size} triplets: RANSAC {timings.ransac_s:.2f} s, refinement "
              f"{timings.refinement_s:.2f} s")
        call = lambda: trigrav.initialize_and_refine(observations)
        spread = [(r + 0.5) / args.repetitions for r in range(args.repetitions)]
        print("  " + summary("in RANSAC", [latency_s(call, f * timings.ransac_s) for f in spread]))
        print("  " + summary("in the refinement", [
            latency_s(call, timings.ransac_s + f * timings.refinement_s) for f in spread]))
    batch = [scene(400, seed) for seed in range(8)] * 100
    start = time.monotonic()
    trigrav.initialize_and_refine_batch(batch, num_threads=args.threads)
    batch_s = time.monotonic() - start
    print(f"batch of {len(batch)} calls of 400 triplets on {args.threads} threads: {batch_s:.2f} s")
    call = lambda: trigrav.initialize_and_refine_batch(batch, num_threads=args.threads)
    print("  " + summary("in the batch", [
        latency_s(call, (r + 0.5) / args.repetitions * batch_s) for r in range(args.repetitions)]))


if __name__ == "__main__":
    main()
