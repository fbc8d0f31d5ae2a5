"""Independent re-check of a ``[system]`` eigenfrequency certificate (``rigor-gyro check``).

The prover builds P(lambda) = det(lambda^2 M + lambda (G + D) + K) by exact evaluation and interpolation and
isolates the frequency polynomial's roots with Arb's root finder. This checker does neither: from the scene's
exact matrices it

* expands the determinant along rows over polynomial entries (:func:`rigor_gyro.core.polymat.det_by_expansion`,
  a different computation of the same exact polynomial), reads off the multiplicity of lambda = 0 and the odd
  terms, and forms Q(omega) itself;
* counts the distinct positive real roots of Q by a Sturm sequence and checks Q squarefree (exact): "m real,
  positive, simple roots" (``roots``, ``stability``) is re-proved, or its failure re-derived, without any root
  finder;
* checks that each stored omega_j interval holds a root by an exact sign change, the intervals disjoint and
  increasing, m of them, and refines each root inside its interval (interval Newton or exact bisection);
* recomputes freq_hz_j and each bracket's bounds in balls at the checker's precision from the refined roots,
  checks the stored enclosures contain them, and re-decides ``brackets`` per root.

Guarantee: a passed check of a ``proved`` claim is an independent proof of its statement for the model as
written in the scene; every stored enclosure it lists is certified to contain its value.
"""
from __future__ import annotations

from fractions import Fraction

from flint import arb, fmpq, fmpq_poly

from ...check import CheckResult
from ...core.balls import ball, certainly_gt, certainly_le, current_precision, working_precision
from ...core.polymat import det_by_expansion
from ...core.polyroots import series_function
from ...core.roots import RootStatus, newton_root
from ...core.stored import encloses, fmpq_of, interval
from .system_model import NotRealBound, SystemModel

__all__ = ["check_system", "frequency_data", "positive_root_count", "refine_in"]


def positive_root_count(p: fmpq_poly) -> int:
    """The number of distinct real roots of p in (0, oo), exactly (Sturm's theorem; needs p(0) != 0)."""
    seq = [p, p.derivative()]
    while seq[-1].degree() > 0:
        r = -(seq[-2] % seq[-1])
        if r == 0:
            break
        seq.append(r)

    def changes(values) -> int:
        s = [v for v in values if v != 0]
        return sum(1 for x, y in zip(s, s[1:]) if (x > 0) != (y > 0))
    return changes([q(0) for q in seq]) - changes([q[q.degree()] for q in seq if q.degree() >= 0])


def refine_in(p: fmpq_poly, lo: Fraction, hi: Fraction, bits: int) -> arb | None:
    """A ball around the root of p in the stored [lo, hi]: the exact rational when lo == hi is a root, else
    (after an exact strict sign change of p) interval Newton to about 2^-bits relative, or 200 exact
    bisections where Newton does not prove uniqueness; None when [lo, hi] shows no root."""
    a, b = fmpq_of(lo), fmpq_of(hi)
    if a == b:
        return arb(a) if p(a) == 0 else None
    pa, pb = p(a), p(b)
    if pa == 0 or pb == 0 or (pa > 0) == (pb > 0):
        return None
    r = newton_root(series_function(p), arb(a), arb(b), rel_tol=arb(2) ** (8 - bits))
    if r.status is RootStatus.UNIQUE and r.enclosure is not None and r.enclosure.is_finite():
        return r.enclosure
    for _ in range(200):
        m = (a + b) / 2
        pm = p(m)
        if pm == 0:
            return arb(m)
        if (pm > 0) == (pa > 0):
            a, pa = m, pm
        else:
            b = m
    return arb(a).union(arb(b))


def frequency_data(model: SystemModel) -> tuple[fmpq_poly, int, list[int], fmpq_poly | None]:
    """(P, multiplicity of lambda = 0, odd powers of P / lambda^mu with nonzero coefficients, Q or None),
    with P by Laplace expansion (not the prover's interpolation)."""
    P = det_by_expansion([model.matrix("K"), model.matrix("G") + model.matrix("D"), model.matrix("M")])
    c = P.coeffs()
    mu = 0
    while c[mu] == 0:
        mu += 1
    odd = [k + mu for k in range(1, len(c) - mu, 2) if c[k + mu] != 0]
    if mu != model.zero_roots or odd:
        return P, mu, odd, None
    even = c[mu::2]
    Q = fmpq_poly([x if k % 2 == 0 else -x for k, x in enumerate(even)])
    # monic, as the certificate states it (the prover divides by the leading coefficient, det M up to sign)
    return P, mu, odd, Q / Q.leading_coefficient()


