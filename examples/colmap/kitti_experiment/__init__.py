"""Helpers of run_kitti_experiment.py: COLMAP model reading, evaluation against KITTI, report."""
