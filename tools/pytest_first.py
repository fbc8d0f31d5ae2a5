"""A pytest plugin (``-p pytest_first``, with this folder on ``sys.path``): the tests whose node ids are the
lines of the environment variable ``PYTEST_FIRST`` start with run first, in that order; every other test keeps its
place after them. The set of tests is unchanged: only their order.

tools/soundness_mutants.py uses it to run the test that killed a mutant last time before the rest, so that
``-x`` stops at once when it kills the mutant again (and the whole default run goes on when it does not).
"""
from __future__ import annotations

import os


def pytest_collection_modifyitems(session, config, items) -> None:
    first = [line for line in os.environ.get("PYTEST_FIRST", "").splitlines() if line.strip()]
    if not first:
        return

    def rank(item) -> int:     # a line may be a node id's start (a parametrisation cut at a space)
        return next((i for i, start in enumerate(first) if item.nodeid.startswith(start)), len(first))
    items.sort(key=rank)       # stable: the rest keep their order