def _holds_for(Q: fmpq_poly | None) -> bool:
    """Q squarefree (exact) with every root real and positive (Sturm count == degree): the roots
    lambda = +-i sqrt(omega) simple and on the imaginary axis."""
    return (Q is not None and Q.gcd(Q.derivative()).degree() == 0 and Q(0) != 0
            and positive_root_count(Q) == Q.degree())


def stability_facts(P: fmpq_poly, mu: int, odd: list[int], z: int) -> tuple[bool, fmpq_poly | None]:
    """(whether claim ``stability`` holds, the frequency polynomial it rests on) when lambda = 0 has multiplicity
    mu != z = zero_roots: false when mu >= 2 and mu > z (a multiple zero root beyond the declared ones);
    otherwise (mu < z, or mu = 1 > z = 0) decided on P / lambda^mu: no odd term, its Q squarefree with all roots
    real and positive. Re-derived here from the Laplace expansion (not the prover's interpolation)."""
    if mu >= 2 and mu > z or odd:
        return False, None
    even = P.coeffs()[mu::2]
    Q = fmpq_poly([x if k % 2 == 0 else -x for k, x in enumerate(even)])
    Q = Q / Q.leading_coefficient()
    return _holds_for(Q), Q


def check_system(model: SystemModel, data: dict) -> list[CheckResult]:
    """Re-decide every claim of a ``[system]`` certificate; see the module docstring."""
    out: list[CheckResult] = []
    say = lambda item, ok, msg: out.append(CheckResult(item, bool(ok), msg))
    q = dict(data["quantities"])
    verified: set[str] = set()
    for name in list(q):                 # "nan", "inf": no enclosure (an older prover stored a bracket's nan bound)
        try:
            interval(q[name])
        except (ValueError, TypeError, KeyError) as e:
            say(name, False, f"the stored enclosure is not a finite interval ({e})")
            del q[name]
    P, mu, odd, Q = frequency_data(model)
    structural_ok = Q is not None
    squarefree = positive = None
    if structural_ok:
        squarefree = Q.gcd(Q.derivative()).degree() == 0
        positive = positive_root_count(Q) if squarefree and Q(0) != 0 else None
    m = Q.degree() if structural_ok else None
    holds = structural_ok and squarefree and positive == m
    stable, Q_stability = (holds, Q) if mu == model.zero_roots else stability_facts(P, mu, odd, model.zero_roots)
    frequency = {"roots": Q, "stability": Q_stability}     # the frequency polynomial each claim rests on
    # the stored roots
    names = sorted((k for k in q if k.startswith("omega_")), key=lambda k: int(k.split("_")[1]))
    omegas = None
    if names:
        ok = structural_ok and names == [f"omega_{j}" for j in range(1, len(names) + 1)] and len(names) == m
        ivs = [interval(q[n]) for n in names]
        refined = []
        if ok:
            for n, (lo, hi) in zip(names, ivs):
                r = refine_in(Q, lo, hi, current_precision())
                if r is None:
                    say(n, False, f"Q has no sign change on the stored [{q[n]['lo']}, {q[n]['hi']}]")
                    ok = False
                    break
                refined.append(r)
                verified.add(n)
            ok = ok and all(ivs[i][1] < ivs[i + 1][0] for i in range(len(ivs) - 1))
        if ok:
            omegas = refined
        else:
            say("omega", False, f"the stored omega_j are not {m} disjoint increasing intervals, each a sign change of Q")
    if omegas is not None and model.hz_scale is not None:
        s = ball(model.hz())
        for j, w in enumerate(omegas, start=1):
            name = f"freq_hz_{j}"
            if name in q:
                if encloses(interval(q[name]), s * w.sqrt()):
                    verified.add(name)
                else:
                    say(name, False, "the stored enclosure does not contain hz_scale sqrt(omega_j)")
    brackets: dict[int, object] = {}
    if omegas is not None:
        for j in range(1, len(model.brackets) + 1):
            try:
                lo, hi = model.bracket_balls(j)
            except NotRealBound as e:
                brackets[j] = str(e)
                continue
            brackets[j] = (lo, hi)
            w = omegas[j - 1]
            for name, x in ((f"bracket_{j}_lo", lo), (f"bracket_{j}_hi", hi), (f"bracket_{j}_slack", (w - lo).min(hi - w))):
                if name in q:
                    if encloses(interval(q[name]), x):
                        verified.add(name)
                    else:
                        say(name, False, "the stored enclosure does not contain the value recomputed from the refined root")
    rel = model.rel_width.rational
    for c in data["claims"]:
        cid, st = c["id"], c["status"]
        if st == "inconclusive":
            say(cid, True, "inconclusive: claims nothing")
            continue
        proved = st == "proved"
        facts = (f"lambda = 0 of multiplicity {mu} (declared {model.zero_roots}); odd terms {odd}; squarefree Q: "
                 f"{squarefree}; positive real roots by Sturm: {positive} of {m}")
        if cid == "stability":
            if mu != model.zero_roots:
                facts += f"; stability on P / lambda^{mu}: {stable}"
            say(cid, stable if proved else not stable, "re-derived by Laplace expansion and Sturm: " + facts)
        elif cid == "roots":
            if proved:
                wide = [n for n in names if (lambda lo, hi: hi - lo > rel * abs(lo))(*interval(q[n]))]
                say(cid, holds and omegas is not None and not wide,
                    facts + f"; {len(names)} stored intervals verified: {omegas is not None}"
                    + (f"; wider than rel_width: {wide}" if wide else ""))
            else:
                say(cid, not holds, "re-derived by Laplace expansion and Sturm: " + facts)
        elif cid == "brackets":
            if omegas is None:
                say(cid, False, "the roots this claim rests on are not verified")
                continue
            inside, outside = [], []
            for j in range(1, len(model.brackets) + 1):
                br = brackets[j]
                if isinstance(br, str):
                    outside.append(j)
                    continue
                lo, hi = br
                w = omegas[j - 1]
                if certainly_le(lo, w) and certainly_le(w, hi):
                    inside.append(j)
                elif certainly_gt(lo, w) or certainly_gt(w, hi):
                    outside.append(j)
            per = {r.get("root"): r.get("status") for r in (c.get("details") or {}).get("per_root", [])}
            claimed_out = [j for j in range(1, len(model.brackets) + 1) if per.get(f"omega_{j}") == "refuted"]
            if proved:
                say(cid, len(inside) == len(model.brackets), f"brackets re-decided: inside for {inside}")
            else:
                say(cid, bool(claimed_out) and set(claimed_out) <= set(outside),
                    f"brackets re-decided: certainly violated for {outside}, the certificate names {claimed_out}")
        else:
            say(cid, False, f"unknown claim {cid!r} for a [system] scene")
            continue
        if not proved and cid in ("roots", "stability") and c.get("counterexample"):
            Q = frequency[cid]
            say(f"{cid} counterexample", *counterexample_ok(c["counterexample"], P, mu, odd, Q, model.zero_roots))
    unverified = sorted(set(q) - verified)
    say("quantities", not unverified, f"{len(verified)} stored enclosures verified"
        + (f"; not verified: {unverified}" if unverified else ""))
    return out


