"""Command line: ``rigor-gyro list`` and ``rigor-gyro prove SCENE... | --all``.

Exit status: 0 every claim proved; 1 some claim refuted (a certified counterexample); 3 some claim
inconclusive (none refuted); 2 bad input or usage (one line naming the parameter, key or option and
what is allowed; nothing is proved or written); 4 an internal error (a bug: one line, the traceback
with ``--debug``). A crash is never 1. When several scenes are proved, the worst status wins, in the
order 4, 2, 1, 3, 0.
"""
from __future__ import annotations

import argparse
import os
import sys
import tempfile
import traceback
from pathlib import Path

from .core.balls import DEFAULT_MAXPREC, DEFAULT_PREC, MAX_PREC, MIN_PREC
from .core.errors import RigorGyroError
from .core.seconds import seconds_text
from .version import __version__

__all__ = ["main", "EXIT_BAD_INPUT", "EXIT_INTERNAL"]

EXIT_BAD_INPUT = 2
_KIND_NAMES = ("eigenfrequencies", "lyapunov", "periodic_orbit")
EXIT_INTERNAL = 4
EXIT_INCONCLUSIVE = 3
#: the worst exit status wins when several scenes are proved
_PRECEDENCE = (EXIT_INTERNAL, EXIT_BAD_INPUT, 1, 3, 0)


EXIT_CODES_HELP = """exit status:
  0  every claim proved            1  some claim refuted (a certified counterexample)
  3  some claim inconclusive       2  bad input or usage (nothing is proved or written)
  4  internal error (a bug; --debug prints the traceback); a crash is never 1"""


class _Parser(argparse.ArgumentParser):
    def __init__(self, *args, **kwargs):
        kwargs.setdefault("allow_abbrev", False)        # --qui is not --quiet: options are spelled out
        kwargs.setdefault("formatter_class", argparse.RawDescriptionHelpFormatter)
        super().__init__(*args, **kwargs)

    def error(self, message):  # usage errors are exit 2, as argparse does: one line, with our prefix
        self.exit(EXIT_BAD_INPUT, f"rigor-gyro: error: {message} (see {self.prog} --help)\n")


def _seconds(text: str) -> float:
    """--time-limit's type: seconds > 0 (argparse turns the ValueError into a usage error, exit 2)."""
    from .core.deadline import check_time_limit
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number of seconds") from None
    try:
        return check_time_limit(value, "--time-limit")
    except ValueError as e:
        raise argparse.ArgumentTypeError(str(e)) from None


def _nonnegative_int(text: str) -> int:
    """An option's count >= 0 (argparse turns the error into a usage error, exit 2)."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"{value} is negative: give 0 or more")
    return value


def _positive_int(text: str) -> int:
    """An option's count >= 1 (argparse turns the error into a usage error, exit 2)."""
    value = _nonnegative_int(text)
    if value < 1:
        raise argparse.ArgumentTypeError("0: give 1 or more")
    return value


def _epilog(examples: str, status: str = EXIT_CODES_HELP) -> str:
    return f"examples:\n{examples}\n\n{status}"


