"""The compiled physics (issue 43): the rolling model's event loop in numba, the same
bits as the numpy engine (billiards.physics.engine) operation for operation.

methods.entry.run_batch sends every run that runner.supports names to runner.
run_compiled, the rest to the numpy engine. numba is imported with the kernels'
modules (jit), by the engine only: neither `import billiards` nor this package's
`notice` (the commands' --quiet) loads it.
"""
