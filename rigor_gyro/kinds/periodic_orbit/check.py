"""Independent re-check of a periodic-orbit certificate (``rigor-gyro check``).

The prover searches: it bisects the range of the half-period function g, runs interval Newton with
restarts, merges roots on shared endpoints, searches for witnesses. This checker only verifies the
stored outcome of that search, at twice the certificate's precision:

* the exact moment identities e1^T M^j e = 0 (j <= 3), so g = O(theta^5) at 0, and g^(5)/5! > 0 on
  [0, theta_min] (Taylor model): no root in (0, theta_min];
* the stored pieces tile [theta_min, T] exactly, for the function the witness names (g, or
  G = g prod |1 + exp(lambda theta)|^2 over the complex pairs: the same roots, no poles near the axis); each "empty" piece holds no root (g excludes 0 on
  it, or one Newton image misses it, or the envelope bound: G = A + B cos + C sin of the nutation
  phase with slowly varying A, B, C and |A| > hypot(B, C)), each "unique" piece exactly one (a Newton image inside the
  current box, by its own short Newton loop; a piece merged at ``splits`` is two unique halves whose
  roots coincide: unique on the hull of both enclosures); a "phase_empty" / "phase_unique" piece (a
  fast nutation's half-period) none / exactly one, by the checker's own leaves (:mod:`.phase_pieces`:
  G of one sign, or G' of one sign for the whole piece, on each leaf); beyond T, when the whole of (0, oo) is
  claimed, the tail bound a T + b - B(T) > 0;
* per root, its classification: a spurious root's witness (beta(t) < 0 at the stored t, or
  beta'(0) < 0), a genuine root's beta'(0) > 0, beta' > 0 on [0, d1], beta' < 0 on
  [right_start, theta], beta > 0 on each stored middle piece (tiling [d1, right_start]);
* the multipliers of the scene's orbit: the Jacobian recomputed at the checker's own enclosure of
  theta*, its eigenvalues by a different algorithm (van der Hoeven-Mourrain) with the smallest
  through the exact Liouville product; stability re-decided on these moduli;
* with option ``orbit`` (:mod:`.tracked`): the root nearest the option re-chosen and its nearness
  re-certified on the checker's own root enclosures; the four claims that follow it re-decided for
  that root only (genuine / spurious by its re-verified classification, stable by its own moduli);
* every stored quantity contains the checker's recomputed enclosure.

A scene with a ``[plant]`` table is checked by :mod:`.plant_check`.
"""
from __future__ import annotations

from flint import acb, acb_mat, arb

from ...check import CheckResult
from ...core.balls import (ball, certainly_gt, certainly_lt, certainly_negative, certainly_positive, interval)
from ...core.stored import encloses, fmpq_of, interval as stored_interval, number
from .claims import RootVerdict
from .g_roots import TAYLOR_ORDER
from .tracked import nearest_root
from .tracked_claims import TRACKED
from .check_verdicts import other_orbit_moduli, redecide
from .flow import (DegenerateSpectrum, Spectrum, g_coeffs, half_period_jacobian, moment_zero_orders, pole_free_coeffs,
                   orbit_expsums, tail_bound, taylor5_leading_coefficient, taylor_enclosure, x0_at)
from .paper import orbit_quantities
from .phase_pieces import phase_count, root_bracket
from .plant_check import check as plant_check
from .plant_model import PlantModel

__all__ = ["check"]

NEWTON_STEPS = 60
#: per claim, the quantities its statement names: a proved claim without them is not confirmed
REQUIRED = {"orbit_genuine": ("theta_star", "period"),
            "initial_point": ("beta_dot_0", "Omega_0", "i_0", "I_0"),
            "multipliers": tuple(f"multiplier_modulus_{j}" for j in range(1, 5))
            + tuple(f"multiplier_{j}_{p}" for j in range(1, 5) for p in ("re", "im")),
            "stable": ("stability_margin",)}


def _pt(text: str) -> arb:
    return arb(fmpq_of(number(text)))