def _parser() -> argparse.ArgumentParser:
    p = _Parser(prog="rigor-gyro", description="Verified numerics for gyroscopic instruments: "
                "prove the claims of a scene with Arb ball arithmetic and write certificates.",
                epilog=_epilog("  rigor-gyro list                          the built-in scenes\n"
                               "  rigor-gyro prove --all -o proofs         prove the papers' examples\n"
                               "  rigor-gyro prove mine.toml --time-limit 60\n"
                               "  rigor-gyro check proofs/*.json           re-verify the certificates"))
    p.add_argument("--version", action="version", version=f"rigor-gyro {__version__}")
    p.add_argument("--debug", action="store_true", help="print the traceback of an internal error")
    sub = p.add_subparsers(dest="command", parser_class=_Parser, metavar="COMMAND")
    sub.add_parser("list", help="list the built-in scenes (the papers' examples, then the demos)",
                   description="List the built-in scenes: group, name, kind and source.",
                   epilog=_epilog("  rigor-gyro list | grep lyapunov", "exit status: 0"))
    pr = sub.add_parser("prove", help="prove scenes; write <name>.json and <name>.md",
                        description="Prove the claims of scenes and write, per scene, a certificate "
                        "(<name>.json) and a report (<name>.md). A scene with tolerances (a parameter "
                        "written as an interval) is paved: every claim decided over the box.",
                        epilog=_epilog("  rigor-gyro prove --all                      the papers' examples into ./proofs\n"
                                       "  rigor-gyro prove rudenko1976 -o out -q      one scene, one line\n"
                                       "  rigor-gyro prove mine.toml --maxprec 8192 --time-limit 120\n"
                                       "  rigor-gyro prove --group margin -j 2        the tolerance boxes on 2 processes\n"
                                       "  rigor-gyro prove box.toml --box-budget 5000 -o out; rigor-gyro prove --resume out/box.json -o out\n"
                                       "several scenes: the worst status wins, in the order 4, 2, 1, 3, 0; a paving stopped by Ctrl-C: 130, "
                                       "its paving so far written"))
    pr.add_argument("scenes", nargs="*", metavar="SCENE", help="built-in scene name or path to a TOML file")
    pr.add_argument("--all", action="store_true", help="prove every built-in scene of the papers")
    pr.add_argument("--group", choices=("paper", "demo", "margin", "stress", "plant", "moment", "all"), default=None,
                    help="prove every built-in scene of a group (demo: planted refuted/inconclusive outcomes; "
                         "margin: tolerance boxes and the papers' general claims, pavings that take minutes; stress: the "
                         "stiff and extreme catalog; plant: relay plants written as [plant] tables; moment: moment laws written as [moment] tables)")
    pr.add_argument("--prec", type=int, default=DEFAULT_PREC,
                    help=f"starting precision in bits, {MIN_PREC}..{MAX_PREC} (default {DEFAULT_PREC}); for a scene "
                         "with tolerances, of its point proofs (the sub-boxes use the scene's box_prec)")
    pr.add_argument("--maxprec", type=int, default=DEFAULT_MAXPREC,
                    help=f"highest precision to escalate to, --prec..{MAX_PREC} (default {DEFAULT_MAXPREC}); a paving's "
                         "point proofs too")
    pr.add_argument("-o", "--out", default="proofs", help="output folder (default: ./proofs)")
    pr.add_argument("-q", "--quiet", action="store_true", help="print only the verdict line of each scene, no progress")
    pr.add_argument("--plots", action="store_true",
                    help="also draw the scene's figures into --out (needs the 'plots' extra: matplotlib)")
    pr.add_argument("-j", "--workers", type=int, default=None,
                    help="processes (default: the cores): one scene per process when several are proved, "
                         "and the sub-boxes of scenes with tolerances")
    pr.add_argument("--scheduler", default=None, metavar="ADDRESS",
                    help="run the sub-boxes of scenes with tolerances on a Dask distributed scheduler "
                         "(tcp://host:8786, or 'local' for a LocalCluster of --workers processes; needs the 'dask' extra)")
    pr.add_argument("--time-limit", type=_seconds, default=None, metavar="SECONDS",
                    help="wall-clock budget per scene: when it runs out, every claim not yet decided is "
                         "inconclusive (reason: time limit) and the certificate is written")
    pr.add_argument("--box-budget", type=_positive_int, default=None, metavar="N",
                    help="pavings: stop after about N sub-box evaluations in this run (checked between batches of "
                         "evaluations) and write the paving so far: its decided sub-boxes and the pending ones, "
                         "undecided until --resume continues them")
    pr.add_argument("--priority", choices=("volume", "boundary"), default=None,
                    help="pavings: the order sub-boxes are evaluated in: volume (the largest first, breadth-first; "
                         "the default) or boundary (those next to a region already decided first)")
    pr.add_argument("--resume", default=None, metavar="PAVING.json",
                    help="continue a paving that stopped early (a budget, Ctrl-C, the checkpoint of a killed run) "
                         "into --out; it is verified first by the checker's rules. Same leaves and verdict as an "
                         "uninterrupted run")
    pr.add_argument("--refine", default=None, metavar="RESOLUTION",
                    help="with --resume: split the paving's undecided sub-boxes again, down to this box_resolution "
                         "(at most the paving's, e.g. 1/256); its decided sub-boxes are kept")
    pr.add_argument("--checkpoint-every", type=float, default=60.0, metavar="SECONDS",
                    help="pavings: write the paving so far to --out every SECONDS while it runs, a partial "
                         "certificate that --resume continues if the run is killed (default 60; 0: never)")
    pr.add_argument("--debug", action="store_true", default=argparse.SUPPRESS, help=argparse.SUPPRESS)
    mg = sub.add_parser("margin", help="certified threshold: where a claim stops holding as one parameter moves",
                        description="Bracket the value of one parameter where a claim changes from proved to "
                        "refuted (both ends certified), or with --scan prove the claims at N exact points.",
                        epilog=_epilog("  rigor-gyro margin agafonov2013 --param k --claim damping_condition\n"
                                       "  rigor-gyro margin roitenberg1947 --param tau --lo 0.005 --hi 0.02 --scan 9 -o out\n"
                                       "  rigor-gyro margin rudenko1976 --param eps --lo 0.1 --hi 2 --width 1e-9 --time-limit 60",
                                       "exit status:\n  0  a bracket to the requested width was certified (a scan: "
                                       "every point decided)\n  3  the search stopped (both ends alike, an "
                                       "inconclusive point, the budget or the time limit): never 1, a search is not "
                                       "a refutation\n  2  bad input         4  internal error"))
    mg.add_argument("scene", metavar="SCENE", help="built-in scene name or path to a TOML file")
    mg.add_argument("--param", required=True, help="the parameter to move")
    mg.add_argument("--lo", default=None, help="lower end of the search (exact number; default: value / 2)")
    mg.add_argument("--hi", default=None, help="upper end of the search (exact number; default: 2 value)")
    mg.add_argument("--claim", default=None, help="the claim whose change to bracket (needed unless the scene has one "
                    "claim; a --scan without it proves every claim)")
    mg.add_argument("--width", default=None, help="relative width of the threshold bracket (default 1e-6)")
    mg.add_argument("-o", "--out", default=None, help="also write margin_<scene>_<param>.json/.md here")
    mg.add_argument("-q", "--quiet", action="store_true", help="no progress display")
    mg.add_argument("--scan", type=int, default=None, metavar="N",
                    help="instead of a threshold: prove the claims (or --claim) at N exact points from --lo to --hi, "
                         "a map of point proofs (exit 0 all decided, 3 some inconclusive); writes "
                         "scan_<scene>_<param>.json/.md with --out")
    mg.add_argument("--log", action="store_true", help="with --scan: points evenly spaced in log scale")
    mg.add_argument("--along", default=None, metavar="PARAM2",
                    help="a threshold curve: bracket the threshold in --param for every value of PARAM2 from --from to "
                         "--to, cell by cell (pavings of each cell; writes curve_<scene>_<param>_<PARAM2>.json/.md)")
    mg.add_argument("--from", dest="along_from", default=None, help="with --along: the first value of PARAM2")
    mg.add_argument("--to", dest="along_to", default=None, help="with --along: the last value of PARAM2")
    mg.add_argument("--cells", type=int, default=8, help="with --along: cells of PARAM2 to start from (default 8)")
    mg.add_argument("--max-depth", type=int, default=4,
                    help="with --along: halvings of a cell where the threshold moves within it (default 4)")
    mg.add_argument("--plots", action="store_true",
                    help="with --out: also draw the result (<stem>.png; needs the 'plots' extra: matplotlib)")
    mg.add_argument("--quantity", action="append", default=None, metavar="Q",
                    help="with --scan: also report this certified quantity at each point (repeatable)")
    mg.add_argument("-j", "--workers", type=int, default=1, help="with --scan: processes (default 1)")
    mg.add_argument("--scheduler", default=None, metavar="ADDRESS",
                    help="with --scan: run the points on a Dask scheduler (tcp://host:8786 or 'local')")
    mg.add_argument("--time-limit", type=_seconds, default=None, metavar="SECONDS",
                    help="wall-clock budget of the threshold search: when it runs out, the bracket certified so "
                         "far is reported and the search is inconclusive (reason: time limit)")
    mg.add_argument("--debug", action="store_true", default=argparse.SUPPRESS, help=argparse.SUPPRESS)
    cp = sub.add_parser("campaign", help="prove N random scenes of a kind and compare them with mpmath, "
                        "floats and independent decisions (needs the 'crosscheck' extra)",
                        description="Prove N random scenes of a kind; compare each with mpmath, floats and "
                        "independent decisions, and re-check each certificate.",
                        epilog=_epilog("  rigor-gyro campaign --kind eigenfrequencies --cases 1000 -j 2 -o out",
                                       "exit status:\n  0  no containment failure, verdict disagreement, check "
                                       "failure or crash\n  1  some case found one\n  2  bad input or usage"))
    cp.add_argument("--kind", required=True, choices=sorted(_KIND_NAMES))
    cp.add_argument("--cases", type=int, default=100, help="number of random scenes (default 100)")
    cp.add_argument("--seed", type=int, default=0, help="seed of the draw (default 0)")
    cp.add_argument("-j", "--workers", type=int, default=1, help="processes (default 1)")
    cp.add_argument("--case-timeout", type=float, default=60.0, metavar="SECONDS",
                    help="stop a case after this many seconds and count it inconclusive (timed out); "
                         "0: no limit (default 60)")
    cp.add_argument("-o", "--out", default=None, help="also write the summary (Markdown) and the results (JSON) here")
    cp.add_argument("-q", "--quiet", action="store_true", help="no progress display")
    cp.add_argument("--debug", action="store_true", default=argparse.SUPPRESS, help=argparse.SUPPRESS)
    from .margins import safe_set_command
    safe_set_command.add_parser(sub, _epilog)
    bn = sub.add_parser("bench", help="work-precision: widths, bits lost and times per precision, against the "
                        "float and mpmath paths (--stress: the stiff and extreme catalog); needs 'crosscheck'",
                        description="Measure widths, bits lost and times per precision (a benchmark decides nothing).",
                        epilog=_epilog("  rigor-gyro bench rudenko1976 --schedule 53,128,512 --repeat 1 -o /tmp/b",
                                       "exit status: 0 measurements written; 2 bad input or usage; 4 internal error"))
    bn.add_argument("scenes", nargs="*", metavar="SCENE", help="scenes (default: the papers' examples)")
    bn.add_argument("--stress", action="store_true", help="run the stress group instead: OUT/stress.md and "
                    "OUT/bench/stress.json")
    bn.add_argument("-o", "--out", default=None, help="folder for the results (default proofs/bench; with --stress, proofs)")
    bn.add_argument("-q", "--quiet", action="store_true", help="no progress display")
    bn.add_argument("--plots", action="store_true", help="also draw a work-precision figure per scene (needs 'plots')")
    bn.add_argument("--schedule", default="53,64,128,256,512,1024,2048",
                    help="precisions in bits, comma-separated (default 53,64,128,256,512,1024,2048)")
    bn.add_argument("--repeat", type=int, default=3, help="runs per measurement; the median is reported (default 3)")
    bn.add_argument("--debug", action="store_true", default=argparse.SUPPRESS, help=argparse.SUPPRESS)
    ck = sub.add_parser("check", help="re-verify certificates from their own data (exit 0 all confirm, "
                        "1 one does not, 2 unreadable)",
                        description="Re-verify written results from their own data, independently of how they were "
                        "proved: certificates, pavings, thresholds and scans.",
                        epilog=_epilog("  rigor-gyro check proofs/*.json\n  rigor-gyro check -q out/margin_*.json",
                                       "exit status:\n  0  every file confirmed\n  1  some file is not confirmed "
                                       "(the first failing check is named)\n  2  a file is unreadable or not a "
                                       "result of rigor-gyro\n  3  --time-limit ran out before every check of a file ran (nothing "
                                       "found wrong; not confirmed either)\n  4  internal error"))
    ck.add_argument("certs", nargs="+", metavar="CERT.json", help="certificate files written by 'prove'")
    ck.add_argument("-q", "--quiet", action="store_true",
                    help="print only one line per certificate (a certificate's checks stop at the first that fails)")
    ck.add_argument("-j", "--workers", type=int, default=1,
                    help="pavings: processes that re-evaluate the decided sub-boxes (default 1)")
    ck.add_argument("--samples", type=_nonnegative_int, default=None, metavar="N",
                    help="pavings: decided sub-boxes per claim that the point prover cross-checks at their "
                         "midpoint and extreme corners (default 8; 0: none)")
    ck.add_argument("--time-limit", type=_seconds, default=None, metavar="SECONDS",
                    help="wall-clock budget per file (some checks prove the scene again, as long as its proof "
                         "took): when it runs out the file is neither confirmed nor failed (exit 3)")
    ck.add_argument("--debug", action="store_true", default=argparse.SUPPRESS, help=argparse.SUPPRESS)
    return p


