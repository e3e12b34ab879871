"""The compiled physics (issue 43): the event loop in numba for both motion models (the
rolling model's motion and times; the spin model's: spin_motion, spin_times, held),
one loop and calendar choosing a run's model and laws by number, the same bits as the
numpy engine (billiards.physics.engine) operation for operation.

methods.entry.run_batch sends every run that runner.supports names to runner.
run_compiled, the rest to the numpy engine. numba is imported with the kernels'
modules (jit), by the engine only: neither `import billiards` nor this package's
`notice` (the commands' --quiet) loads it.
"""