class _G:
    """The isolated function (g, or the pole-free G = g K with the same roots) and its derivative on a
    ball by the flow's Taylor models (the model's evaluation; no search)."""

    def __init__(self, sp: Spectrum, function: str = "g"):
        self.sp = sp
        self.coeffs = (lambda c, n: pole_free_coeffs(sp, c, n)) if function == "pole_free" else \
            (lambda c, n: g_coeffs(sp, c, n))

    def both(self, X: arb) -> tuple[arb, arb]:
        g, dg = taylor_enclosure(self.coeffs, X, TAYLOR_ORDER, (0, 1))
        return g, dg

    def at(self, t: arb) -> arb:
        return self.coeffs(t, 1)[0]


def _newton(G: _G, X: arb) -> tuple[str, arb | None]:
    """("empty", None), ("unique", enclosure) or ("unknown", None) for the box X: Moore's theorem on
    x_{k+1} = x_k n N(x_k); every root of X stays in x_k, N(x) inside int(x) means exactly one."""
    g, _ = G.both(X)
    if not g.contains(0):
        return "empty", None
    x = X
    for _ in range(NEWTON_STEPS):
        m = arb(x.mid())
        gm = G.at(m)
        _, dg = G.both(x)
        if dg.contains(0) or not dg.is_finite():
            return "unknown", None
        n = m - gm / dg
        if not n.overlaps(x):
            return "empty", None
        if x.contains_interior(n):
            for _ in range(NEWTON_STEPS):          # refine: the root stays in the shrinking box
                m = arb(n.mid())
                _, dg = G.both(n)
                n2 = (m - G.at(m) / dg).intersection(n)
                if not certainly_lt(n2.rad(), n.rad()):
                    break
                n = n2
            return "unique", n
        x = x.intersection(n)
    return "unknown", None


def _phase_unique(G: _G, lo: arb, hi: arb) -> tuple[bool, arb | None]:
    """A phase_unique piece: exactly one root by :func:`.phase_pieces.phase_count` (the checker's own
    leaves), enclosed by its own certified sign change (:func:`.phase_pieces.root_bracket`) and
    refined by interval Newton when that lands (the classification needs a narrow theta)."""
    if not phase_count(G.coeffs, lo, hi, 1)[0]:
        return False, None
    s_lo = _strict_sign(G.coeffs(lo, 1)[0])
    br = root_bracket(G.coeffs, lo, hi, s_lo)
    if br is None:
        return False, None
    e = interval(*br)
    st, n = _newton(G, e)
    return True, (n if st == "unique" else e)


def _strict_sign(x: arb) -> int:
    return 1 if certainly_positive(x) else -1 if certainly_negative(x) else 0


def _monotone_root_free(G: _G, lo: arb, hi: arb) -> bool:
    """No root of g on [lo, hi] by monotonicity: g'' of one strict sign on the piece (so g' is strictly
    monotone there), g' of one strict sign at both ends (so g' != 0 on the piece: g strictly monotone),
    and g of one strict sign at both ends."""
    if not certainly_lt(lo, hi):
        return False
    d2 = taylor_enclosure(G.coeffs, interval(lo, hi), TAYLOR_ORDER, (2,))[0]
    a, b = G.coeffs(lo, 2), G.coeffs(hi, 2)
    s1, s2 = _strict_sign(a[1]), _strict_sign(b[1])
    s0, s3 = _strict_sign(a[0]), _strict_sign(b[0])
    return _strict_sign(d2) != 0 and s1 != 0 and s1 == s2 and s0 != 0 and s0 == s3


def _envelope_root_free(sp: Spectrum, lo: arb, hi: arb) -> bool:
    """See :func:`_envelope_lower`: its bound certainly > 0."""
    low = _envelope_lower(sp, lo, hi)
    return low is not None and certainly_positive(low)


