"""Independent re-check of an eigenfrequency certificate (``rigor-gyro check``).

The prover isolates the quartic's roots with Arb's polynomial root finder and decides the claims on
its balls. This checker does not call it: from the exact parameters it rebuilds the quartic Q and
the quadratics (4) in rational arithmetic and

* counts the distinct positive real roots of Q by a Sturm sequence (exact), and checks that Q is
  squarefree: "four real, positive, simple roots" is then re-proved without any root finder;
* checks that each stored omega_j (and nu_k) interval holds a root by an exact sign change (or is
  the exact rational itself), the four intervals disjoint and increasing, and refines each root by
  exact rational bisection inside its interval to the checker's precision;
* recomputes every closed-form quantity (bounds (5), brackets (7)-(10), approximations, Hz) in balls
  at twice the certificate's precision from the refined roots, checks that the stored [lo, hi]
  contains it, and re-decides every claim on these balls; a refuted claim has its counterexample
  re-derived (Sturm count, exact gcd, exact equality of nus, an exactly vanishing denominator).

Guarantee: a passed check of a ``proved`` claim is an independent proof of its statement (given the
model of :mod:`.model`); the stored enclosures it lists are certified to contain their values.
"""
from __future__ import annotations

from fractions import Fraction

from flint import arb, fmpq, fmpq_poly

from ...check import CheckResult
from ...core.balls import ball, certainly_ge, certainly_gt, certainly_le, certainly_lt, current_precision
from ...core.polyroots import series_function
from ...core.roots import RootStatus, newton_root
from ...core.stored import encloses, fmpq_of, interval, meets
from .system_check import check_system
from .system_model import SystemModel
from .model import (BRACKETS, NotReal, Params, approximation, approx_rel_error, bracket, bracket_slack, characteristic_quartic, nu_bounds,
                    nu_identities, nu_quadratics, nus_exactly_equal, r2_denominator)

__all__ = ["branch_sides", "check", "sturm_positive_roots"]


def _sign(x: fmpq) -> int:
    return (x > 0) - (x < 0)


def sturm_positive_roots(p: fmpq_poly) -> int:
    """The number of distinct real roots of p in (0, oo), exactly (Sturm's theorem; p(0) != 0)."""
    seq = [p, p.derivative()]
    while seq[-1].degree() > 0:
        r = -(seq[-2] % seq[-1])
        if r == 0:
            break
        seq.append(r)
    def changes(values):
        s = [v for v in values if v != 0]
        return sum(1 for a, b in zip(s, s[1:]) if a != b)
    at0 = changes([_sign(q(0)) for q in seq])
    at_inf = changes([_sign(q[q.degree()]) for q in seq if q.degree() >= 0])
    return at0 - at_inf


def _refine(p: fmpq_poly, lo: Fraction, hi: Fraction, bits: int) -> arb | None:
    """A ball around the root of p in [lo, hi] (an exact sign change, or lo == hi an exact root),
    refined to relative width about 2^-bits: interval Newton on the bracket when it proves the root
    unique there (fast at any precision), else 200 exact bisections; None if [lo, hi] shows no root."""
    a, b = fmpq_of(lo), fmpq_of(hi)
    if a == b:
        return arb(a) if p(a) == 0 else None
    pa, pb = p(a), p(b)
    if pa == 0 or pb == 0 or _sign(pa) == _sign(pb):
        return None
    r = newton_root(series_function(p), arb(a), arb(b), rel_tol=arb(2) ** (8 - bits))
    if r.status is RootStatus.UNIQUE and r.enclosure is not None and r.enclosure.is_finite():
        return r.enclosure
    for _ in range(200):
        m = (a + b) / 2
        pm = p(m)
        if pm == 0:
            return arb(m)
        if _sign(pm) == _sign(pa):
            a, pa = m, pm
        else:
            b = m
    return arb(a).union(arb(b))


def branch_sides(omegas: list[arb], nus: dict[int, arb], empty: dict[int, bool]) -> tuple[list[bool], list[bool]]:
    """For each omega_j, whether it is certainly strictly inside its branch (0, nu1), (nu2, nu3), (nu4, nu5),
    (nu6, oo), and whether it is certainly outside it: on or beyond an end, or the branch exactly empty
    (``empty[j]``: nu2 = nu3 or nu4 = nu5 decided exactly). Both False: undecided. An inverted branch
    (lo > hi, where the nu ordering fails) holds no omega: both ends are tested, never either one."""
    iv = [(arb(0), nus[1]), (nus[2], nus[3]), (nus[4], nus[5]), (nus[6], None)]
    inside = [certainly_lt(lo, w) and (hi is None or certainly_lt(w, hi)) for w, (lo, hi) in zip(omegas, iv)]
    outside = [certainly_ge(lo, w) or (hi is not None and certainly_ge(w, hi)) or empty.get(j, False)
               for j, (w, (lo, hi)) in enumerate(zip(omegas, iv), start=1)]
    return inside, outside