def _box_holds_root(box: dict, roots: list) -> bool:
    """Whether the stored box {"re": [lo, hi], "im": [lo, hi]} certainly contains one of ``roots`` (acb balls,
    each holding exactly one root)."""
    (rl, rh), (il, ih) = interval(box["re"]), interval(box["im"])
    for z in roots:
        re, im = z.real, z.imag
        if (arb(fmpq_of(rl)) <= re.lower() and re.upper() <= arb(fmpq_of(rh))
                and arb(fmpq_of(il)) <= im.lower() and im.upper() <= arb(fmpq_of(ih))):
            return True
    return False


def _is_point(box: dict) -> bool:
    (rl, rh), (il, ih) = interval(box["re"]), interval(box["im"])
    return rl == rh and il == ih


def _exact_root(poly, box: dict) -> bool:
    """Whether the point box {"re": [x, x], "im": [y, y]} is exactly a root of the exact polynomial: p(x + i y) = 0
    by Horner's rule in exact complex rationals (review: a rational root stored as [1, 1] was rejected, Arb's ball
    around it never fitting inside a point)."""
    x, y = fmpq_of(interval(box["re"])[0]), fmpq_of(interval(box["im"])[0])
    re, im = fmpq(0), fmpq(0)
    for c in reversed(poly.coeffs()):
        re, im = re * x - im * y + c, re * y + im * x
    return re == 0 and im == 0