def _envelope_lower(sp: Spectrum, lo: arb, hi: arb) -> arb | None:
    """A lower bound of sign(s) G over [lo, hi] (0 < lo < hi), None where the premises fail; no root of
    g there when it is > 0. The envelope bound, re-derived here: with the one
    complex pair lambda (Re lambda < 0) and rho = |E|, E = exp(lambda theta), the pole-free G equals
    A + B cos(Im lambda theta) + C sin(Im lambda theta) with A = s (1 + rho^2) + 2 Re q (1 - rho^2),
    B = 2 s rho, C = 4 Im q rho (q = pe_0 / lambda, s the real modes' and the linear term of g), so
    sign(s) G >= sign(s) A - hypot(B, C), evaluated without cancellation (1 - rho by expm1)."""
    if getattr(sp, "near_zero", None) is not None or not (certainly_positive(lo) and certainly_lt(lo, hi)):
        return None
    pairs = [m for m in sp.modes if m.weight == 2]
    if len(pairs) != 1:
        return None
    lam = pairs[0].lam
    X = interval(lo, hi)
    re = lam.real
    if not certainly_negative(re):
        return None
    q = pairs[0].pe[0] * lam.conjugate() / (lam.real ** 2 + lam.imag ** 2)
    s = -(sp.p0e[0] / 2) * X
    for m in sp.modes:
        if m.weight == 1:
            s = s - (m.pe[0] / m.lam * (m.lam * acb(X) / 2).tanh()).real
    sign = _strict_sign(s)
    if sign == 0:
        return None
    u = sign * s                                    # |s| > 0 on X
    one_minus = -(re * X).expm1()                   # 1 - rho
    one_minus_sq = -(2 * re * X).expm1()            # 1 - rho^2
    rho = (re * X).exp()
    if not (certainly_positive(u) and certainly_positive(one_minus)):
        return None

    def square(x: arb) -> arb:                      # x > 0: from its ends (a wide ball squared may reach < 0)
        return (x.lower() ** 2).lower().union((x.upper() ** 2).upper())
    qi2 = square(abs(q.imag)) if certainly_positive(abs(q.imag).lower()) else q.imag * q.imag
    lower = ((u.lower() * square(one_minus).lower()).lower() + 2 * sign * q.real * one_minus_sq
             - 16 * rho * qi2 / (2 * u + (4 * square(u) + 16 * qi2).sqrt()))
    return lower


def _merged_unique(G: _G, lo: arb, hi: arb, splits: list[arb]) -> tuple[bool, arb | None]:
    """A piece merged at ``splits``: each part unique, and one root on the hull of their enclosures.
    The splits must lie strictly inside the piece, in increasing order (the parts tile it)."""
    edges = [lo] + splits + [hi]
    if not all(certainly_lt(a, b) for a, b in zip(edges, edges[1:])):
        return False, None
    encl = []
    for a, b in zip(edges, edges[1:]):
        st, e = _newton(G, interval(a, b))
        if st != "unique":
            return False, None
        encl.append(e)
    hull = encl[0]
    for e in encl[1:]:
        hull = hull.union(e)
    pad = hull.rad() + hull.abs_upper() * arb(2) ** -40
    st, e = _newton(G, interval(hull.lower() - pad, hull.upper() + pad))
    return st == "unique", e


def _dbeta(beta, X: arb) -> arb:
    return taylor_enclosure(beta.coeffs, X, TAYLOR_ORDER, (1,))[0]


def _beta(beta, X: arb) -> arb:
    return taylor_enclosure(beta.coeffs, X, TAYLOR_ORDER, (0,))[0]


def _classify(sp: Spectrum, theta: arb, w: dict) -> tuple[bool, str]:
    """Re-verify one root's stored classification."""
    x0 = x0_at(sp, theta)
    beta = orbit_expsums(sp, x0)[0]
    bd0 = x0[1]
    if w["kind"] == "spurious":
        if "witness_t" in w:
            t = _pt(w["witness_t"])
            ok = certainly_positive(t) and certainly_lt(t, theta) and certainly_negative(beta(t))
            return ok, f"spurious: beta(t) < 0 at the stored t: {ok}"
        ok = certainly_negative(bd0)
        return ok, f"spurious: beta'(0) < 0: {ok}"
    if w["kind"] != "genuine":
        return False, f"root classified {w['kind']!r}"
    d1, rs = _pt(w["d1"]), _pt(w["right_start"])
    ok = (certainly_positive(bd0) and certainly_positive(d1) and certainly_lt(rs, theta)
          and certainly_positive(_dbeta(beta, interval(arb(0), d1)))
          and certainly_negative(_dbeta(beta, interval(rs, theta.upper()))))
    middle = [(number(a), number(b)) for a, b in w.get("middle", [])]
    d1q, rsq = number(w["d1"]), number(w["right_start"])
    if middle:
        tiles = middle[0][0] <= d1q and middle[-1][1] >= rsq and all(
            middle[i][1] >= middle[i + 1][0] for i in range(len(middle) - 1))
        pos = all(certainly_positive(_beta(beta, interval(arb(fmpq_of(a)), arb(fmpq_of(b))))) for a, b in middle)
        ok = ok and tiles and pos
    else:
        ok = ok and d1q >= rsq
    return ok, f"genuine: beta'(0) > 0, end intervals and {len(middle)} middle pieces re-verified: {ok}"