class _Checker:
    def __init__(self, model, data: dict):
        self.m, self.data = model, data
        self.q = data["quantities"]
        self.results: list[CheckResult] = []
        self.verified: set[str] = set()
        a, b, e, W = (model.q(k) for k in ("a", "b", "eps", "Omega2"))
        self.exact = (a, b, e, W)
        self.Q = characteristic_quartic(a, b, e, W)
        self.q14, self.q26 = nu_quadratics(a, b, e)
        self.P = Params(ball(a), ball(b), ball(e), ball(W))
        self.bits = current_precision()

    def say(self, item: str, ok: bool, message: str) -> bool:
        self.results.append(CheckResult(item, ok, message))
        return ok

    def stored(self, name: str):
        return interval(self.q[name]) if name in self.q else None

    def contains(self, name: str, x: arb) -> bool:
        """The stored enclosure of ``name`` contains the checker's ball x (marks it verified)."""
        s = self.stored(name)
        if s is None:
            return True        # not stored: nothing claimed about it
        ok = encloses(s, x)
        if ok:
            self.verified.add(name)
        else:
            self.say(name, False, f"stored [{self.q[name]['lo']}, {self.q[name]['hi']}] does not contain the "
                                  f"value recomputed from the exact parameters")
        return ok

    # ------------------------------------------------------------------ roots and nus from the data
    def omegas(self) -> list[arb] | None:
        names = [f"omega_{j}" for j in range(1, 5)]
        if not all(n in self.q for n in names):
            return None
        ivs = [self.stored(n) for n in names]
        out = []
        for n, (lo, hi) in zip(names, ivs):
            r = _refine(self.Q, lo, hi, self.bits)
            if r is None:
                self.say(n, False, f"Q has no sign change on the stored [{self.q[n]['lo']}, {self.q[n]['hi']}]")
                return None
            out.append(r)
            self.verified.add(n)
        if not all(ivs[i][1] < ivs[i + 1][0] for i in range(3)):
            self.say("omega", False, "the stored omega intervals are not disjoint and increasing")
            return None
        return out

    def nus(self) -> dict[int, arb] | None:
        ident = nu_identities(*self.exact[:3])
        out = {}
        for k, idn in ident.items():
            name = f"nu_{k}"
            if name not in self.q:
                return None
            lo, hi = self.stored(name)
            if idn[0] == "rational":
                r = idn[1]
                if not (lo <= Fraction(int(r.p), int(r.q)) <= hi):
                    self.say(name, False, "the stored interval does not contain the exact rational")
                    return None
                out[k] = arb(r)
            else:
                x = _refine(idn[1], lo, hi, self.bits)
                if x is None:
                    self.say(name, False, "the quadratic (4) has no sign change on the stored interval")
                    return None
                out[k] = x
            self.verified.add(name)
        for q, (i, j) in ((self.q14, (1, 4)), (self.q26, (2, 6))):
            if not self.stored(f"nu_{i}")[1] < self.stored(f"nu_{j}")[0]:
                self.say("nu", False, f"nu_{i} and nu_{j} intervals are not disjoint and ordered")
                return None
        return out