def _say(text: str, err: bool = False) -> None:
    """Print a line; a closed pipe (``rigor-gyro list | head``) silences the rest, never crashes."""
    stream = sys.stderr if err else sys.stdout
    try:
        print(text, file=stream, flush=True)
    except BrokenPipeError:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, stream.fileno())


def _input_error(ref: str, e: Exception) -> str:
    """A bad-input line naming ``ref`` once: the messages of scene loading start with the path already."""
    msg = str(e)
    return f"rigor-gyro: {msg}" if msg.startswith((ref, f"builtin:{ref}")) else f"rigor-gyro: {ref}: {msg}"


def _bad(message: str) -> int:
    _say(f"rigor-gyro: error: {message}", err=True)
    return EXIT_BAD_INPUT


def _cmd_list() -> int:
    from .scene import builtin_scenes, load_scene
    for group in ("paper", "demo", "margin", "stress", "plant", "moment"):
        for name in builtin_scenes(group):
            s = load_scene(name)
            _say(f"{group:6s} {name:34s} {s.kind:18s} {s.source.splitlines()[0][:80] if s.source else ''}")
    return 0


def _check_out(out: str) -> str | None:
    """None if ``out`` is (or can be made) a writable folder; otherwise what is wrong with it."""
    if not out.strip():
        return "--out is empty: name a folder (default: proofs)"
    if out.strip() == "-":
        return ("--out -: rigor-gyro writes files (a certificate and a report per result), not a stream: "
                "name a folder (the verdict lines go to standard output anyway)")
    path = Path(out)
    try:
        if path.exists() and not path.is_dir():
            return f"--out {out[:200]!r} is a file, not a folder"
        path.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=path):
            pass
    except OSError as e:
        return f"--out {out[:200]!r} is not a writable folder ({e.strerror or e})"
    return None


