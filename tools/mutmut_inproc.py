"""Run chosen test functions against many mutmut mutants in ONE interpreter.

    python tools/mutmut_inproc.py MUTMUT_DIR TEST_FILE NAMES_FILE TEST [TEST ...] > OUT.tsv
    python tools/mutmut_inproc.py MUTMUT_DIR --pytest NAMES_FILE PYTEST_ARG [...] > OUT.tsv
    python tools/mutmut_inproc.py MUTMUT_DIR --module tests.MODULE NAMES_FILE [SUBSTRING ...] > OUT.tsv

mutmut's trampolines read ``MUTANT_UNDER_TEST`` at every call, so one process can switch mutants
between runs of the tests: no fork, no import of the mutated modules per mutant (15 s each for the
big Lyapunov modules in mutmut's folder), no test collection. Each mutant costs only its tests' time.

It is sound only for tests that build everything they check afresh: a test that reads a module-level
cache, a ``scope="module"`` fixture or anything computed at import would see the unmutated code's
values (the flaw of mutmut's own runner noted in proofs/mutation.md section 5). Fixtures supported:
``monkeypatch`` and ``tmp_path``; no parametrisation (wrap a parametrised test in a plain function).
With ``--pytest`` the PYTEST_ARGs (node ids, ``-k EXPR``) go to ``pytest.main`` once per mutant in
the same process (any fixture, parametrised tests; about a second more per mutant for collection;
test modules are imported once, so the same caveat holds for work they do at import). With
``--module`` the test functions of a test module (those whose names contain a SUBSTRING, all without
one; ``slow`` ones left out) run in file order, each parametrisation expanded, and **its own fixtures
computed once, by the unmutated code**, then deep-copied into every call: much faster than pytest for
files whose module fixtures prove a scene, and sound only for mutants of code those fixtures do not run
(a checker's mutants against certificates the prover made).

The unmutated code must pass first (else it stops). Prints ``name<TAB>killed|survived|timeout`` per
mutant (NAMES_FILE: mutmut's full names, one per line); any exception or failed assert is a kill, as
in pytest; a mutant still running after TIMEOUT_S seconds is a timeout.
"""
from __future__ import annotations

import contextlib
import importlib.util
import io
import inspect
import os
import pathlib
import signal
import sys
import tempfile

#: seconds before a mutant counts as a timeout (environment: MUTMUT_INPROC_TIMEOUT)
TIMEOUT_S = int(os.environ.get("MUTMUT_INPROC_TIMEOUT", "120"))


class _Timeout(Exception):
    pass


#: set when the alarm fired: under ``--pytest`` the _Timeout is raised inside a test, where pytest reports
#: it as a failure (exit 1), so the exception alone would make a timeout look like a kill
_timed_out = False


def _alarm(*_):
    global _timed_out
    _timed_out = True
    raise _Timeout()


def main(argv: list[str]) -> int:
    if len(argv) < 4:
        print(__doc__, file=sys.stderr)
        return 2
    root, test_file, names_file, *tests = argv
    os.chdir(os.path.join(root, "mutants"))
    sys.path.insert(0, os.getcwd())        # the mutated package before any installed copy
    import pytest
    if test_file == "--pytest":
        args = ["-x", "-q", "-p", "no:cacheprovider", "-p", "no:randomly", *tests]

        def run_all() -> None:
            with contextlib.redirect_stdout(io.StringIO()):        # pytest's report; ours is the TSV
                code = pytest.main(args)
            if code != 0:
                raise AssertionError(f"pytest exit {code}")
        return _loop(run_all, names_file)
    if test_file == "--module":
        return _loop(_module_runner(names_file, tests[1:]), tests[0])
    spec = importlib.util.spec_from_file_location("mutmut_inproc_tests", test_file)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    functions = [getattr(module, t) for t in tests]

    def run_all() -> None:
        for fn in functions:
            kw, mp = {}, pytest.MonkeyPatch()
            for p in inspect.signature(fn).parameters:
                if p == "monkeypatch":
                    kw[p] = mp
                elif p == "tmp_path":
                    kw[p] = pathlib.Path(tempfile.mkdtemp())
                else:
                    raise SystemExit(f"{fn.__name__}: fixture {p!r} is not supported")
            try:
                fn(**kw)
            finally:
                mp.undo()

    return _loop(run_all, names_file)


def _module_runner(dotted: str, substrings: list[str]):
    """run_all for ``--module``: the module's tests, parametrisations expanded, its fixtures memoised."""
    import copy
    import importlib
    import itertools

    import pytest
    module = importlib.import_module(dotted)
    fixtures = {n: f for n, f in vars(module).items() if hasattr(f, "_get_wrapped_function")}
    memo: dict = {}

    def fixture(name: str, mp):
        if name == "monkeypatch":
            return mp
        if name == "tmp_path":
            return pathlib.Path(tempfile.mkdtemp())
        if name not in fixtures:
            raise SystemExit(f"fixture {name!r} is not supported")
        if name not in memo:            # first asked in the unmutated run (see _loop)
            fn = fixtures[name]._get_wrapped_function()
            with pytest.MonkeyPatch.context() as own:
                memo[name] = fn(**{p: fixture(p, own) for p in inspect.signature(fn).parameters})
        return copy.deepcopy(memo[name])

    calls = []
    for name, fn in vars(module).items():
        if not (name.startswith("test_") and callable(fn)) or (substrings and not any(s in name for s in substrings)):
            continue
        marks = getattr(fn, "pytestmark", [])
        if any(m.name == "slow" for m in marks):
            continue
        grids = []
        for m in marks:
            if m.name == "parametrize":
                names = [a.strip() for a in m.args[0].split(",")] if isinstance(m.args[0], str) else list(m.args[0])
                rows = [tuple(v.values) if type(v).__name__ == "ParameterSet" else v if len(names) > 1 else (v,)
                        for v in m.args[1]]     # pytest.param(...) unwrapped (a dict has .values too)
                grids.append([dict(zip(names, r)) for r in rows])
        for combo in itertools.product(*grids):
            calls.append((fn, {k: v for d in combo for k, v in d.items()}))

    def run_all() -> None:
        for fn, params in calls:
            with pytest.MonkeyPatch.context() as mp:
                kw = {p: params[p] if p in params else fixture(p, mp) for p in inspect.signature(fn).parameters}
                fn(**kw)
    return run_all


def _loop(run_all, names_file: str) -> int:
    signal.signal(signal.SIGALRM, _alarm)
    os.environ["MUTANT_UNDER_TEST"] = ""
    run_all()                               # the unmutated code passes, or nothing is measured
    global _timed_out
    for name in open(names_file).read().split():
        os.environ["MUTANT_UNDER_TEST"] = name
        _timed_out = False
        signal.alarm(TIMEOUT_S)
        try:
            run_all()
            verdict = "survived"
        except _Timeout:
            verdict = "timeout"
        except KeyboardInterrupt:
            raise
        except BaseException:               # noqa: BLE001 - a failing test of any kind kills the mutant
            verdict = "killed"
        finally:
            signal.alarm(0)
        if _timed_out:                      # whatever pytest made of it: not a kill
            verdict = "timeout"
        print(f"{name}\t{verdict}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
