"""Benchmarks: error against run time, per scene and precision. Prints a table; asserts nothing.

    python benchmarks/run.py [--repeat 3]

For each built-in scene and each starting precision, proves the scene with ``maxprec = prec`` (no
escalation) and reports the wall time (best of ``--repeat``), the verdict, and the largest relative
width (2 rad / |mid|) over the scene's quantities named in ``KEY_QUANTITIES``, plus the same for
extreme parameter sets (stiff cases). Timing lives here, never in the tests.
"""
from __future__ import annotations

import argparse
import time

from flint import arb

from rigor_gyro.prover import prove_scene
from rigor_gyro.scene import load_scene, parse_scene

#: per kind, the quantities whose worst relative width is reported
KEY_QUANTITIES = {"eigenfrequencies": ("omega_", "freq_hz_"),
                  "lyapunov": ("m", "M", "p", "R1", "R2", "c_star", "R_sup_at_mu_best"),
                  "periodic_orbit": ("theta_star", "multiplier_modulus_", "stability_margin")}

EXTREME = {
    "b near 1": dict(a="15.08", b="1.0001", eps="0.1076", Omega2="0.629"),
    "a near b": dict(a="6.1541", b="6.154", eps="0.1076", Omega2="0.629"),
    "eps tiny": dict(a="15.08", b="6.154", eps="1e-9", Omega2="0.629"),
    "Omega2 huge": dict(a="15.08", b="6.154", eps="0.1076", Omega2="1e8"),
    "Omega2 tiny": dict(a="15.08", b="6.154", eps="0.1076", Omega2="1e-9"),
}

LYAPUNOV_EXTREME = {
    "H = 1e6": {"H": "1e6"},
    "H = 10": {"H": "10"},
    "linear moment": {"moment": "linear"},
    "x2* = 1.5": {"x2_star": "1.5"},
    "a = 1e-6": {"a": "1e-6"},
    "a = 1e4": {"a": "1e4"},
}


def max_rel_width(cert) -> str:
    worst = None
    keys = KEY_QUANTITIES.get(cert.scene["kind"], ())
    for name, x in cert.quantities.items():
        if any(name == k or (k.endswith("_") and name.startswith(k)) for k in keys) and x.is_finite() \
                and not x.contains(0):
            w = 2 * x.rad() / abs(x.mid())
            worst = w if worst is None or w > worst else worst
    return "-" if worst is None else worst.str(3, radius=False)


def timed(scene, prec: int, repeat: int):
    best, cert = float("inf"), None
    for _ in range(repeat):
        t = time.perf_counter()
        cert = prove_scene(scene, prec=prec, maxprec=prec)
        best = min(best, time.perf_counter() - t)
    return best, cert


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    rows = []
    from rigor_gyro.scene import builtin_scenes
    scenes = [(name, load_scene(name)) for name in builtin_scenes()]
    for label, params in EXTREME.items():
        body = "\n".join(f'{k} = "{v}"' for k, v in params.items())
        scenes.append((f"eigfreq: {label}", parse_scene(f'name = "x"\nkind = "eigenfrequencies"\n'
                                                        f'[parameters]\n{body}\n[claims]\nonly = ["roots", "branches"]\n')))
    base = dict(load_scene("agafonov2013").parameters)
    for label, change in LYAPUNOV_EXTREME.items():
        body = "\n".join(f'{k} = "{v}"' for k, v in dict(base, **change).items())
        scenes.append((f"lyapunov: {label}", parse_scene(f'name = "x"\nkind = "lyapunov"\n[parameters]\n{body}\n')))
    for name, scene in scenes:
        for prec in (64, 128, 256):
            t, cert = timed(scene, prec, args.repeat)
            rows.append((name, prec, cert.verdict.value, max_rel_width(cert), f"{1000 * t:.1f}"))
    widths = [max(len(str(r[i])) for r in rows + [("scene", "bits", "verdict", "max rel width", "ms")]) for i in range(5)]
    header = ("scene", "bits", "verdict", "max rel width", "ms")
    print("  ".join(h.ljust(w) for h, w in zip(header, widths)))
    for r in rows:
        print("  ".join(str(c).ljust(w) for c, w in zip(r, widths)))


if __name__ == "__main__":
    main()