def _cmd_prove(args) -> int:
    from .kinds import kind_module, scene_claims
    from .prover import requested_claims
    from .report import output_paths
    from .core.boxes import is_tolerance
    from .scene import builtin_scenes, load_scene

    if args.resume is not None:
        return _cmd_resume(args)
    if args.refine is not None:
        return _bad("--refine splits the undecided sub-boxes of a paving: give it with --resume PAVING.json")
    if (args.all or args.group) and args.scenes or (args.all and args.group):
        return _bad("give scene names, --all or --group, one of them")
    refs = list(builtin_scenes()) if args.all else list(builtin_scenes(args.group)) if args.group else args.scenes
    if not refs:
        return _bad("name at least one scene (see `rigor-gyro list`) or use --all")
    if not (MIN_PREC <= args.prec <= args.maxprec <= MAX_PREC):
        return _bad(f"need {MIN_PREC} <= --prec <= --maxprec <= {MAX_PREC} (got {args.prec}, {args.maxprec})")
    # every scene is loaded and checked, and --out too, before anything is proved or written
    scenes, codes = [], []
    for ref in refs:
        try:
            scene = load_scene(ref)
            if any(is_tolerance(v) for v in scene.parameters.values()):   # margins.paving.has_tolerances
                from .margins.paving import box_scene       # imported only for a paving (issue 41)
                scene = box_scene(scene)        # a claim for every parameter in the box: a paving
            else:
                module = kind_module(scene.kind)
                module.validate(scene)
                requested_claims(scene, *scene_claims(module, scene))
        except RigorGyroError as e:
            _say(_input_error(ref, e), err=True)
            codes.append(EXIT_BAD_INPUT)
            continue
        scenes.append((ref, scene))
    names = [getattr(s, "scene", s).name for _, s in scenes]
    dupes = sorted({n for n in names if names.count(n) > 1})
    if dupes:
        return _bad(f"two scenes named {dupes[0]!r} in one call would write the same files: rename one")
    if codes:
        return EXIT_BAD_INPUT
    problem = _check_out(args.out)
    if problem:
        return _bad(problem)
    try:
        for name in names:
            output_paths(name, args.out)
    except RigorGyroError as e:
        return _bad(str(e))
    if args.workers is not None and not 1 <= args.workers <= 256:
        return _bad(f"need 1 <= --workers <= 256 (got {args.workers})")
    boxes = sum(hasattr(s, "box") for _, s in scenes)
    if args.scheduler is not None and not boxes:
        return _bad("--scheduler runs the sub-boxes of scenes with tolerances, and none of these scenes has "
                    "tolerances: drop --scheduler (point scenes run on --workers processes)")
    for flag, given in (("--box-budget", args.box_budget), ("--priority", args.priority)):
        if given is not None and not boxes:
            return _bad(f"{flag} applies to pavings (scenes with tolerances), and none of these scenes has tolerances")
    if args.scheduler is not None and boxes < len(scenes):
        _say("rigor-gyro: warning: --scheduler applies to the scenes with tolerances only; the point scenes "
             "run here, on --workers processes", err=True)
    executor = None
    for ref, scene in scenes:
        if not hasattr(scene, "box"):
            continue
        try:
            if executor is None:
                from .margins.executors import make_executor
                executor = make_executor(args.workers, args.scheduler)
            codes.append(_pave(scene, executor, args))
            if codes[-1] == EXIT_INTERRUPTED:       # Ctrl-C: the paving so far is written; no further scene
                executor.close()
                return EXIT_INTERRUPTED
        except RigorGyroError as e:
            _say(_input_error(ref, e), err=True)
            codes.append(EXIT_BAD_INPUT)
        except OSError as e:
            _say(f"rigor-gyro: {ref}: cannot write to --out {args.out!r}: {e.strerror or e}", err=True)
            codes.append(EXIT_BAD_INPUT)
        except Exception as e:  # a bug: one line, never exit 1
            _internal(e, args, where=ref)
            codes.append(EXIT_INTERNAL)
    if executor is not None:
        executor.close()
    points = [(ref, scene) for ref, scene in scenes if not hasattr(scene, "box")]
    codes.extend(_prove_points(points, args))
    return next(c for c in _PRECEDENCE if c in codes or c == 0)


