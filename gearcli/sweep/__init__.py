"""``gearcli sweep``: operating-range and tolerance studies (docs/sweeps.md).

- ``spec``          ``--vary`` grids, ``--random`` samples (Latin hypercube / Monte Carlo), points, branches
- ``columns``       the output columns and the one mapping from a simulation result to a row
- ``continuation``  a continued point's initial state from the previous point's final state
- ``worker``        the points of one task (any process: local, pool, Dask worker), evaluated by the
                    injected ``PointEvaluator`` (:func:`gearcli.api.evaluate_point`)
- ``execute``       planning tasks (batches, branches, resume) and running them in this process, a local
                    process pool, or a Dask distributed cluster; rows in order of completion
- ``modes``         natural frequencies against the swept speed (Campbell diagram)

The core never prints: the CLI shows progress and :mod:`gearcli.io.sweep_file` writes the rows.
"""

from gearcli.sweep.columns import columns
from gearcli.sweep.execute import execute, plan
from gearcli.sweep.spec import SweepSpec, SweepUsageError, spec_from_options
from gearcli.sweep.worker import Scene, Task

__all__ = ["Scene", "SweepSpec", "SweepUsageError", "Task", "columns", "execute", "plan", "spec_from_options"]
