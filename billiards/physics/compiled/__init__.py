"""The compiled physics (issue 43): the rolling model's event loop in numba, the same
bits as the numpy engine (billiards.physics.engine) operation for operation.

engine.stepper.run_batch sends every run that `supports` names here, the rest to the
numpy engine. numba is imported with this package: by the engine, never by
`import billiards`.
"""

from __future__ import annotations

from billiards.physics.compiled.runner import run_compiled, supports

__all__ = ["run_compiled", "supports"]
