"""``rigor-gyro safe-set PAVING.json``: the safe set of a paving and its certified yield, as a table, a CSV
file and figures (see :mod:`rigor_gyro.margins.safe_set`).

The paving is read, its digest verified and its leaves checked to tile its box (the claims' common
refinement needs a bisection tree); the statuses of its sub-boxes are what ``rigor-gyro check`` re-verifies,
which this command does not repeat (run it first on a paving you did not make). Nothing new is claimed:
the safe set and the yield are exact consequences of the paving's certified statuses.

Exit status: 0 the safe set was written; 2 bad input (an unreadable file, not a paving, a digest that
does not match, a claim it does not pave, a law or an axis it cannot read).
"""
from __future__ import annotations

import json
from pathlib import Path

__all__ = ["add_parser", "run", "figure_options"]


def add_parser(sub, epilog) -> None:
    ss = sub.add_parser("safe-set", help="where all the selected claims of a paving hold, and the certified yield",
                        description="The safe set of a paving (where every selected claim is proved) and its "
                        "certified yield under uniform or truncated-normal tolerance laws; a CSV of the pieces and "
                        "figures on request. Derived from the paving's certified statuses: nothing new is claimed.",
                        epilog=epilog("  rigor-gyro safe-set out/margin_roitenberg_n_tolerance.json\n"
                                      "  rigor-gyro safe-set P.json --claims stable,orbit_genuine --law 'normal 3' --csv "
                                      "--plots --axes n --format png,svg",
                                      "exit status:\n  0  written\n  2  bad input (unreadable, not a paving, digest, "
                                      "claim, law, axis)\n  4  internal error"))
    ss.add_argument("paving", metavar="PAVING.json", help="a paving written by 'rigor-gyro prove' (schema paving/1)")
    ss.add_argument("--claims", default=None, help="comma-separated claims (default: every claim of the paving)")
    ss.add_argument("--law", default="uniform",
                    help="tolerance laws: 'uniform' (default), 'normal K' (the tolerance is +-K standard deviations), "
                         "or per parameter 'H: normal 3, B: uniform'")
    ss.add_argument("--csv", action="store_true", help="also write <out>/<name>_leaves.csv (every piece, every claim)")
    ss.add_argument("--plots", action="store_true", help="also draw <out>/<name>_safe_set.<format>")
    ss.add_argument("--axes", default=None, help="with --plots: one or two box parameters to draw, e.g. eps,Omega2")
    ss.add_argument("--format", default="png", help="with --plots: png, svg, pdf, comma-separated (default png)")
    ss.add_argument("-o", "--out", default=None, help="folder for the CSV and figures (default: the paving's folder)")


def run(args, say) -> tuple[dict, dict]:
    """The command but its figures; ``say(text)`` prints a line. Returns (paving, safe set) for the caller to
    draw (``--plots``: the command line's float side). Raises RigorGyroError for bad input (exit 2)."""
    from ..certificate import digest
    from ..core.balls import working_precision
    from ..core.errors import ParameterError
    from .export import leaves_csv
    from .safe_set import from_paving
    path = Path(args.paving)
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, json.JSONDecodeError, RecursionError) as e:
        raise ParameterError(f"{args.paving}: not a readable paving ({type(e).__name__})") from None
    if not isinstance(data, dict) or data.get("schema") != "rigor-gyro/paving/1":
        raise ParameterError(f"{args.paving}: not a paving (schema rigor-gyro/paving/1); pave a scene with tolerances "
                             "with 'rigor-gyro prove'")
    if not isinstance(data.get("integrity"), dict) or data["integrity"].get("sha256") != digest(data):
        raise ParameterError(f"{args.paving}: the digest does not match the content: an edited or damaged paving")
    claims = [c.strip() for c in args.claims.split(",")] if args.claims else None
    try:
        with working_precision(128):
            safe = from_paving(data, claims, args.law)
    except ValueError as e:
        raise ParameterError(f"{args.paving}: {e}") from None
    name = data["scene"]["name"]
    vol, yl = safe["volume"], safe["yield"]
    say(f"{name}: where {', '.join(safe['claims'])} all hold: {safe['counts']['proved']} safe, "
        f"{safe['counts']['refuted']} failing, {safe['counts']['undecided']} undecided piece(s)")
    say(f"{name}: safe volume fraction in [{vol['lower']}, {vol['upper']}]"
        + (f" (exactly [{vol['lower_exact']}, {vol['upper_exact']}])" if vol.get("exact") else ""))
    kinds = sorted(set(safe["laws"].values()))
    laws = f"every parameter {kinds[0]}" if len(kinds) == 1 else "; ".join(f"{k}: {v}" for k, v in safe["laws"].items())
    say(f"{name}: certified yield ({laws}) in [{yl['lower']}, {yl['upper']}]")
    out = Path(args.out) if args.out else path.parent
    if args.csv or args.plots:
        out.mkdir(parents=True, exist_ok=True)
    if args.csv:
        csv_path = out / f"{name}_leaves.csv"
        csv_path.write_text(leaves_csv(data), encoding="utf-8")
        say(f"{name}: leaves -> {csv_path}")
    return data, safe


def figure_options(args) -> tuple[Path, tuple[str, ...] | None, tuple[str, ...]]:
    """(folder, axes, formats) of ``--plots``."""
    out = Path(args.out) if args.out else Path(args.paving).parent
    axes = tuple(a.strip() for a in args.axes.split(",")) if args.axes else None
    return out, axes, tuple(f.strip() for f in args.format.split(","))