#: the scenes of one ``prove`` call and its arguments, inherited by forked workers (nothing is pickled)
_POINT_JOBS: list = []


def _prove_points(points: list, args) -> list[int]:
    """Prove scenes without tolerances, each in its own worker process when there are several and more
    than one worker (``--workers``, default the cores). Each worker writes its scene's files and returns
    its exit code and printed text; the text is printed in the order of the scenes, so the output and
    the files are the same whatever the worker count."""
    if args.workers is None:
        from .margins.executors import default_workers
    workers = min(len(points), default_workers() if args.workers is None else args.workers)
    if workers <= 1 or "fork" not in _mp_start_methods():
        return [_prove_point(ref, scene, args) for ref, scene in points]
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor
    from concurrent.futures.process import BrokenProcessPool
    _POINT_JOBS[:] = [(ref, scene, args) for ref, scene in points]
    codes = []
    from .progress import progress_bar
    try:
        with ProcessPoolExecutor(max_workers=workers, mp_context=multiprocessing.get_context("fork")) as pool, \
                progress_bar("prove", total=len(points), unit="scene", delay=2.0, enabled=not args.quiet) as bar:
            for code, out, err in pool.map(_prove_point_captured, range(len(points))):
                if out:
                    _say(out.rstrip("\n"))
                if err:
                    _say(err.rstrip("\n"), err=True)
                codes.append(code)
                bar.update(1)
    except BrokenProcessPool as e:  # a worker died (killed, out of memory): a failure, never a verdict
        _internal(e, args, where="a prove worker")
        codes.append(EXIT_INTERNAL)
    finally:
        _POINT_JOBS.clear()
    return codes


def _mp_start_methods() -> list[str]:
    import multiprocessing
    return multiprocessing.get_all_start_methods()


def _prove_point_captured(i: int) -> tuple[int, str, str]:
    """In a worker: prove scene ``i`` of :data:`_POINT_JOBS`, capturing what it prints."""
    import io
    from contextlib import redirect_stderr, redirect_stdout
    ref, scene, args = _POINT_JOBS[i]
    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err):
        try:
            code = _prove_point(ref, scene, args, show_progress=False)
        except Exception as e:  # a bug outside the proof (a figure): one line, never exit 1
            _internal(e, args, where=ref)
            code = EXIT_INTERNAL
    return code, out.getvalue(), err.getvalue()


def _prove_point(ref: str, scene, args, show_progress: bool = True) -> int:
    """Prove one scene without tolerances, write its certificate and report, print its lines; its exit
    code. On a terminal, a proof that takes more than 2 s shows its phase (claim) and precision."""
    from .certificate import EXIT_CODES
    from .progress import progress_bar
    from .prover import prove_scene
    from .report import write_outputs
    try:
        with progress_bar(scene.name, delay=2.0, unit="phase", enabled=show_progress and not args.quiet) as bar:
            def progress(phase: str, bits: int) -> None:
                bar.update(1 if phase else 0)
                bar.status(f"{phase or 'start'}, {bits} bits")
            cert = prove_scene(scene, prec=args.prec, maxprec=args.maxprec, time_limit=args.time_limit,
                               progress=progress)
        jpath, mpath = write_outputs(cert, args.out)
    except RigorGyroError as e:
        _say(_input_error(ref, e), err=True)
        return EXIT_BAD_INPUT
    except OSError as e:
        _say(f"rigor-gyro: {ref}: cannot write to --out {args.out!r}: {e.strerror or e}", err=True)
        return EXIT_BAD_INPUT
    except Exception as e:  # a bug: say so in one line, never exit 1 (refuted)
        _internal(e, args, where=ref)
        return EXIT_INTERNAL
    code = EXIT_CODES[cert.verdict]
    if args.plots:
        code = _plots(scene, cert, args.out) or code
    if not args.quiet:
        for c in cert.claims:
            _say(f"{scene.name}: {c.id}: {c.status.value} ({c.precision_bits} bits) - {c.reason}")
    _say(f"{scene.name}: verdict {cert.verdict.value} in {seconds_text(cert.timings['total_s'])} "
         f"at {cert.precision_bits} bits -> {jpath}, {mpath}")
    return code


