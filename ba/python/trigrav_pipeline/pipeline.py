"""The triplet stage of a COLMAP database (what examples/colmap/triplet_initializer runs) split into
partitions of consecutive triplets and estimated on a dask.distributed cluster.

Client (plan): the options are checked; the gravity CSV and the database's cameras and images are
read and its rows' shapes checked (no keypoint or match data is read); the triplets are enumerated
with the library's ConsecutiveTriplets / ConnectedTriplets (connected reads the verified matches,
not the keypoints); every triplet image needs a gravity row. Anything wrong raises ValueError or
FileNotFoundError naming the problem before a task is scheduled.

Workers (estimate_partition): each task opens the database read-only, reads the keypoints of its
partition's images and the verified matches of its triplets' pairs only, builds the library's
MatchGraph and ThreeViewTracks, runs initialize_and_refine on each triplet with the tool's options
and seed (base seed + the triplet's index in the whole run) and returns the partition's CSV text
(format_triplet_csv: the tool's columns and number formatting).

Client (collect): each finished partition is written atomically to <output_csv>.parts/ (a
temporary file, flushed, renamed); once all are there they are merged in triplet order into
<output_csv> (written the same way) and the parts folder is removed. A rerun with the same input
and options reuses the parts already written. A worker that dies loses only its running tasks,
which the scheduler runs again elsewhere; the results are deterministic, so the output is the same.
"""

import dataclasses
import hashlib
import json
import os
import shutil
import tempfile
import time
import uuid

import numpy as np

import trigrav

from . import database_subset

ROTATION_MODELS = {
    "yaw_only": trigrav.ThreeViewBundleAdjustmentOptions.RotationModel.YAW_ONLY,
    "gravity_prior": trigrav.ThreeViewBundleAdjustmentOptions.RotationModel.GRAVITY_PRIOR,
}
ENGINES = {name.lower(): value for name, value in
           trigrav.ThreeViewBundleAdjustmentOptions.Engine.__members__.items()}


@dataclasses.dataclass
class TripletOptions:
    """triplet_initializer's flags of the same names and defaults (examples/colmap/README.md)."""
    triplets: str = "consecutive"  # or "connected"
    max_triplets: int = 0  # 0: no limit
    min_tracks: int = 20
    solver: str = "3pt"
    threshold_px: float = 2.0  # inlier threshold (the tool's --threshold_px)
    rotation_model: str = "gravity_prior"  # or "yaw_only"
    gravity_sigma_deg: float = 0.1
    engine: str = trigrav.ThreeViewBundleAdjustmentOptions().engine.name.lower()
    check_gravity: bool = True
    seed: int = 1

    def check(self):
        """ValueError naming the first bad option, as the tool's flag checks."""
        def require(ok, message):
            if not ok:
                raise ValueError(message)
        require(self.triplets in ("consecutive", "connected"),
                "triplets must be consecutive or connected")
        require(self.max_triplets >= 0, "max_triplets must be >= 0")
        require(self.min_tracks >= 3, "min_tracks must be >= 3")
        require(np.isfinite(self.threshold_px) and self.threshold_px > 0,
                "threshold_px must be positive and finite")
        require(self.rotation_model in ROTATION_MODELS,
                "rotation_model must be yaw_only or gravity_prior")
        require(np.isfinite(self.gravity_sigma_deg) and self.gravity_sigma_deg > 0,
                "gravity_sigma_deg must be positive and finite")
        require(self.engine in ENGINES, "engine must be " + " or ".join(ENGINES))
        require(0 <= self.seed < 2 ** 64, "seed must be in [0, 2^64)")
        trigrav.InitialSolver.from_short_name(self.solver)  # ValueError naming the solvers
        self.estimator_options()

    def estimator_options(self):
        """InitializeAndRefineOptions as triplet_initializer's EstimatorOptions() builds them."""
        options = trigrav.InitializeAndRefineOptions()
        options.robust.solver = trigrav.InitialSolver.from_short_name(self.solver)
        options.robust.ransac.max_error = self.threshold_px
        options.robust.check_gravity_after_success = self.check_gravity
        ba = options.bundle_adjustment
        ba.rotation_model = ROTATION_MODELS[self.rotation_model]
        ba.gravity_sigma_deg = self.gravity_sigma_deg
        ba.loss_scale_px = self.threshold_px
        ba.engine = ENGINES[self.engine]
        ba.compute_covariance = True
        # The Check() of the C++ options, through the keyword constructor.
        trigrav.InitializeAndRefineOptions(robust=options.robust, refine=options.refine,
                                           reclassification_rounds=options.reclassification_rounds,
                                           bundle_adjustment=options.bundle_adjustment)
        return options