def _multipliers(sp: Spectrum, theta: arb) -> list[acb] | None:
    """Eigenvalues of the half-period Jacobian, sorted by decreasing modulus (floats only order)."""
    J = half_period_jacobian(sp, theta, x0_at(sp, theta))
    try:
        eig = list(acb_mat(J).eig(algorithm="vdhoeven_mourrain"))
    except ValueError:
        try:
            eig = list(acb_mat(J).eig(algorithm="rump"))
        except ValueError:
            return None
    P = sp.P
    liou = acb(-((-(1 / ball(P.tau) + 1 / ball(P.sigma))) * theta).exp())
    k = min(range(4), key=lambda i: float(abs(eig[i]).upper()))
    rest = acb(1)
    for i in range(4):
        if i != k:
            rest *= eig[i]
    if rest.is_finite() and certainly_positive(abs(rest)):
        z = liou / rest
        if z.is_finite() and z.overlaps(eig[k]) and (not certainly_positive(abs(eig[k]))
                                                     or certainly_lt(z.rad(), eig[k].rad())):
            eig[k] = z
    for i, z in enumerate(eig):       # J real: a ball meeting no other's conjugate is real
        if z.imag.contains(0) and not any(z.conjugate().overlaps(w) for j, w in enumerate(eig) if j != i):
            eig[i] = acb(z.real, 0)
    out = sorted(eig, key=lambda z: -float(abs(z).mid()))
    for k in range(3):                # a conjugate pair: the member with Im > 0 first (as stored)
        a, b = out[k], out[k + 1]
        if abs(a).overlaps(abs(b)) and certainly_negative(a.imag) and certainly_positive(b.imag):
            out[k], out[k + 1] = b, a
    return out


def _tracked(model, w: dict, roots: list[arb]) -> tuple | None:
    """(Nearest, kind) of the root the checker certifies nearest the option ``orbit`` among its own
    re-verified root enclosures ([T, oo) a rival when the search stopped at T), or None (no root)."""
    beyond = None if w["covers_all"] else _pt(w["T"])
    nr = nearest_root(ball(model.orbit.fmpq()), roots, (), beyond)
    if nr.index is None:
        return None
    return nr, w["roots"][nr.index]["kind"]


def _tracked_verdict(cid: str, st: str, tracked, main, moduli_main, others_ok: bool,
                     no_root: bool) -> tuple[bool, str]:
    """Re-decide a claim that follows the tracked orbit (option ``orbit``): proved needs the root the
    checker certifies nearest to be genuine with the stored theta*; refuted needs it certified nearest
    and spurious, or (stable) a modulus of its own multipliers > 1, or g without a root on (0, oo)."""
    certified = tracked is not None and tracked[0].certified
    spurious = certified and tracked[1] == "spurious"
    if st == "proved":
        if cid in ("orbit_genuine", "initial_point"):
            ok = certified and main is not None
        elif cid == "multipliers":
            ok = certified and main is not None and moduli_main is not None and others_ok
        else:
            ok = certified and main is not None and moduli_main is not None and all(certainly_lt(m, 1) for m in moduli_main)
        return ok, "the root certified nearest the option orbit, re-verified " + ("genuine" + (
            " and stable" if cid == "stable" else "") if ok else "NOT as stored")
    unstable = cid == "stable" and certified and main is not None and moduli_main is not None \
        and any(certainly_gt(m, 1) for m in moduli_main)
    ok = spurious or no_root or unstable
    return ok, ("the root certified nearest the option orbit, re-verified " + ("spurious" if spurious else "unstable")
                if spurious or unstable else "g has no root on (0, oo), re-verified" if no_root
                else "the refutation of the tracked orbit is NOT re-verified")