def _cmd_resume(args) -> int:
    """``prove --resume PAVING.json [--refine RES]``: continue a paving (verified first) into --out."""
    import json
    from .margins.resume import resume_state
    from .report import output_paths
    if args.scenes or args.all or args.group:
        return _bad("--resume continues the paving it names: give no scene, --all or --group with it")
    try:
        data = json.loads(Path(args.resume).read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, ValueError, RecursionError) as e:
        return _bad(f"--resume {args.resume[:200]!r}: not a readable paving ({type(e).__name__})")
    problem = _check_out(args.out)
    if problem:
        return _bad(problem)
    if args.workers is not None and not 1 <= args.workers <= 256:
        return _bad(f"need 1 <= --workers <= 256 (got {args.workers})")
    from .margins.executors import make_executor
    executor = make_executor(args.workers, args.scheduler)
    try:
        bs, state = resume_state(data, executor, refine=args.refine, priority=args.priority)
        output_paths(bs.scene.name, args.out)
        return _pave(bs, executor, args, state)
    except RigorGyroError as e:
        _say(f"rigor-gyro: --resume {args.resume[:200]}: {e}", err=True)
        return EXIT_BAD_INPUT
    except OSError as e:
        _say(f"rigor-gyro: cannot write to --out {args.out!r}: {e.strerror or e}", err=True)
        return EXIT_BAD_INPUT
    finally:
        executor.close()


#: the exit status of a paving stopped by Ctrl-C (its partial certificate written), as of any interrupted run
EXIT_INTERRUPTED = 130


def _pave(bs, executor, args, state=None) -> int:
    """Pave one scene with tolerances (or continue ``state``, :mod:`.margins.resume`); print its claims and
    verdict; write its paving pair, and while it runs, every --checkpoint-every seconds, the paving so far."""
    from .margins.paving import INTERRUPTED, pave
    from .margins.report import write_paving
    from .progress import progress_bar

    if state is None:
        bs.point_prec, bs.point_maxprec = args.prec, args.maxprec     # the point proofs' precisions
        if args.priority is not None:
            bs.priority = args.priority
    every = args.checkpoint_every if args.checkpoint_every > 0 else None
    with progress_bar(bs.scene.name, unit="box", enabled=not args.quiet) as bar:
        def progress(done, queued, result):
            vols = [c.volume(bs.box) for c in result.values()]
            worst = min(vols, key=lambda v: v["proved"])          # the claim furthest from proved
            bar.update(done - progress.done)
            progress.done = done
            bar.status(f"{queued} queued; least proved claim: {float(worst['proved']):.3f} proved, "
                       f"{float(worst['refuted']):.3f} refuted")
        progress.done = 0
        paving = pave(bs, executor, progress, time_limit=args.time_limit, box_budget=args.box_budget, state=state,
                      checkpoint=lambda p: write_paving(p, args.out), checkpoint_every=every, keep_on_interrupt=True)
    jpath, mpath = write_paving(paving, args.out)
    if not args.quiet:
        for c in paving.claims:
            v = c.volume(bs.box)
            _say(f"{bs.scene.name}: {c.id}: {c.status} over the box (volume proved {float(v['proved']):.4g}, "
                 f"refuted {float(v['refuted']):.4g}, undecided {float(v['undecided']):.4g})")
    _say(f"{bs.scene.name}: verdict {paving.verdict} over the box in {seconds_text(paving.seconds)} "
         f"({paving.evaluated} {'box' if paving.evaluated == 1 else 'boxes'}, {executor.label}) -> {jpath}, {mpath}")
    if paving.stopped:
        pending = sum(len(g.boxes) for g in paving.pending)
        _say(f"{bs.scene.name}: stopped: {paving.stopped}" + (f"; {pending} sub-box{'es' if pending != 1 else ''} pending: `rigor-gyro prove "
                                                               f"--resume {jpath}` continues" if pending else ""))
    if paving.stopped == INTERRUPTED:
        return EXIT_INTERRUPTED
    if args.plots:
        if not _has_matplotlib():
            return _bad(NO_MATPLOTLIB)
        from .margins.plots import paving_plots
        from .margins.report import paving_json
        for path in paving_plots(paving_json(paving), args.out):
            _say(f"{bs.scene.name}: figure -> {path}")
    return paving.exit_code


def _cmd_margin(args) -> int:
    from .margins.threshold import find_threshold, write_threshold
    from .scene import load_scene
    scene = load_scene(args.scene)
    if args.out is not None:
        problem = _check_out(args.out)
        if problem:
            return _bad(problem)
    if args.plots:
        if args.out is None:
            return _bad("--plots writes the figure beside the result: give --out")
        if not _has_matplotlib():
            return _bad(NO_MATPLOTLIB)
    if args.scan is not None:
        from .margins.scan import run_scan, write_scan
        if args.width is not None:
            return _bad("--width is the threshold's; a scan proves exactly the --scan N points")
        if not 1 <= args.workers <= 64:
            return _bad("need 1 <= --workers <= 64")
        if args.time_limit is not None:
            return _bad("--time-limit bounds a threshold search; a scan proves exactly its --scan N points "
                        "(lower N, or prove a single point with `rigor-gyro prove --time-limit`)")
        return _said(run_scan(scene, args.param, args.scan, lo=args.lo, hi=args.hi, claim=args.claim,
                              quantities=args.quantity, log=args.log, workers=args.workers,
                              scheduler=args.scheduler), write_scan, args.out, args.plots)
    if args.log or args.quantity or args.workers != 1 or args.scheduler:
        return _bad("--log, --quantity, --workers and --scheduler go with --scan")
    if args.along is not None:
        from .margins.threshold_curve import find_curve, write_curve
        if args.claim is None:
            return _bad("--along brackets one claim's threshold: name it with --claim")
        return _said(find_curve(scene, args.param, args.along, lo=args.lo, hi=args.hi, along_lo=args.along_from,
                                along_hi=args.along_to, claim=args.claim, cells=args.cells,
                                width=args.width if args.width is not None else "1e-3", max_depth=args.max_depth,
                                time_limit=args.time_limit), write_curve, args.out, args.plots)
    if args.along_from is not None or args.along_to is not None:
        return _bad("--from and --to go with --along")
    return _said(find_threshold(scene, args.param, lo=args.lo, hi=args.hi, claim=args.claim,
                                width=args.width if args.width is not None else "1e-6", time_limit=args.time_limit),
                 write_threshold, args.out, args.plots)


