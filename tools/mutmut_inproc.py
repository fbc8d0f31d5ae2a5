"""Run chosen test functions against many mutmut mutants in ONE interpreter.

    python tools/mutmut_inproc.py MUTMUT_DIR TEST_FILE NAMES_FILE TEST [TEST ...] > OUT.tsv
    python tools/mutmut_inproc.py MUTMUT_DIR --pytest NAMES_FILE PYTEST_ARG [...] > OUT.tsv

mutmut's trampolines read ``MUTANT_UNDER_TEST`` at every call, so one process can switch mutants
between runs of the tests: no fork, no import of the mutated modules per mutant (15 s each for the
big Lyapunov modules in mutmut's folder), no test collection. Each mutant costs only its tests' time.

It is sound only for tests that build everything they check afresh: a test that reads a module-level
cache, a ``scope="module"`` fixture or anything computed at import would see the unmutated code's
values (the flaw of mutmut's own runner noted in proofs/mutation.md section 5). Fixtures supported:
``monkeypatch`` and ``tmp_path``; no parametrisation (wrap a parametrised test in a plain function).
With ``--pytest`` the PYTEST_ARGs (node ids, ``-k EXPR``) go to ``pytest.main`` once per mutant in
the same process (any fixture, parametrised tests; about a second more per mutant for collection;
test modules are imported once, so the same caveat holds for work they do at import).

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


def _alarm(*_):
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


def _loop(run_all, names_file: str) -> int:
    signal.signal(signal.SIGALRM, _alarm)
    os.environ["MUTANT_UNDER_TEST"] = ""
    run_all()                               # the unmutated code passes, or nothing is measured
    for name in open(names_file).read().split():
        os.environ["MUTANT_UNDER_TEST"] = name
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
        print(f"{name}\t{verdict}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
