"""Re-run mutmut's survivors, each in a fresh process.

    python tools/mutmut_fresh.py MUTMUT_DIR OUT.jsonl [--only] [--first TEST_FILE ...] [MUTANT ...]

Why: mutmut 3 runs each mutant in a process forked from one that has already imported the test
modules, so work done at import time (module-level certificates, caches filled during collection)
was done by the unmutated code, and a mutant of code reached only there is reported "survived"
although the tests kill it (measured: ``g = None`` in ``isolate_polynomial``, which crashes every
eigenfrequency proof, was reported a survivor). This runs ``pytest -x`` on the tests mutmut maps to
the mutant (``mutmut tests-for-mutant``), file by file (the cheap files first), in a new interpreter
with ``MUTANT_UNDER_TEST`` set, inside MUTMUT_DIR/mutants, and appends one JSON line per mutant to
OUT.jsonl: {"name", "verdict": killed | survived | timeout, "by": the first failing test, "tests",
"s"}. Mutants already in OUT.jsonl are skipped (the run resumes). Default: every mutant ``mutmut
results`` lists as survived. ``--first TEST_FILE`` runs that whole file first for every mutant (a
test file written after mutmut's stats run, which ``tests-for-mutant`` does not know); with
``--only``, those files are all that runs (a quick pass over many survivors with the fast files
aimed at them: a "survived" then means "not killed by these files"). Asserts nothing; a killed
verdict needs a failing test, as in mutmut.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import time

#: test files in the order they are tried (fast ones first); others after them
ORDER = ["tests/test_balls.py", "tests/test_roots.py", "tests/test_subdivision.py", "tests/test_exact.py",
         "tests/test_lyapunov_memo.py", "tests/test_eigfreq.py", "tests/test_sublevel.py", "tests/test_lyapunov.py",
         "tests/test_review_regressions.py", "tests/test_corpus.py", "tests/test_check.py"]
TIMEOUT_S = 400


def survivors(root: str) -> list[str]:
    r = subprocess.run(["mutmut", "results"], cwd=root, capture_output=True, text=True, check=True)
    return [line.split(":")[0].strip() for line in r.stdout.splitlines() if line.strip().endswith("survived")]


def run_one(root: str, name: str, first: list[str] = (), only: bool = False) -> dict:
    tests = []
    if not only:
        r = subprocess.run(["mutmut", "tests-for-mutant", name], cwd=root, capture_output=True, text=True, check=True)
        tests = [t.strip() for t in r.stdout.splitlines() if t.strip().startswith("tests/")]
    tests = [t for t in tests if t.split("::")[0] not in first] + list(first)
    files = list(first) + sorted({t.split("::")[0] for t in tests if t not in first},
                                 key=lambda f: ORDER.index(f) if f in ORDER else len(ORDER))
    verdict, by, t0 = "survived", None, time.time()
    env = dict(os.environ, MUTANT_UNDER_TEST=name)
    for f in files:
        ids = [f] if f in first else [t for t in tests if t.startswith(f + "::")]
        try:
            p = subprocess.run([sys.executable, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider"] + ids,
                               cwd=os.path.join(root, "mutants"), env=env, capture_output=True, text=True,
                               timeout=TIMEOUT_S)
        except subprocess.TimeoutExpired:
            verdict, by = "timeout", f
            break
        if p.returncode != 0:
            verdict = "killed"
            by = next((line.split()[1] for line in p.stdout.splitlines() if line.startswith(("FAILED", "ERROR"))), f)
            break
    return {"name": name, "verdict": verdict, "by": by, "tests": len(tests), "s": round(time.time() - t0, 1)}


def main() -> int:
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    root, out, rest = sys.argv[1], sys.argv[2], sys.argv[3:]
    only = rest[:1] == ["--only"]
    rest = rest[1:] if only else rest
    first = []
    while rest[:1] == ["--first"] and len(rest) >= 2:
        first.append(rest[1])
        rest = rest[2:]
    names = rest or survivors(root)
    done = set()
    if os.path.exists(out):
        with open(out) as fh:
            done = {json.loads(line)["name"] for line in fh if line.strip()}
    for name in names:
        if name in done:
            continue
        rec = run_one(root, name, first, only)
        print(json.dumps(rec), flush=True)
        with open(out, "a") as fh:
            fh.write(json.dumps(rec) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