NO_MATPLOTLIB = "--plots needs matplotlib: pip install 'rigor_gyro[plots]'"


def _has_matplotlib() -> bool:
    """Whether the optional 'plots' extra is installed (looked up, not imported: figures import it)."""
    from importlib.util import find_spec
    return find_spec("matplotlib") is not None


def _said(result, write, out: str | None, plots: bool = False) -> int:
    """Print a margin result's lines, write its files (and with ``plots`` its figure) to ``out`` (when
    given), return its exit code."""
    for line in result.lines():
        _say(line)
    if out is not None:
        for path in write(result, out):
            _say(f"-> {path}")
        if plots:
            from .margins.plots import margin_plot
            _say(f"-> {margin_plot(result.to_json(), out)}")
    return result.exit_code


def _cmd_campaign(args) -> int:
    """Exit 0 when no containment failure, verdict disagreement or crash, 1 otherwise."""
    import json
    from .campaign import run_campaign, summary_table
    if not (1 <= args.cases <= 10 ** 6 and 1 <= args.workers <= 64):
        return _bad("need 1 <= --cases <= 1000000 and 1 <= --workers <= 64")
    if not (args.case_timeout >= 0 and args.case_timeout < float("inf")):
        return _bad("need a finite --case-timeout >= 0 (seconds; 0 means no limit)")
    if args.out is not None:        # checked before any case runs: a campaign is not lost at its end
        problem = _check_out(args.out)
        if problem:
            return _bad(problem)
    from .progress import progress_bar
    try:
        with progress_bar(args.kind, total=args.cases, unit="case", enabled=not args.quiet) as bar:
            def progress(done, total):
                bar.update(done - progress.done)
                progress.done = done
            progress.done = 0
            results = run_campaign(args.kind, args.cases, args.seed, args.workers, progress,
                                   args.case_timeout or None)
    except ImportError as e:
        return _bad(f"campaign needs the cross-check libraries ({e.name}): pip install 'rigor_gyro[crosscheck]'")
    table = summary_table(args.kind, args.seed, results)
    _say(table)
    if args.out:
        out = Path(args.out)
        (out / f"campaign_{args.kind}_{args.seed}.md").write_text(table + "\n", encoding="utf-8")
        (out / f"campaign_{args.kind}_{args.seed}.json").write_text(json.dumps(results, indent=1) + "\n",
                                                                     encoding="utf-8")
    bad = any(r["containment_failures"] or r["verdict_disagreements"] or r.get("check_failures") or r["error"]
              for r in results)
    return 1 if bad else 0


def _cmd_check(args) -> int:
    """Exit 0 when every certificate confirms, 1 naming the first check that does not, 2 unreadable."""
    from .check import CertificateError, check_file
    from .margins.executors import Executor
    if args.workers < 1:
        return _bad(f"--workers {args.workers}: give 1 or more")
    with Executor(args.workers) as ex:
        return _check_files(args, ex, check_file, CertificateError)


def _check_files(args, ex, check_file, CertificateError) -> int:
    codes = []
    from .core.deadline import TimeLimitReached, time_limit
    for path in args.certs:
        try:
            with time_limit(args.time_limit) as budget:
                report = check_file(path, samples=args.samples, executor=ex if args.workers > 1 else None,
                                    stop_at_failure=args.quiet)
            if budget.fired:        # the alarm went off, but its exception was swallowed (inside a C or GC
                raise TimeLimitReached(budget.reason())     # callback) or turned into a failed check: undecided
        except TimeLimitReached:
            _say(f"{path}: not decided: the time limit of {args.time_limit:g} s (--time-limit) ran out before "
                 "every check ran (neither confirmed nor failed); give it more time")
            codes.append(EXIT_INCONCLUSIVE)
            continue
        except CertificateError as e:
            _say(f"rigor-gyro: {e}", err=True)
            codes.append(EXIT_BAD_INPUT)
            continue
        except RecursionError:      # json nested beyond Python's recursion limit: not a result of ours
            _say(f"rigor-gyro: {path}: nested too deeply to be a certificate", err=True)
            codes.append(EXIT_BAD_INPUT)
            continue
        if not args.quiet:
            for r in report.results:
                _say(f"{path}: {r.item}: {r.message}" if r.skipped else
                     f"{path}: {r.item}: {'ok' if r.ok else 'FAILED'} - {r.message}")
        bad = report.first_failure
        _say(f"{path}: " + ("confirmed" if report.ok else f"NOT confirmed: {bad.item}: {bad.message}")
             + f" ({len(report.results)} checks, {seconds_text(report.seconds)})")
        codes.append(0 if report.ok else 1)
    return next(c for c in (EXIT_BAD_INPUT, 1, EXIT_INCONCLUSIVE, 0) if c in codes or c == 0)


