"""Small bounded memos of pure computations keyed by their exact inputs (what the points of a sweep share: the same
chain's linearisation, eigenproblem, damping ratios), shared by the threads of a process."""

from __future__ import annotations

from collections.abc import Hashable
from typing import TypeVar

V = TypeVar("V")


def remember(memo: dict, key: Hashable, value: V, cap: int = 16) -> V:
    """Store ``value`` under ``key`` in ``memo``, which keeps at most ``cap`` entries (the oldest dropped first), and
    return it. Threads may share the memo: a lost race only drops or recomputes an entry, never a wrong value."""
    while len(memo) >= cap:
        try:
            memo.pop(next(iter(memo)), None)
        except (StopIteration, RuntimeError):  # emptied, or changed under the iteration by another thread
            break
    memo[key] = value
    return value