@dataclasses.dataclass
class Plan:
    """What the client knows before scheduling: the triplets (M x 3 image ids) and, for their
    images only, name, camera (COLMAP model name and parameters) and gravity."""
    database_path: str
    options: TripletOptions
    triplets: np.ndarray
    images: dict  # image_id -> (name, camera_id)
    cameras: dict  # camera_id -> (model, params)
    gravity: dict  # image name -> (gx, gy, gz)

    def fingerprint(self):
        """Identifies the run's input and options (partial results are reused only when equal)."""
        stat = os.stat(self.database_path)
        text = json.dumps([os.path.abspath(self.database_path), stat.st_size, stat.st_mtime_ns,
                           dataclasses.asdict(self.options), self.triplets.tolist(),
                           sorted(self.gravity.items())], default=str)
        return hashlib.sha256(text.encode()).hexdigest()


def plan(database_path, gravity_csv, options=None):
    """Checks everything the run needs and enumerates the triplets, as triplet_initializer does
    before estimating. FileNotFoundError for a missing file; ValueError naming the problem."""
    options = options or TripletOptions()
    options.check()
    gravity = trigrav.read_gravity_csv(gravity_csv)
    with trigrav.Database(database_path) as database:
        cameras = database.read_cameras()
        images = sorted(database.read_images(), key=lambda image: image.name)
        database_subset.check_database_rows(database_path)
        ids_by_name = np.array([image.image_id for image in images], dtype=np.uint32)
        max_triplets = options.max_triplets if options.max_triplets > 0 else len(images)
        if options.triplets == "consecutive":
            triplets = trigrav.consecutive_triplets(ids_by_name)
        else:
            graph = trigrav.MatchGraph(database.read_two_view_geometries())
            triplets = trigrav.connected_triplets(graph, ids_by_name, max(max_triplets, 1))
            del graph
    triplets = triplets[:max_triplets]
    if len(triplets) == 0:
        raise ValueError(f"no triplet of images in {database_path}")
    image_of_id = {image.image_id: image for image in images}
    used = np.unique(triplets)
    names = [image_of_id[int(i)].name for i in used]
    vectors = trigrav.gravity_of_images(gravity, names)  # ValueError naming the missing ones
    camera_of_id = {c.camera_id: (c.camera.model, list(c.camera.params)) for c in cameras}
    for i in used:
        image = image_of_id[int(i)]
        if image.camera_id not in camera_of_id:
            raise ValueError(f"{database_path}: image {image.name} has camera_id "
                             f"{image.camera_id}, not among the cameras")
    return Plan(database_path=database_path, options=options, triplets=triplets,
                images={int(i): (image_of_id[int(i)].name, image_of_id[int(i)].camera_id)
                        for i in used},
                cameras={cid: camera_of_id[cid] for cid in
                         {image_of_id[int(i)].camera_id for i in used}},
                gravity={n: tuple(float(x) for x in v) for n, v in zip(names, vectors)})


@dataclasses.dataclass
class Partition:
    """A task's input: consecutive triplets from index `start`, with what the client knows of
    their images (plain data: it is pickled to the workers)."""
    index: int
    start: int
    triplets: np.ndarray
    images: dict
    cameras: dict
    gravity: dict