def check(model, data: dict) -> list[CheckResult]:
    """Re-decide every claim of a periodic-orbit certificate; see the module docstring. A [plant] scene's
    certificate: :func:`.plant_check.check` (another road to the same numbers)."""
    if isinstance(model, PlantModel):
        return plant_check(model, data)
    res: list[CheckResult] = []
    say = lambda item, ok, msg: res.append(CheckResult(item, ok, msg))  # noqa: E731
    q = data["quantities"]
    verified: set[str] = set()

    def contains(name: str, x: arb) -> None:
        if name not in q:
            return
        if encloses(stored_interval(q[name]), x):
            verified.add(name)
        else:
            say(name, False, f"stored [{q[name]['lo']}, {q[name]['hi']}] does not contain the recomputed value")

    claims = {c["id"]: c for c in data["claims"]}
    try:
        sp = Spectrum(model.params)
    except DegenerateSpectrum as e:
        for cid, c in claims.items():
            say(cid, c["status"] == "inconclusive", f"degenerate spectrum ({e})")
        return res
    G = _G(sp)
    w = (data.get("witnesses") or {}).get("half_period")
    roots: list[arb] = []
    classes: list[tuple[bool, str]] = []
    half_ok, why = False, "no isolation witness stored"
    if w is not None:
        if w.get("function", "g") not in ("g", "pole_free"):
            return [CheckResult("half_period", False, f"unknown isolated function {w.get('function')!r}")]
        G = _G(sp, w.get("function", "g"))
        mom = moment_zero_orders(model.params)
        t_min, T = _pt(w["theta_min"]), _pt(w["T"])
        steps = [("g = O(theta^5)", all(m == 0 for m in mom[:4]) and mom[4] != 0),
                 ("g^(5) > 0 on [0, theta_min]", certainly_positive(taylor5_leading_coefficient(sp, interval(arb(0), t_min))))]
        pcs = w["pieces"]
        tiles = bool(pcs) and number(pcs[0]["lo"]) <= number(w["theta_min"]) and number(pcs[-1]["hi"]) >= number(w["T"])
        tiles = tiles and all(number(pcs[i]["hi"]) == number(pcs[i + 1]["lo"]) for i in range(len(pcs) - 1))
        steps.append(("the pieces tile [theta_min, T]", tiles))
        if w["covers_all"]:
            steps.append(("tail bound > 0 beyond T", certainly_positive(tail_bound(sp, T).lower())))
        elif model.T_max is not None:
            steps.append(("T >= T_max", number(w["T"]) >= model.T_max.rational))
        else:
            steps.append(("covers (0, oo)", False))
        pieces_ok = True
        for pc in pcs:
            lo, hi = _pt(pc["lo"]), _pt(pc["hi"])
            if pc["kind"] == "empty" and pc.get("by") == "monotone":
                pieces_ok = pieces_ok and _monotone_root_free(G, lo, hi)
            elif pc["kind"] == "empty" and pc.get("by") == "envelope":
                pieces_ok = pieces_ok and _envelope_root_free(sp, lo, hi)
            elif pc["kind"] == "empty":
                st, e = _newton(G, interval(lo, hi))
                pieces_ok = pieces_ok and st == "empty"
            elif pc["kind"] == "phase_empty":
                pieces_ok = pieces_ok and phase_count(G.coeffs, lo, hi, 0)[0]
            elif pc["kind"] == "phase_unique":
                ok, e = _phase_unique(G, lo, hi)
                pieces_ok = ok and pieces_ok
                if ok:
                    roots.append(e)
            elif pc["kind"] == "unique":
                if pc.get("splits"):
                    ok, e = _merged_unique(G, lo, hi, [_pt(s) for s in pc["splits"]])
                else:
                    st, e = _newton(G, interval(lo, hi))
                    ok = st == "unique"
                pieces_ok = pieces_ok and ok
                if ok:
                    roots.append(e)
            else:
                pieces_ok = False
            if not pieces_ok:
                steps.append((f"piece [{float(number(pc['lo'])):.6g}, {float(number(pc['hi'])):.6g}] ({pc['kind']})", False))
                break
        steps.append(("every piece re-decided", pieces_ok))
        steps.append(("one classification per root", len(w.get("roots", [])) == len(roots)))
        if pieces_ok and len(w.get("roots", [])) == len(roots):
            classes = [_classify(sp, th, rw) for th, rw in zip(roots, w["roots"])]
            steps.append(("every classification re-verified", all(ok for ok, _ in classes)))
        half_ok = all(ok for _, ok in steps)
        why = "; ".join(f"{name}: {'ok' if ok else 'FAILED'}" for name, ok in steps)
    genuine = [th for th, rw in zip(roots, (w or {}).get("roots", [])) if rw["kind"] == "genuine"] if half_ok else []
    main = None
    tracked = _tracked(model, w, roots) if half_ok and getattr(model, "orbit", None) is not None else None
    if getattr(model, "orbit", None) is not None:
        # option orbit: the scene's orbit is the root the checker itself certifies nearest, when genuine
        if tracked is not None and tracked[1] == "genuine" and "theta_star" in q \
                and encloses(stored_interval(q["theta_star"]), roots[tracked[0].index]):
            main = roots[tracked[0].index]
    elif "theta_star" in q and genuine:
        s = stored_interval(q["theta_star"])
        main = next((th for th in genuine if encloses(s, th)), None)
    if main is not None:
        verified.add("theta_star")
        contains("period", 2 * main)
    moduli_main, mults_main = None, None
    if main is not None:
        x0 = x0_at(sp, main)
        for name, k in (("beta_dot_0", 1), ("Omega_0", 2), ("i_0", 3), ("I_0", 4)):
            contains(name, x0[k])
        oq, _ = orbit_quantities(model, sp, RootVerdict(main, x0, "genuine", ""))
        for name, x in oq.items():
            contains(name, x)
        mults_main = _multipliers(sp, main)
        if mults_main is not None:
            moduli_main = [abs(z) for z in mults_main]
            for j, (z, m) in enumerate(zip(mults_main, moduli_main), start=1):
                contains(f"multiplier_modulus_{j}", m)
                contains(f"multiplier_{j}_re", z.real)
                contains(f"multiplier_{j}_im", z.imag)
            mx = moduli_main[0]
            for m in moduli_main[1:]:
                mx = mx.max(m)
            contains("stability_margin", 1 - mx)
    others, other_moduli = other_orbit_moduli(genuine, main, lambda th: _multipliers(sp, th), contains)
    exhaustive = half_ok and w["covers_all"]
    all_moduli = ([moduli_main] if moduli_main else []) + list(other_moduli.values())
    for cid, c in claims.items():
        st = c["status"]
        if st == "inconclusive":
            say(cid, True, "inconclusive: claims nothing")
        elif cid in TRACKED and getattr(model, "orbit", None) is not None:
            say(cid, *_tracked_verdict(cid, st, tracked, main, moduli_main, len(other_moduli) == len(others),
                                       exhaustive and not roots))
        else:
            say(cid, *redecide(cid, st, half_ok=half_ok, why=why, main=main, genuine=genuine, exhaustive=exhaustive,
                               moduli_ok=(moduli_main is not None and len(other_moduli) == len(others)),
                               all_moduli=all_moduli))
    for cid, names in REQUIRED.items():
        if claims.get(cid, {}).get("status") == "proved":
            missing = [n for n in names if n not in q]
            if missing:
                say(cid, False, f"a proved {cid} without the quantities its statement names: {missing}")
    unverified = sorted(set(q) - verified)
    say("quantities", not unverified, f"{len(verified)} stored enclosures verified"
        + (f"; not verified: {unverified}" if unverified else ""))
    if classes:
        say("roots", all(ok for ok, _ in classes), f"{len(classes)} roots classified: "
            + "; ".join(m for _, m in classes[:3]) + (" ..." if len(classes) > 3 else ""))
    return res
