"""Command line: ``rigor-gyro list`` and ``rigor-gyro prove SCENE... | --all``.

Exit status: 0 every claim proved; 1 some claim refuted; 3 some claim inconclusive (none refuted);
2 bad input or usage (the message names the parameter or option to change).
"""
from __future__ import annotations

import argparse
import sys

from .core.balls import DEFAULT_MAXPREC, DEFAULT_PREC
from .core.errors import RigorGyroError

__all__ = ["main"]

EXIT_BAD_INPUT = 2


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # usage errors are exit 2, as argparse does, with our prefix
        self.print_usage(sys.stderr)
        self.exit(EXIT_BAD_INPUT, f"rigor-gyro: error: {message}\n")


def _parser() -> argparse.ArgumentParser:
    p = _Parser(prog="rigor-gyro", description="Verified numerics for gyroscopic instruments: "
                "prove the claims of a scene with Arb ball arithmetic and write certificates.")
    sub = p.add_subparsers(dest="command", required=True, parser_class=_Parser)
    sub.add_parser("list", help="list the built-in scenes")
    pr = sub.add_parser("prove", help="prove scenes; write <name>.json and <name>.md")
    pr.add_argument("scenes", nargs="*", metavar="SCENE", help="built-in scene name or path to a TOML file")
    pr.add_argument("--all", action="store_true", help="prove every built-in scene")
    pr.add_argument("--prec", type=int, default=DEFAULT_PREC, help=f"starting precision in bits (default {DEFAULT_PREC})")
    pr.add_argument("--maxprec", type=int, default=DEFAULT_MAXPREC,
                    help=f"highest precision to escalate to (default {DEFAULT_MAXPREC})")
    pr.add_argument("--out", default="proofs", help="output folder (default: ./proofs)")
    pr.add_argument("--quiet", action="store_true", help="print only the verdict line of each scene")
    pr.add_argument("--plots", action="store_true",
                    help="also draw the scene's figures into --out (needs the 'plots' extra: matplotlib)")
    return p


def _cmd_list() -> int:
    from .scene import builtin_scenes, load_scene
    for name in builtin_scenes():
        s = load_scene(name)
        print(f"{name:24s} {s.kind:18s} {s.source.splitlines()[0][:90] if s.source else ''}")
    return 0


def _cmd_prove(args) -> int:
    from .certificate import EXIT_CODES
    from .core.outcome import Status
    from .prover import prove_scene
    from .report import write_outputs
    from .scene import builtin_scenes, load_scene

    if args.all and args.scenes:
        print("rigor-gyro: error: give scene names or --all, not both", file=sys.stderr)
        return EXIT_BAD_INPUT
    refs = list(builtin_scenes()) if args.all else args.scenes
    if not refs:
        print("rigor-gyro: error: name at least one scene (see `rigor-gyro list`) or use --all", file=sys.stderr)
        return EXIT_BAD_INPUT
    if args.prec < 16 or args.maxprec < args.prec:
        print(f"rigor-gyro: error: need 16 <= --prec <= --maxprec (got {args.prec}, {args.maxprec})", file=sys.stderr)
        return EXIT_BAD_INPUT
    codes = []
    for ref in refs:
        try:
            scene = load_scene(ref)
            cert = prove_scene(scene, prec=args.prec, maxprec=args.maxprec)
        except RigorGyroError as e:
            print(f"rigor-gyro: {ref}: bad input: {e}", file=sys.stderr)
            codes.append(EXIT_BAD_INPUT)
            continue
        jpath, mpath = write_outputs(cert, args.out)
        if args.plots:
            code = _plots(scene, cert, args.out)
            if code:
                codes.append(code)
        if not args.quiet:
            for c in cert.claims:
                print(f"{scene.name}: {c.id}: {c.status.value} ({c.precision_bits} bits) - {c.reason}")
        print(f"{scene.name}: verdict {cert.verdict.value} in {cert.timings['total_s']:.2f} s "
              f"at {cert.precision_bits} bits -> {jpath}, {mpath}")
        codes.append(EXIT_CODES[cert.verdict])
    if EXIT_BAD_INPUT in codes:
        return EXIT_BAD_INPUT
    for status in (Status.REFUTED, Status.INCONCLUSIVE):
        if EXIT_CODES[status] in codes:
            return EXIT_CODES[status]
    return 0


def _plots(scene, cert, out: str) -> int:
    """Draw the figures of a proved scene (float drawings of certified objects; never a verdict)."""
    from .kinds import plots_hook
    draw = plots_hook(scene.kind)
    if draw is None:
        print(f"rigor-gyro: {scene.name}: kind {scene.kind!r} has no figures; --plots ignored", file=sys.stderr)
        return 0
    try:
        import matplotlib  # noqa: F401  (optional extra, imported only here)
    except ImportError:
        print("rigor-gyro: error: --plots needs matplotlib: pip install 'rigor_gyro[plots]'", file=sys.stderr)
        return EXIT_BAD_INPUT
    for path in draw(scene, cert, out):
        print(f"{scene.name}: figure -> {path}")
    return 0


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    if args.command == "list":
        return _cmd_list()
    return _cmd_prove(args)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