def partitions(plan_, partition_size):
    """The plan's triplets in chunks of partition_size, each with its images' data."""
    result = []
    for index, start in enumerate(range(0, len(plan_.triplets), partition_size)):
        chunk = plan_.triplets[start:start + partition_size]
        ids = [int(i) for i in np.unique(chunk)]
        images = {i: plan_.images[i] for i in ids}
        result.append(Partition(
            index=index, start=start, triplets=chunk, images=images,
            cameras={cid: plan_.cameras[cid] for cid in {images[i][1] for i in ids}},
            gravity={images[i][0]: plan_.gravity[images[i][0]] for i in ids}))
    return result


def default_partition_size(num_triplets, num_workers):
    """About 8 partitions per worker (a lost task costs little, the scheduler stays lightly
    loaded), between 1 and 500 triplets each."""
    return int(min(500, max(1, -(-num_triplets // (8 * max(1, num_workers))))))


def estimate_partition(database_path, partition, options, delay_s=0.0, keep_results=False):
    """One task: the CSV text of the partition's triplets (format_triplet_csv) and a summary
    {'num_triplets', 'num_success', 'num_trusted', 'best': (num_inliers, index) of the trusted
    triplet with the most inliers or None, 'seconds', 'pid'}. Reads only the partition's keypoints
    and matches. delay_s: a pause before the work (fault-injection tests). keep_results: also the
    TripletResult list (in-process use; bound objects are not picklable)."""
    start_time = time.perf_counter()
    if delay_s > 0:
        time.sleep(delay_s)
    estimator = options.estimator_options()
    cameras = {cid: trigrav.Camera(model, params)
               for cid, (model, params) in partition.cameras.items()}
    keypoints = {}
    with trigrav.Database(database_path) as database:
        for image_id in partition.images:
            keypoints[image_id] = database.read_keypoints(image_id)
    pairs = set()
    for a, b, c in partition.triplets:
        pairs.update({(int(a), int(b)), (int(a), int(c)), (int(b), int(c))})
    graph = trigrav.MatchGraph(database_subset.read_two_view_geometries(database_path, pairs))
    results = []
    best = None
    num_success = num_trusted = 0
    for offset, triplet in enumerate(partition.triplets):
        ids = [int(i) for i in triplet]
        images = [trigrav.DatabaseImage(i, partition.images[i][0], partition.images[i][1])
                  for i in ids]
        tracks = trigrav.three_view_tracks(graph, ids)
        result = trigrav.TripletResult(images, num_tracks=len(tracks))
        if len(tracks) >= options.min_tracks:
            observations = trigrav.ThreeViewObservations(
                pixels=[keypoints[ids[k]][tracks[:, k]] for k in range(3)],
                cameras=[cameras[partition.images[i][1]] for i in ids],
                gravity_in_cam=[partition.gravity[partition.images[i][0]] for i in ids])
            estimator.robust.ransac.seed = options.seed + partition.start + offset
            result.estimate = trigrav.initialize_and_refine(observations, estimator)
            result.estimated = True
        num_success += result.estimate.success
        if result.verdict == "trusted":
            num_trusted += 1
            candidate = (result.estimate.num_inliers, -(partition.start + offset))
            best = candidate if best is None or candidate > best else best
        results.append(result)
    text = trigrav.format_triplet_csv(results, ROTATION_MODELS[options.rotation_model])
    summary = {"num_triplets": len(results), "num_success": num_success,
               "num_trusted": num_trusted,
               "best": None if best is None else (best[0], -best[1]),
               "seconds": time.perf_counter() - start_time, "pid": os.getpid()}
    return (text, summary, results) if keep_results else (text, summary)


# --- output -------------------------------------------------------------------------------------


def write_atomically(path, text):
    """Writes `text` (a string, or a function writing to the file it is given) to a temporary
    sibling, flushes it to the disk, renames it to `path`."""
    folder = os.path.dirname(os.path.abspath(path))
    handle, temporary = tempfile.mkstemp(prefix=os.path.basename(path) + ".", suffix=".tmp",
                                         dir=folder)
    try:
        with os.fdopen(handle, "w") as f:
            if callable(text):
                text(f)
            else:
                f.write(text)
            f.flush()
            os.fsync(f.fileno())
        os.replace(temporary, path)
    except BaseException:
        if os.path.exists(temporary):
            os.unlink(temporary)
        raise
    directory = os.open(folder, os.O_RDONLY)
    try:
        os.fsync(directory)
    finally:
        os.close(directory)


def split_csv(text):
    """(the '#' lines and the header row, the data rows) of format_triplet_csv's text."""
    position = 0
    while text.startswith("#", position):
        position = text.index("\n", position) + 1
    header_end = text.index("\n", position) + 1
    return text[:header_end], text[header_end:]


class PartStore:
    """<output_csv>.parts/: one file per finished partition, a manifest naming the run."""

    def __init__(self, output_csv, fingerprint, num_partitions):
        self.folder = output_csv + ".parts"
        self.num_partitions = num_partitions
        manifest = {"fingerprint": fingerprint, "num_partitions": num_partitions}
        manifest_path = os.path.join(self.folder, "manifest.json")
        if os.path.isdir(self.folder):
            try:
                with open(manifest_path) as f:
                    reusable = json.load(f) == manifest
            except (OSError, ValueError):
                reusable = False
            if not reusable:
                shutil.rmtree(self.folder)
        os.makedirs(self.folder, exist_ok=True)
        if not os.path.exists(manifest_path):
            write_atomically(manifest_path, json.dumps(manifest))

    def path(self, index):
        return os.path.join(self.folder, f"part-{index:06d}.csv")

    def done(self, index):
        return os.path.exists(self.path(index)) and os.path.exists(self.path(index) + ".json")

    def write(self, index, text, summary):
        write_atomically(self.path(index), text)
        write_atomically(self.path(index) + ".json", json.dumps(summary))  # the commit mark

    def summary(self, index):
        with open(self.path(index) + ".json") as f:
            return json.load(f)

    def merge(self, output_csv):
        """The parts in order as one CSV (atomically; one part in memory at a time); then the
        parts folder is removed."""
        def write(out):
            header = None
            for index in range(self.num_partitions):
                with open(self.path(index)) as f:
                    part_header, part_rows = split_csv(f.read())
                if header is None:
                    header = part_header
                    out.write(header)
                elif part_header != header:
                    raise ValueError(f"{self.path(index)}: a different CSV header")
                out.write(part_rows)
        write_atomically(output_csv, write)
        shutil.rmtree(self.folder)


# --- the run ------------------------------------------------------------------------------------


@dataclasses.dataclass
class RunReport:
    num_triplets: int
    num_partitions: int
    num_success: int
    num_trusted: int
    best: object  # (num_inliers, triplet index) or None
    seconds: float
    reused_partitions: int
    worker_pids: list  # the processes that ran this run's partitions
    partition_pids: list  # per partition: the process whose result was kept


def _progress(total, enabled):
    if not enabled:
        return None
    try:
        from tqdm import tqdm
    except ImportError:
        return None
    return tqdm(total=total, unit="triplet", desc="triplets", smoothing=0.1)


def run(database_path, gravity_csv, output_csv, options=None, *, client=None, scheduler=None,
        workers=2, partition_size=0, progress=True, output_model_path=None, delay_s=0.0,
        log=print):
    """The whole triplet stage: plan (fails before scheduling), the partitions on the cluster
    (`client`; else a Client of `scheduler`'s address; else a LocalCluster of `workers` worker
    processes of one thread each), their CSV parts, the merged CSV, and, with output_model_path,
    the seed model of the best trusted triplet as triplet_initializer writes it. Returns a
    RunReport. partition_size 0: default_partition_size."""
    start_time = time.perf_counter()
    options = options or TripletOptions()
    if workers < 1:
        raise ValueError("workers must be >= 1")
    for flag, path in (("output_csv", output_csv), ("output_model_path", output_model_path)):
        if path is not None and os.path.abspath(path) in (os.path.abspath(database_path),
                                                          os.path.abspath(gravity_csv)):
            raise ValueError(f"{flag}={path} is an input")
    if not os.path.isdir(os.path.dirname(os.path.abspath(output_csv))):
        raise FileNotFoundError(f"output_csv={output_csv}: no such folder")
    the_plan = plan(database_path, gravity_csv, options)

    own_cluster = own_client = None
    if client is None:
        from dask.distributed import Client, LocalCluster
        if scheduler:
            client = own_client = Client(scheduler)
        else:
            import logging
            own_cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                       dashboard_address=None, silence_logs=logging.ERROR)
            client = own_client = Client(own_cluster)
    try:
        num_workers = max(1, len(client.scheduler_info().get("workers", {})))
        size = partition_size or default_partition_size(len(the_plan.triplets), num_workers)
        parts = partitions(the_plan, size)
        fingerprint = the_plan.fingerprint()
        store = PartStore(output_csv, fingerprint, len(parts))
        todo = [p for p in parts if not store.done(p.index)]
        bar = _progress(len(the_plan.triplets), progress)
        if bar is not None:
            bar.update(sum(len(p.triplets) for p in parts if store.done(p.index)))
        pids = set()
        if todo:
            from dask.distributed import as_completed
            run_id = uuid.uuid4().hex[:12]  # keys of this run only (no result of another run)
            futures = client.map(estimate_partition, [database_path] * len(todo), todo,
                                 [options] * len(todo), [delay_s] * len(todo),
                                 key=[f"trigrav-triplets-{run_id}-{p.index}"
                                      for p in todo])
            index_of = {f.key: p.index for f, p in zip(futures, todo)}
            try:
                for future in as_completed(futures):
                    text, summary = future.result()
                    store.write(index_of[future.key], text, summary)
                    # Written: the scheduler may forget it (neither client nor worker keeps it).
                    future.release()
                    del text
                    pids.add(summary["pid"])
                    if bar is not None:
                        bar.update(summary["num_triplets"])
            except BaseException:
                client.cancel(futures)
                raise
        if bar is not None:
            bar.close()
        summaries = [store.summary(p.index) for p in parts]
        best = None
        for s in summaries:
            if s["best"] is not None:
                candidate = (s["best"][0], -s["best"][1])
                best = candidate if best is None or candidate > best else best
        best = None if best is None else (best[0], -best[1])
        if output_model_path is not None and best is not None:
            write_seed_model(the_plan, best[1], output_model_path)
        store.merge(output_csv)
        return RunReport(num_triplets=len(the_plan.triplets), num_partitions=len(parts),
                         num_success=sum(s["num_success"] for s in summaries),
                         num_trusted=sum(s["num_trusted"] for s in summaries), best=best,
                         seconds=time.perf_counter() - start_time,
                         reused_partitions=len(parts) - len(todo), worker_pids=sorted(pids),
                         partition_pids=[s["pid"] for s in summaries])
    finally:
        if own_client is not None:
            own_client.close()
        if own_cluster is not None:
            own_cluster.close()


def write_seed_model(the_plan, triplet_index, output_model_path):
    """The seed model of one triplet (TripletModel), written as COLMAP binary like the tool's
    --output_model_path; the triplet is estimated again (the same seed gives the same result)."""
    one = partitions(dataclasses.replace(the_plan, triplets=the_plan.triplets[
        triplet_index:triplet_index + 1]), 1)[0]
    one.start = triplet_index
    _, _, results = estimate_partition(the_plan.database_path, one, the_plan.options,
                                       keep_results=True)
    ids = [int(i) for i in one.triplets[0]]
    with trigrav.Database(the_plan.database_path) as database:
        cameras = database.read_cameras()
        keypoints = [database.read_keypoints(i) for i in ids]
    pairs = {(ids[0], ids[1]), (ids[0], ids[2]), (ids[1], ids[2])}
    graph = trigrav.MatchGraph(
        database_subset.read_two_view_geometries(the_plan.database_path, pairs))
    tracks = trigrav.three_view_tracks(graph, ids)
    model = trigrav.triplet_model(cameras, results[0].images, keypoints, tracks,
                                  results[0].estimate)
    trigrav.write_model(model, output_model_path, trigrav.ModelFormat.BINARY,
                        create_parents=True)
    return model
