#!/usr/bin/env python3
"""Writes the seed corpus of the fuzz harnesses into corpus/<harness>/ (run from anywhere).

The byte layouts are those the harnesses decode (fuzz_input.h, fuzz_scene.h, solvers_fuzzer.cc,
robust_fuzzer.cc): each seed is a valid synthetic scene of one kind (size, yaw range, zero baseline,
noise, outliers, IMU noise, wide lens, strong tilt), some with one edit of each kind, plus a few raw
problems. libFuzzer mutates from there.
"""
import itertools
import pathlib
import struct

HERE = pathlib.Path(__file__).resolve().parent

# Scene flag bits (fuzz_scene.h): yaw range in bits 0-1, then the options.
YAW90, YAW180, ZERO_BASELINE, NOISE, OUTLIERS, IMU_NOISE, WIDE, TILT = 1, 2, 4, 8, 16, 32, 64, 128
SCENE_KINDS = [0, YAW90, YAW180, 3, ZERO_BASELINE, NOISE, NOISE | IMU_NOISE, WIDE | TILT,
               YAW180 | NOISE | TILT, NOISE | OUTLIERS]


def special(index):
    """Double() tag for the index-th special value (NaN, +Inf, -Inf, 0, ...)."""
    return bytes([4 * index])


def fixed(value):
    """Double() encoding of a value in [-8, 8) on a 1/4096 grid."""
    raw = int(round(value * 4096)) + 32768
    return bytes([1, raw >> 8, raw & 255])


def edits(kind):
    """A count byte and one edit (fuzz_scene.h ApplyEdits) of the given kind, or none."""
    if kind is None:
        return bytes([0])
    operands = {
        0: bytes([0, 1, 2]) + special(0),       # view 1, point 1, entry 2 := NaN
        1: bytes([1]) + special(3),             # gravity of view 2, entry 0 := 0
        2: bytes([0, 1]),                       # triplet 1 := triplet 0
        3: b"",                                 # view loses a point
        4: fixed(0.5) + fixed(-0.25) + fixed(1.0),
        5: bytes([2]) + special(7),             # point 2 scaled by the largest double
        6: bytes([0]),                          # view := view 1
        7: bytes([0, 1, 2]) + fixed(0.5),       # point 1 midway between 0 and 2
    }[kind]
    view = 1
    return bytes([1, kind, view]) + operands


def solvers_seeds():
    seeds = []
    for kind, size in zip(SCENE_KINDS, itertools.cycle([0, 1, 2, 4, 5, 9])):
        # mode 0 (scene), flags, size (3 + byte % 10), seed, no edit, 4-point options (defaults).
        seeds.append(bytes([0, kind, size]) + struct.pack(">I", 1000 + kind) + edits(None) +
                     bytes([0, 0, 0, 1]))
    for kind in range(8):
        seeds.append(bytes([0, NOISE, 5]) + struct.pack(">I", 7) + edits(kind) + bytes([kind % 3, 0, 1, 1]))
    # Raw problems: 4 equal rays per view of small fixed-point numbers; then with special values.
    raw = bytes([1, 0, 4]) + b"".join(fixed(v) for v in [0.1, -0.2, 1.0] * 12 + [0.0, 1.0, 0.0] * 3)
    seeds.append(raw + edits(None) + bytes([0, 0, 0, 1]))
    seeds.append(bytes([1, 0, 3]) + b"".join(special(i % 16) for i in range(36)) + edits(None))
    return seeds


def robust_seeds():
    seeds = []
    for solver in range(6):
        for kind, size in [(NOISE | OUTLIERS, 30), (NOISE, 12), (YAW180 | NOISE | OUTLIERS, 40)]:
            # solver, max_error 2 px, confidence 0.9999, min 10 / max 64 iterations, seed, LO on,
            # 3 rounds, multiplier 3; scene mode, flags, size (1 + byte % 40), seed, no edits, no
            # camera edits.
            options = bytes([solver, 1, 1, 12, 65]) + struct.pack(">I", solver) + bytes([1, 4, 1])
            scene = bytes([0, kind, size - 1]) + struct.pack(">I", 100 * solver + size)
            seeds.append(options + scene + edits(None) + bytes([0]))
    options = bytes([0, 1, 1, 12, 65]) + struct.pack(">I", 0) + bytes([1, 4, 1])
    for kind in range(8):
        scene = bytes([0, NOISE | OUTLIERS, 19]) + struct.pack(">I", kind)
        seeds.append(options + scene + edits(kind) + bytes([0]))
    # One camera edit: fx := 0 (invalid), then fx := 1e-300 (valid, tiny).
    scene = bytes([0, NOISE, 19]) + struct.pack(">I", 3) + edits(None)
    seeds.append(options + scene + bytes([1, 0, 0]) + special(3))
    seeds.append(options + scene + bytes([1, 0, 0]) + special(10))
    # Gravity from an IMU (1 deg per camera) with the tilt-correcting local optimisation: 3pt,
    # sextic and 4pt with max_tilt_correction_deg = 5 (the last byte), then a NaN bound (invalid).
    for solver in range(3):
        options = bytes([solver, 1, 1, 12, 65]) + struct.pack(">I", solver) + bytes([1, 4, 1])
        scene = bytes([0, NOISE | OUTLIERS | IMU_NOISE, 29]) + struct.pack(">I", 500)
        seeds.append(options + scene + edits(None) + bytes([0, 2]))
    seeds.append(options + scene + edits(None) + bytes([0, 4]) + special(0))
    return seeds


def main():
    for harness, seeds in [("solvers_fuzzer", solvers_seeds()), ("robust_fuzzer", robust_seeds())]:
        directory = HERE / "corpus" / harness
        directory.mkdir(parents=True, exist_ok=True)
        for old in directory.glob("seed_*"):
            old.unlink()
        for index, seed in enumerate(seeds):
            (directory / f"seed_{index:03d}").write_bytes(seed)
        print(f"{directory}: {len(seeds)} seeds")


if __name__ == "__main__":
    main()