#: the highest precision at which the checker computes a polynomial's roots to fit them in stored boxes
ROOT_BOX_MAXPREC = 8192


def _boxes_hold_roots(poly, boxes: list) -> bool:
    """Whether each stored box certainly holds a root of ``poly`` (exact): Arb's roots at the checker's precision,
    doubled (up to ROOT_BOX_MAXPREC) while a box is narrower than they are (the prover may store boxes refined
    beyond the certificate's precision)."""
    # a box of zero width (a rational root, stored as [r, r]) can hold no ball of positive radius: decided exactly
    point = [b for b in boxes if _is_point(b)]
    if not all(_exact_root(poly, b) for b in point):
        return False
    boxes = [b for b in boxes if not _is_point(b)]
    if not boxes:
        return True
    p = current_precision()
    while True:
        with working_precision(p):
            roots = [z for z, _ in poly.complex_roots()]
            if all(_box_holds_root(b, roots) for b in boxes):
                return True
        if 2 * p > ROOT_BOX_MAXPREC:
            return False
        p *= 2


def counterexample_ok(ce: dict, P, mu: int, odd: list[int], Q, zero_roots: int) -> tuple[bool, str]:
    """A refuted claim's stored counterexample re-derived: its exact parts (the characteristic and frequency
    polynomials' coefficients, the zero-root multiplicity, the odd terms) equal to the checker's own (Laplace
    expansion), and each stored root box certainly holding a root of that polynomial (Arb's roots of the
    checker's exact polynomial at its precision). ``odd``: the powers of P (not of P / lambda^mu) above
    lambda^mu whose odd distance from mu has a nonzero coefficient, as :func:`frequency_data` gives them."""
    c = P.coeffs()
    checks = {"characteristic_coefficients": [str(x) for x in c],
              "zero_root_multiplicity": mu, "zero_roots_declared": zero_roots,
              "odd_powers": list(odd), "odd_coefficients": [str(c[k]) for k in odd]}   # odd: powers of P
    if Q is not None:
        checks["frequency_polynomial"] = [str(x) for x in Q.coeffs()]
        checks["gcd_with_derivative"] = str(Q.gcd(Q.derivative()))
    for key, want in checks.items():
        if key in ce and ce[key] != want:
            return False, f"the stored {key} is not the re-derived one"
    unknown = set(ce) - set(checks) - {"nonreal_roots", "negative_roots", "offaxis_roots"}
    if unknown:
        return False, f"unknown counterexample data {sorted(unknown)}"
    if "nonreal_roots" in ce or "negative_roots" in ce:
        if Q is None:
            return False, "roots of the frequency polynomial stored, but P is not lambda^z times an even polynomial"
        boxes = list(ce.get("nonreal_roots", [])) + [{"re": r, "im": ["0", "0"]} for r in ce.get("negative_roots", [])]
        if not _boxes_hold_roots(Q, boxes):
            return False, "a stored root box of the frequency polynomial holds none of its roots"
        if not all(interval(b["im"])[0] > 0 or interval(b["im"])[1] < 0 for b in ce.get("nonreal_roots", [])):
            return False, "a stored non-real root box does not exclude the real axis"
        if not all(interval(r)[1] < 0 for r in ce.get("negative_roots", [])):
            return False, "a stored negative root interval is not below 0"
    if "offaxis_roots" in ce:
        if not _boxes_hold_roots(fmpq_poly(c[mu:]), ce["offaxis_roots"]):
            return False, "a stored off-axis root box holds none of the roots of P / lambda^z"
        if not all(interval(b["re"])[0] > 0 or interval(b["re"])[1] < 0 for b in ce["offaxis_roots"]):
            return False, "a stored off-axis root box does not exclude the imaginary axis"
    return True, "the counterexample re-derived from the checker's own expansion"