def _plots(scene, cert, out: str) -> int:
    """Draw the figures of a proved scene (float drawings of certified objects; never a verdict)."""
    from .kinds import plots_hook
    draw = plots_hook(scene.kind)
    if draw is None:
        _say(f"rigor-gyro: {scene.name}: kind {scene.kind!r} has no figures; --plots ignored", err=True)
        return 0
    if not _has_matplotlib():
        return _bad(NO_MATPLOTLIB)
    for path in draw(scene, cert, out):
        _say(f"{scene.name}: figure -> {path}")
    return 0


def _internal(e: BaseException, args, where: str = "") -> None:
    place = f"{where}: " if where else ""
    _say(f"rigor-gyro: {place}internal error: {type(e).__name__}: {str(e).splitlines()[0] if str(e) else ''} "
         "(a bug in rigor_gyro; rerun with --debug for the traceback)", err=True)
    if getattr(args, "debug", False):
        _say("".join(traceback.format_exception(e)), err=True)


def _cmd_safe_set(args) -> int:
    """The safe set of a paving (rigor_gyro.margins.safe_set_command); the figures drawn here (float side)."""
    from .margins import safe_set_command
    if args.plots and not _has_matplotlib():
        return _bad(NO_MATPLOTLIB)
    data, safe = safe_set_command.run(args, _say)
    if args.plots:
        from .margins.plots import safe_set_plot
        out, axes, formats = safe_set_command.figure_options(args)
        for p in safe_set_plot(data, safe, out, axes, formats):
            _say(f"{data['scene']['name']}: figure -> {p}")
    return 0


def _cmd_bench(args) -> int:
    """Exit 0 when the measurements were written (a benchmark decides nothing), 2 for bad usage."""
    try:
        schedule = tuple(int(x) for x in args.schedule.split(","))
    except ValueError:
        return _bad(f"--schedule {args.schedule!r}: give precisions in bits, comma-separated, e.g. 53,64,128")
    for p in schedule:
        if not MIN_PREC <= p <= MAX_PREC:
            return _bad(f"--schedule: each precision must be in [{MIN_PREC}, {MAX_PREC}] bits (got {p})")
    if not 1 <= args.repeat <= 100:
        return _bad("need 1 <= --repeat <= 100")
    if args.stress and args.scenes:
        return _bad("give scene names or --stress, not both")
    from importlib.util import find_spec
    missing = [m for m in ("numpy", "scipy", "mpmath") if find_spec(m) is None]
    if missing:
        return _bad(f"bench needs the cross-check libraries ({', '.join(missing)}): "
                    "pip install 'rigor_gyro[crosscheck]'")
    if args.plots and not _has_matplotlib():
        return _bad(NO_MATPLOTLIB)
    from .progress import progress_bar
    with progress_bar("bench", unit="step", enabled=not args.quiet) as bar:
        def progress(text):
            bar.update(1)
            bar.status(text)
        return _bench(args, schedule, progress)


def _bench(args, schedule, progress) -> int:
    import json
    if args.stress:
        from .bench.stress import run_stress, stress_markdown
        out = Path(args.out or "proofs")
        problem = _check_out(str(out))
        if problem:
            return _bad(problem)
        rows = run_stress(progress=progress)
        md = stress_markdown(rows)
        (out / "stress.md").write_text(md, encoding="utf-8")
        # the data beside the work-precision results (a JSON in proofs/ itself would pass for a certificate)
        (out / "bench").mkdir(exist_ok=True)
        (out / "bench" / "stress.json").write_text(json.dumps(rows, indent=1, default=str) + "\n", encoding="utf-8")
        _say(md)
        return 0
    from .bench.tables import summary_markdown, write_scene
    from .bench.workprecision import bench_scene
    from .margins.paving import has_tolerances
    from .scene import builtin_scenes, load_scene
    refs = args.scenes or list(builtin_scenes())
    scenes = [load_scene(r) for r in refs]
    for sc in scenes:
        if has_tolerances(sc):
            return _bad(f"scene {sc.name!r} has tolerances: bench measures point scenes (a paving's cost is "
                        "its boxes; see benchmarks/paving_speedup.py)")
    out = Path(args.out or "proofs/bench")
    problem = _check_out(str(out))
    if problem:
        return _bad(problem)
    benches = []
    for sc in scenes:
        sb = bench_scene(sc, schedule, args.repeat, progress=progress)
        benches.append(sb)
        write_scene(sb, out)
        if args.plots:
            from .bench.plots import work_precision_figure
            work_precision_figure(sb, out)
    summary = summary_markdown(benches)
    if not args.scenes:
        (out / "README.md").write_text(summary, encoding="utf-8")
    _say(summary)
    return 0


def main(argv: list[str] | None = None) -> int:
    parser = _parser()
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return EXIT_BAD_INPUT
    try:
        if args.command == "list":
            return _cmd_list()
        if args.command == "check":
            return _cmd_check(args)
        if args.command == "campaign":
            return _cmd_campaign(args)
        if args.command == "margin":
            return _cmd_margin(args)
        if args.command == "bench":
            return _cmd_bench(args)
        if args.command == "safe-set":
            return _cmd_safe_set(args)
        return _cmd_prove(args)
    except RigorGyroError as e:
        return _bad(str(e))
    except KeyboardInterrupt:
        _say("rigor-gyro: interrupted", err=True)
        return 130
    except Exception as e:  # a bug: never exit 1 (refuted)
        _internal(e, args)
        return EXIT_INTERNAL


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