def check(model, data: dict) -> list[CheckResult]:
    """Re-decide every claim of an eigenfrequency certificate; see the module docstring (a ``[system]``
    certificate: :func:`.system_check.check_system`)."""
    if isinstance(model, SystemModel):
        return check_system(model, data)
    ck = _Checker(model, data)
    say = ck.say
    Q = ck.Q
    a, b, e, _ = ck.exact
    squarefree = Q.gcd(Q.derivative()).degree() == 0
    positive = sturm_positive_roots(Q) if squarefree and Q(0) != 0 else None
    omegas = ck.omegas()
    nus = ck.nus()
    ident = nu_identities(a, b, e)
    # every closed-form quantity, recomputed at the checker's precision, and checked against the store
    bounds = nu_bounds(ck.P) if nus is not None else {}
    for k, (lo, hi) in bounds.items():
        ck.contains(f"nu_{k}_lower_bound", lo)
        ck.contains(f"nu_{k}_upper_bound", hi)
    brackets: dict[int, tuple[arb, arb] | str] = {}
    approx: dict[int, arb] = {}
    if omegas is not None:
        for j in range(1, 5):
            if j in (3, 4) and r2_denominator(a, b, e) == 0:
                brackets[j] = "R2's denominator b/(b-1) - eps a/(b(a-b)) is exactly 0: the bracket is undefined"
            else:
                try:
                    brackets[j] = bracket(j, ck.P, reading="intended")
                    ck.contains(f"bracket_{j}_lo", brackets[j][0])
                    ck.contains(f"bracket_{j}_hi", brackets[j][1])
                    ck.contains(f"bracket_{j}_slack", bracket_slack(j, ck.exact, omegas[j - 1]))
                except NotReal as err:
                    brackets[j] = f"no real value ({err})"
            try:
                approx[j] = approximation(j, ck.P)
                ck.contains(f"approx_omega_{j}", approx[j])
                ck.contains(f"approx_rel_error_{j}", approx_rel_error(j, ck.exact, omegas[j - 1]))
            except NotReal:
                pass
        if model.hz_scale is not None:
            s = ball(model.hz_scale.fmpq())
            for j, w in enumerate(omegas, start=1):
                ck.contains(f"freq_hz_{j}", s * w.sqrt())
    rel = model.rel_width.fmpq()
    rel_q = Fraction(int(rel.p), int(rel.q))
    for c in data["claims"]:
        cid, st = c["id"], c["status"]
        if st == "inconclusive":
            say(cid, True, "inconclusive: claims nothing")
            continue
        proved = st == "proved"
        if cid == "roots":
            if proved:
                wide = [j for j in range(1, 5) if omegas is not None and
                        (lambda lo, hi: hi - lo > rel_q * abs(lo))(*ck.stored(f"omega_{j}"))]
                say(cid, squarefree and positive == 4 and omegas is not None and not wide,
                    f"squarefree: {squarefree}; positive real roots by Sturm: {positive}; four stored intervals, each "
                    f"an exact sign change: {omegas is not None}" + (f"; wider than rel_width: {wide}" if wide else ""))
            else:
                say(cid, not squarefree or positive != 4,
                    f"re-derived: squarefree {squarefree}, positive real roots by Sturm {positive}")
            continue
        if nus is None or (omegas is None and cid != "nu_ordering"):
            say(cid, False, "the enclosures this claim rests on are not verified")
            continue
        if cid == "nu_ordering":
            chain = [arb(0)] + [nus[k] for k in range(1, 7)]
            if proved:
                say(cid, all(certainly_lt(chain[i], chain[i + 1]) for i in range(6)), "0 < nu1 < ... < nu6 re-decided")
                continue
            viol = (c.get("counterexample") or {}).get("violations", [])
            ok = bool(viol)
            names = ["0"] + [f"nu{k}" for k in range(1, 7)]
            for v in viol:
                if v.get("left") not in names or v.get("right") not in names:
                    ok = False
                    break
                i, j = names.index(v["left"]), names.index(v["right"])
                equal = i > 0 and j == i + 1 and nus_exactly_equal(ident[i], ident[j])
                values_ok = all(meets(interval(v[f"{side}_value"]), chain[k])
                                for side, k in (("left", i), ("right", j)) if f"{side}_value" in v)
                ok = ok and j == i + 1 and values_ok and (equal if "exactly_equal" in v else certainly_ge(chain[i], chain[j]))
            say(cid, ok, "the stored violations re-derived" if ok else "a stored violation does not hold")
        elif cid == "branches":
            empty = {2: nus_exactly_equal(ident[2], ident[3]), 3: nus_exactly_equal(ident[4], ident[5])}
            inside, outside = branch_sides(omegas, nus, empty)
            if proved:
                say(cid, all(inside), "each omega_j strictly inside its branch, re-decided")
            else:
                items = (c.get("counterexample") or {}).get("outside", [])
                roots_named = [o.get("root") for o in items]
                ok = bool(items) and all(r in (f"omega_{j}" for j in range(1, 5)) for r in roots_named)
                ok = ok and all(outside[int(o["root"][6]) - 1] and meets(interval(o["value"]), omegas[int(o["root"][6]) - 1])
                                for o in items)
                say(cid, ok, "the roots outside their branch re-derived")
        elif cid == "nu_bounds":
            holds = all(certainly_le(bounds[k][0], nus[k]) and certainly_le(nus[k], bounds[k][1]) for k in bounds)
            fails = any(certainly_gt(bounds[k][0], nus[k]) or certainly_gt(nus[k], bounds[k][1]) for k in bounds)
            say(cid, holds if proved else fails, "bounds (5) recomputed and re-decided")
        elif cid.startswith("bracket_"):
            j = int(cid.split("_")[1])
            br = brackets.get(j)
            if isinstance(br, str):
                say(cid, not proved, br)
                continue
            lo, hi = br
            w = omegas[j - 1]
            decided = (certainly_le(lo, w) and certainly_le(w, hi)) if proved else (certainly_gt(lo, w) or certainly_gt(w, hi))
            say(cid, decided, f"bracket {BRACKETS[j].eq} recomputed and re-decided against the refined root")
        elif cid == "approximations":
            say(cid, proved and len(approx) == 4, "the four approximations and their relative errors recomputed")
        else:
            say(cid, False, f"unknown claim {cid!r}")
    required = {"roots": [f"omega_{j}" for j in range(1, 5)],
                "nu_bounds": [f"nu_{k}_{s}_bound" for k in (1, 2, 4, 6) for s in ("lower", "upper")],
                "approximations": [f"approx_{n}_{j}" for j in range(1, 5) for n in ("omega", "rel_error")]}
    for j in range(1, 5):
        required[f"bracket_{j}"] = [f"bracket_{j}_lo", f"bracket_{j}_hi"]
    for c in data["claims"]:
        missing = [n for n in required.get(c["id"], []) if n not in data["quantities"]]
        if c["status"] == "proved" and missing:
            say(c["id"], False, f"a proved {c['id']} without the quantities its statement names: {missing}")
    unverified = sorted(set(data["quantities"]) - ck.verified)
    say("quantities", not unverified, f"{len(ck.verified)} stored enclosures verified"
        + (f"; not verified: {unverified}" if unverified else ""))
    return ck.results
