"""Sweeps: one scene run many times, its inputs varied or its cue ball nudged, on a
Dask cluster (`python -m billiards.sweep`). Dask only here, behind the `sweep` extra.

Floors, bottom up: variations (which scene numbers change, and run i's values), runs
(run i -> one row), records (rows -> runs.csv lines and running statistics), folder
(output written whole), pictures, cluster (where batches of runs are computed), and
the command (__main__).
"""
