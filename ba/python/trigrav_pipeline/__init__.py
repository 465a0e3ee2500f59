"""trigrav_pipeline: the triplet stage of a COLMAP database (examples/colmap/triplet_initializer's
per-triplet CSV) on a dask.distributed cluster, on top of the trigrav module. README.md beside
this file; the command: python3 -m trigrav_pipeline --help."""

from .pipeline import (Partition, Plan, RunReport, TripletOptions, default_partition_size,
                       estimate_partition, partitions, plan, run, split_csv, write_seed_model)

__all__ = ["Partition", "Plan", "RunReport", "TripletOptions", "default_partition_size",
           "estimate_partition", "partitions", "plan", "run", "split_csv", "write_seed_model"]
