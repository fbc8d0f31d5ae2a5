"""Named soundness mutants: each weakens one step a proof rests on; the default tests must kill all.

    python tools/soundness_mutants.py [--only NAME ...] [--tests FILE ...] [--in-order] [--list] [--out FILE]
                                      [--record [--group GROUP]]

Each mutant is one textual substitution in one file. It is applied to a fresh copy of the files git
tracks, as they are in the working tree (in a temporary folder), and the README's test command runs
there (``python -m pytest -x``, the ``ci`` hypothesis profile, with the copy first on ``sys.path``). A
mutant is *killed* when the tests fail. The test that killed it last time (its ``killed_by`` in
tools/mutant_kills.json) runs first (tools/pytest_first.py: the same tests, only in another order),
so that ``-x`` stops within seconds when it kills it again; ``--in-order`` keeps pytest's order. The
unmutated copy must pass the same tests first (otherwise the run stops, exit 4: a test failing there
would "kill" every mutant); a pytest exit of 4 or 5 (a broken run) is "NOT RUN", never a kill.
``test_rules``' checks of this list's texts and record are left out of both runs (see ``RULE``). Prints a table
(and writes it with ``--out``); exits 1 if any mutant survives or was not run.

``--record`` writes this run's outcomes into tools/mutant_kills.json (the record proofs/mutation.md
summarises by group): for each mutant killed, the first failing test, the date and whether the run was the
whole default command or ``--tests`` files; a survivor's ``killed_by`` becomes null; a mutant not applied
or not run keeps its entry. A mutant new to the file takes ``--group``, else the group of the mutants of
the same file already there (``tests/test_rules.py`` checks that every mutant has an entry and that
proofs/mutation.md counts each group).
"""
from __future__ import annotations

import argparse
import datetime
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
#: mutant name -> {"group", "killed_by" (a test node id, or a test file where only the file is known; null
#: after a survival), "run" ("whole": the default command, or "targeted": --tests files), "date"}
KILLS = ROOT / "tools" / "mutant_kills.json"
#: tests/test_rules.py checks that each mutant's target text occurs once in the tree: in a mutated copy
#: the applied mutant's text is gone, so that check would "kill" every mutant whose own test runs after
#: it (test_sublevel, test_subdivision): it is left out of these runs (it is about this list, not soundness);
#: so is its check of the kill record, which a mutant new to the list fails until a run has recorded it
RULE = ["--deselect", "tests/test_rules.py::test_every_named_soundness_mutant_still_applies",
        "--deselect", "tests/test_rules.py::test_every_named_mutant_is_recorded_killed_and_its_group_counted_in_mutation_md"]
#: the README's test command, as both the unmutated and the mutated copies run it
PYTEST = [sys.executable, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider", *RULE]

#: (name, file, original text, mutated text, what it breaks)
MUTANTS = [
    ("paving_search_refutation_ignored", "rigor_gyro/margins/paving.py",
     "    return any(p.get(\"status\") == \"refuted\" for p in found.get(\"proofs\", []) if isinstance(p, dict))\n",
     "    return False\n",
     "a paving's counterexample search that found a refuted point proof leaves the claim inconclusive"),
    ("paving_check_search_refutation_ignored", "rigor_gyro/margins/check.py",
     "                  or found\n",
     "                  or False\n",
     "the paving checker re-derives a claim's status without the counterexamples its search certified"),
    ("yield_normal_lower_one_with_undecided", "rigor_gyro/margins/safe_set.py",
     "    if mass[\"refuted\"] == mass[\"undecided\"] == 0 and not any(st != \"proved\" for _, st in pieces):\n",
     "    if mass[\"refuted\"] == mass[\"undecided\"] == 0:\n",
     "a truncated-normal yield's lower bound set to 1 while some pieces are undecided or failing"),
    # issue 40 part 1: the natural sublevel set (kinds/lyapunov/natural_domain.py, check.py; tests/test_natural_sublevel.py)
    ('natural_active_form_without_vertex_check', 'rigor_gyro/kinds/lyapunov/natural_domain.py',
     '            if certainly_positive(B * (-be / (2 * ga) - r0)):\n',
     '            if True:\n',
     "the natural c_max lower bound takes V at the half-line's end r0 = -A/B also where the vertex of V(r) lies inside the half-line (a value above the minimum)"),
    ('natural_phi_bound_from_its_upper_end', 'rigor_gyro/kinds/lyapunov/natural_domain.py',
     '        low = better(low, g.phi(X))\n',
     '        low = better(low, g.phi(X).upper())\n',
     "the natural c_max lower bound uses phi's upper end over the box's x2 (not a lower bound of V)"),
    ('natural_mean_value_without_s_term', 'rigor_gyro/kinds/lyapunov/natural_domain.py',
     'W(Dual(U, arb(1)), S).d * (U - um) + W(U, Dual(S, arb(1))).d * (S - sm)',
     'W(Dual(U, arb(1)), S).d * (U - um)',
     'the centred form of W drops the t-direction term (an enclosure too narrow over the box)'),
    ('natural_checker_skips_box_bounds', 'rigor_gyro/kinds/lyapunov/check.py',
     '        if not (float(low) == float("inf") or (low.is_finite() and low >= lo_q)):\n',
     '        if False:\n',
     'the natural c_max checker accepts a lower bound its boxes do not show'),
    ('natural_checker_skips_band_positivity', 'rigor_gyro/kinds/lyapunov/check.py',
     '    if not (_covers(w.get("band") or [], xc, X) and _all_positive(band_function(g, level), w["band"])):\n',
     '    if not _covers(w.get("band") or [], xc, X):\n',
     'the natural c_max checker accepts band pieces without phi > c_max_upper on them (the faces may bind)'),
    ('natural_checker_skips_positivity', 'rigor_gyro/kinds/lyapunov/check.py',
     '        if not (_covers(pieces, arb(0), X) and _all_positive(fn, pieces)):\n',
     '        if not _covers(pieces, arb(0), X):\n',
     'the natural range X confirmed without re-evaluating S, f/x, psi > 0 on the stored pieces'),
    ('natural_checker_point_without_vdot', 'rigor_gyro/kinds/lyapunov/check.py',
     '    if not (certainly_le(abs(x2), xc) and certainly_positive(x1 * x1 + x3 * x3) and certainly_positive(g.vdot(x1, x2, x3))):\n',
     '    if not (certainly_le(abs(x2), xc) and certainly_positive(x1 * x1 + x3 * x3)):\n',
     'the natural c_max upper bound confirmed from a point where Vdot > 0 is not re-evaluated'),
    ('natural_checker_no_tiling', 'rigor_gyro/kinds/lyapunov/check.py',
     '    if not tiles_by_bisection(Box.of(DIRECT_DOMAIN), boxes):\n        return False, "the stored (x2, t) boxes over |x2| <= X_c do not tile the domain"',
     '    if False:\n        return False, "the stored (x2, t) boxes over |x2| <= X_c do not tile the domain"',
     'the natural c_max checker accepts (x2, t) boxes that do not tile the domain'),
    ('natural_checker_skips_reach_positivity', 'rigor_gyro/kinds/lyapunov/check.py',
     '                and _all_positive(lambda x: cl - g.phi(x), w["reach_pieces"])):\n',
     '                ):\n',
     "the natural set's x2 extent confirmed without phi < c_max_lower re-evaluated on the stored pieces"),
    ("threshold_step_around_wrong_end", "rigor_gyro/margins/threshold.py",
     "        if st == \"proved\":\n            return x, r\n",
     "        if st == \"proved\":\n            return p, x\n",
     "a threshold search that steps around an inconclusive midpoint moves its refuted end to a proved point"),
    ("safe_set_any_proved_is_safe", "rigor_gyro/margins/safe_set.py",
     "    if statuses and all(s == \"proved\" for s in statuses.values()):\n",
     "    if statuses and any(s == \"proved\" for s in statuses.values()):\n",
     "a piece of a paving counted safe when only some of the selected claims are proved on it"),
    ("yield_lower_counts_undecided", "rigor_gyro/margins/safe_set.py",
     "        lo, hi = mass[\"proved\"], 1 - mass[\"refuted\"]\n",
     "        lo, hi = mass[\"proved\"] + mass[\"undecided\"], 1 - mass[\"refuted\"]\n",
     "the certified yield's lower bound counts the undecided pieces as safe"),
    ("normal_law_untruncated", "rigor_gyro/margins/safe_set.py",
     "        part = (_phi(z(hi)) - _phi(z(lo))) / (_phi(z(whi)) - _phi(z(wlo)))\n",
     "        part = _phi(z(hi)) - _phi(z(lo))\n",
     "a truncated normal tolerance law's probabilities not renormalised to the interval"),
    ("sampled_contradiction_ignored", "rigor_gyro/margins/sampled.py",
     "            if got == _CONTRADICTS[status]:\n", "            if False:\n",
     "the paving checker's point-prover cross-check never reports a point that contradicts its sub-box"),
    ("sampled_midpoint_only", "rigor_gyro/margins/sampled.py",
     "    out = [(\"midpoint\", box.midpoint()), (\"lower corner\", lower), (\"upper corner\", upper)]\n",
     "    out = [(\"midpoint\", box.midpoint())]\n",
     "the paving checker's point-prover cross-check asks only the sub-boxes' midpoints"),
    ("sampled_first_boxes_only", "rigor_gyro/margins/sampled.py",
     "    return [boxes[(i * (n - 1)) // (count - 1)] for i in range(count)]\n",
     "    return list(boxes[:count])\n",
     "the paving checker's point-prover cross-check asks only the first decided sub-boxes, not a spread"),
    ("continuation_newton_ignores_box", "rigor_gyro/kinds/periodic_orbit/continuation.py",
     "        G0 = second_order_value(Gc, Gn, zero_devs)\n", "        G0 = Gc.v.real\n",
     "theta*'s box Newton operator ignores how g(theta_c, P) moves over the box (relay box continuation)"),
    ("subbox_cells_drop_top_end", "rigor_gyro/kinds/periodic_orbit/subbox_union.py",
     "for i in range(1, n)] + [hi]\n", "for i in range(1, n)] + [arb(((lo + hi) / 2).mid())]\n",
     "the sub-box cells of a relay box's derivative union stop short of the box's upper end"),
    ("subbox_union_last_cell_only", "rigor_gyro/kinds/periodic_orbit/subbox_union.py",
     "            out = cellg if out is None else [a.union(b) for a, b in zip(out, cellg)]\n",
     "            out = cellg\n", "the derivative union over a relay box keeps only its last cell"),
    ("cellwise_max_modulus_first_cell", "rigor_gyro/kinds/periodic_orbit/cellwise.py",
     "            mx = mx.union(o.max_modulus)\n", "            pass\n",
     "a relay box's max multiplier modulus decided cell by cell keeps only the first cell's"),
    ("band_root_first_image_trusted", "rigor_gyro/kinds/periodic_orbit/continuation.py",
     "        if certainly_lt(-rho, image.lower()) and certainly_lt(image.upper(), rho):\n",
     "        if True:\n", "the relay band Newton step accepts its image without checking it lies inside the band"),
    ("band_root_slope_dropped", "rigor_gyro/kinds/periodic_orbit/continuation.py",
     "                out = out + s * dev\n", "                pass\n",
     "theta*(P)'s band enclosure forgets the tangent's motion over the box"),
    ("band_root_residual_last_cell", "rigor_gyro/kinds/periodic_orbit/subbox_union.py",
     "        F0 = val if F0 is None else F0.union(val)\n", "        F0 = val\n",
     "the band Newton step's residual F(0, P) keeps only the last parameter cell's"),
    ("cellwise_unvisited_cells_genuine", "rigor_gyro/kinds/periodic_orbit/cellwise.py",
     "    if not all(known for _, _, known in stack) or not reason:\n", "    if not reason:\n",
     "orbit_genuine over a relay box proved although cells left over hold no cell proved genuine"),
    ("jets_hessian_dropped", "rigor_gyro/core/jets.py", "            out = out + _hessian(box, k, j) * dd / 2\n",
     "            pass\n", "the second-order form of a jet forgets its Lagrange remainder"),
    ("certainly_lt_to_possibly", "rigor_gyro/core/balls.py", "    if x < y:\n        return -1",
     "    if not (x > y):\n        return -1", "a certainty predicate weakened to 'possibly' (compare / certainly_lt)"),
    ("certainly_le_to_possibly", "rigor_gyro/core/balls.py", "return bool(x.is_finite() and y.is_finite() and x <= y)",
     "return bool(x.is_finite() and y.is_finite() and not (x > y))", "certainly_le weakened to 'possibly'"),
    ("nan_decides", "rigor_gyro/core/balls.py", "    if not (x.is_finite() and y.is_finite()):\n        return None\n",
     "", "NaN/infinite balls allowed to decide a comparison"),
    ("rounding_to_nearest", "rigor_gyro/core/balls.py",
     'lo = _round_decimal(a, d, "down") if a is not None else "-inf"',
     'lo = _round_decimal(a, d, "nearest") if a is not None else "-inf"', "outward rounding of decimals turned to nearest"),
    ("taylor_remainder_halved", "rigor_gyro/kinds/periodic_orbit/flow.py",
     "        tot += comb(order, k) * cN * _ipow(w, order - k)\n",
     "        tot += comb(order, k) * cN * _ipow(w, order - k) / 2\n", "a Taylor (Lagrange) remainder shrunk"),
    ("subdivision_piece_skipped", "rigor_gyro/core/subdivision.py", "        stack.append((mid, b))\n        stack.append((a, mid))",
     "        stack.append((a, mid))", "certify_positive skips the right half of every bisected piece"),
    ("max_cover_dropped", "rigor_gyro/core/subdivision.py", "        upper = upper.max(item[4])          # certified max of upper bounds",
     "        pass", "enclose_max forgets the upper bounds of the pieces left (a maximum enclosed too low)"),
    ("spurious_witness_possibly", "rigor_gyro/kinds/periodic_orbit/claims.py",
     "            if certainly_negative(beta(t)):", "            if not certainly_positive(beta(t)):",
     "a spurious-root witness accepted on 'possibly <= 0'"),
    ("stable_possibly_below_1", "rigor_gyro/kinds/periodic_orbit/multipliers.py",
     "    if all(certainly_lt(m, 1) for m in v.moduli):", "    if all(not certainly_gt(m, 1) for m in v.moduli):",
     "stability accepted on 'possibly < 1'"),
    ("psi_disc_term_dropped", "rigor_gyro/kinds/lyapunov/model.py", "        return c10 - R * hypot_ball(c11, c13)",
     "        return c10 - R * abs(c11)", "one term dropped from the Psi1 disc minimum"),
    ("sign_change_check_removed", "rigor_gyro/core/polyroots.py", "        elif not (p(lo) * p(hi) < 0):",
     "        elif False:", "the exact sign-change check of a real polynomial root removed"),
    ("newton_inside_to_overlap", "rigor_gyro/core/roots.py", "        inside = bool(x.contains_interior(n))",
     "        inside = bool(x.overlaps(n))", "interval Newton's uniqueness condition weakened"),
    ("tail_bound_loosened", "rigor_gyro/kinds/periodic_orbit/flow.py", "        B += amp * q / (1 - q)",
     "        B += amp * q", "a term of the relay tail bound shrunk"),
    ("branch_inside_possibly", "rigor_gyro/kinds/eigenfrequencies/claims.py",
     "        inside = certainly_lt(lo, w) and (hi is None or certainly_lt(w, hi))",
     "        inside = not certainly_ge(lo, w) and (hi is None or not certainly_ge(w, hi))",
     "a root accepted on its branch on 'possibly inside'"),
    ("verdict_ignores_inconclusive", "rigor_gyro/certificate.py",
     "        if Status.INCONCLUSIVE in statuses or not self.claims:", "        if not self.claims:",
     "the verdict 'proved' despite an inconclusive claim"),
    ("series_padded_with_zeros", "rigor_gyro/core/balls.py", "    if s.prec < n:\n        raise SeriesTruncated(",
     "    if False:\n        raise SeriesTruncated(", "a series cut by ctx.cap padded with zeros"),
    ("checker_ignores_integrity", "rigor_gyro/check.py", 'ok = isinstance(integrity, dict) and integrity.get("sha256") == digest(data)',
     "ok = True", "the checker accepts an altered certificate"),
    ("checker_trusts_stored_status", "rigor_gyro/kinds/eigenfrequencies/check.py",
     '                say(cid, all(certainly_lt(chain[i], chain[i + 1]) for i in range(6)), "0 < nu1 < ... < nu6 re-decided")',
     '                say(cid, True, "0 < nu1 < ... < nu6 re-decided")', "the checker trusts a stored 'proved'"),
    ("family_newton_inside_to_overlap", "rigor_gyro/core/family_roots.py",
     "        if certainly_lt(y.lower(), n.lower()) and certainly_lt(n.upper(), y.upper()):\n            return _contract(F, n)",
     "        if n.overlaps(y):\n            return _contract(F, n)",
     "the family interval Newton's existence/uniqueness condition weakened (parameter boxes)"),
    ("box_undecided_as_proved", "rigor_gyro/kinds/eigenfrequencies/boxes.py",
     "    und = [label for label, lo, x, hi in items if not (certainly_le(lo, x) and certainly_le(x, hi))]",
     "    und = []", "an undecided bound over a box reported proved"),
    ("paving_any_box_proves", "rigor_gyro/margins/paving.py",
     '        if self.boxes and all(s == "proved" for _, s in self.boxes):',
     '        if self.boxes and any(s == "proved" for _, s in self.boxes):',
     "a whole-box claim proved when only some sub-boxes are"),
    ("near_zero_tail_dropped", "rigor_gyro/kinds/periodic_orbit/flow.py",
     "        return [self._derivs[k](center) + arb(0, (self.tail / s ** k).upper()) for k in range(n)]",
     "        return [self._derivs[k](center) for k in range(n)]",
     "the truncation tail of g's power series near 0 dropped (relay boxes)"),
    ("box_ball_is_its_lower_end", "rigor_gyro/core/boxes.py",
     "    return a if lo == hi else a.union(arb(fmpq(hi.numerator, hi.denominator)))",
     "    return a", "a parameter box evaluated at its lower end only"),
    ("paving_checker_skips_tiling", "rigor_gyro/margins/check.py",
     "        tiles = _tiles(bs.box, [b for b, _ in boxes], bs.frozen)", "        tiles = True",
     "the paving checker accepts sub-boxes that do not tile the box"),
    # the largest sublevel set and the extents (issue 13)
    ("sublevel_leaf_skipped", "rigor_gyro/core/subdivision.py",
     "        if key.lo is not None and (not bound.is_finite() or certainly_lt(key.lo, bound)):",
     "        if key.lo is not None and bound.is_finite() and certainly_lt(bound, key.lo):",
     "lower_bound_on_box keeps the largest leaf bound instead of the smallest (a lower bound raised)"),
    ("sublevel_wrong_half_line", "rigor_gyro/kinds/lyapunov/model.py",
     "                b = (-beta).lower()         # r = -s, s >= rho",
     "                b = beta.lower()            # r = -s, s >= rho",
     "the half-line where Vdot >= 0 taken on the wrong side of r = 0 (V bounded on the wrong branch)"),
    ("sublevel_checker_skips_tiling", "rigor_gyro/kinds/lyapunov/check.py",
     "    if not tiles_by_bisection(Box.of(DIRECT_DOMAIN), boxes):\n        return False, \"the stored (x2, t) boxes do not tile the domain\"",
     "    if False:\n        return False, \"the stored (x2, t) boxes do not tile the domain\"",
     "the c_max checker accepts (x2, t) boxes that do not tile the domain"),
    ("extent_empty_slice_as_point", "rigor_gyro/kinds/lyapunov/model.py",
     "def slice_in_region(g: Gimbal, c: arb, R: arb, x2) -> bool:",
     "def slice_in_region(g: Gimbal, c: arb, R: arb, x2) -> bool:\n    return True",
     "an extent's lower end taken from a slice not known to belong to the set"),
    ("refutation_without_counterexample", "rigor_gyro/kinds/periodic_orbit/claims.py",
     "    exhaustive = complete and an.covers_all", "    exhaustive = complete",
     "a search restricted by T_max allowed to refute"),
    # the speed work of issue 12
    ("envelope_qi_term_dropped", "rigor_gyro/kinds/periodic_orbit/flow.py",
     "         - 16 * rho * qi2 / ((4 * _positive_product(a_s, a_s) + 16 * qi2).sqrt() + 2 * a_s))",
     "         - 0 * rho * qi2 / ((4 * _positive_product(a_s, a_s) + 16 * qi2).sqrt() + 2 * a_s))",
     "the relay envelope bound forgets the oscillation's sine amplitude (a root-free piece that is not)"),
    ("envelope_sign_ignored", "rigor_gyro/kinds/periodic_orbit/flow.py",
     "    elif certainly_positive(-slow):\n        sigma = -1", "    elif certainly_positive(-slow):\n        sigma = 1",
     "the envelope bound taken with the wrong sign of the slow part"),
    ("envelope_checker_accepts", "rigor_gyro/kinds/periodic_orbit/check.py",
     "    low = _envelope_lower(sp, lo, hi)\n    return low is not None and certainly_positive(low)",
     "    return True",
     "the checker accepts any piece said to be root-free by the envelope"),
    ("memo_key_without_precision", "rigor_gyro/kinds/lyapunov/model.py",
     "            key = (name, current_precision(), x2.mid().man_exp(), x2.rad().man_exp())",
     "            key = (name, x2.mid().man_exp(), x2.rad().man_exp())",
     "a memoised ball handed back at another precision"),
    ("dual_quotient_rule_sign", "rigor_gyro/kinds/lyapunov/model.py",
     "(self.d * o.v - self.v * o.d) / (o.v * o.v)", "(self.d * o.v + self.v * o.d) / (o.v * o.v)",
     "a wrong derivative in the mean-value forms (the quotient rule)"),
    # the gains p, K as amplitude parameters (issue 11, section 2)
    ("gain_n_as_amplitude", "rigor_gyro/kinds/periodic_orbit/flow.py",
     'AMPLITUDE_PARAMETERS = ("S", "p", "K")', 'AMPLITUDE_PARAMETERS = ("S", "p", "K", "n")',
     "the back-emf gain n treated as an amplitude: a box in n decided at its lower end only"),
    ("amplitude_box_at_lower_end_of_every_gain", "rigor_gyro/kinds/periodic_orbit/boxes.py",
     "    fixed = {k: _q(box.interval(k)[0]) for k in AMPLITUDE_PARAMETERS if k in box.names}",
     "    fixed = {k: _q(box.interval(k)[0]) for k in box.names}",
     "every parameter of a relay box taken at its lower end (not only S, p, K)"),
    ("relay_memo_key_without_radius", "rigor_gyro/kinds/periodic_orbit/claims.py",
     "        key = (current_precision(), ctr.mid().man_exp(), ctr.rad().man_exp(), n)",
     "        key = (current_precision(), ctr.mid().man_exp(), n)",
     "G's memoised Taylor coefficients at a point handed back for a ball around it"),
    ("midpoint_refutation_unchecked", "rigor_gyro/core/subdivision.py",
     "            if certainly_le(vm, 0):\n                return BoxPositivity(Status.REFUTED",
     "            if not certainly_positive(vm):\n                return BoxPositivity(Status.REFUTED",
     "a box refuted where f is only possibly <= 0 at its midpoint"),
    # the direct test over the mu interval (issue 13): best_mu_direct and its checker
    ("direct_bound_wrong_end", "rigor_gyro/kinds/lyapunov/model.py",
     "        end = mu.upper() if certainly_le(arb(0), slope) else mu.lower() if certainly_le(slope, 0) else None",
     "        end = mu.lower() if certainly_le(arb(0), slope) else mu.upper() if certainly_le(slope, 0) else None",
     "a mu piece's radius bound taken at the end its derivative points away from (a bound below the radius)"),
    ("direct_slope_sign_ignored", "rigor_gyro/kinds/lyapunov/model.py",
     "        slope = (Ad / Bd).d if certainly_positive(B) else -(Ad / Bd).d",
     "        slope = (Ad / Bd).d", "the derivative of A/|B| taken as that of A/B where B < 0"),
    ("direct_point_outside_range", "rigor_gyro/kinds/lyapunov/model.py",
     "    if not certainly_le(abs(arb(u)), 1):\n        return arb(\"inf\")\n    X, T",
     "    X, T", "a point with |x2| > x2* allowed to bound the radius"),
    ("direct_checker_skips_mu_cover", "rigor_gyro/kinds/lyapunov/check.py",
     "        if pts and _covers_16(wbd.get(\"mu_pieces\", []), K):",
     "        if pts:", "the checker accepts mu pieces that do not cover (16)"),
    ("direct_checker_at_scene_mu", "rigor_gyro/kinds/lyapunov/check.py",
     "        at_mu = _direct_boxes_hold(g.with_mu(mu_d), Rdm,", "        at_mu = _direct_boxes_hold(g, Rdm,",
     "the checker re-evaluates best_mu_direct's boxes at the scene's mu, not at mu_direct"),
    # the x2 -> -x2 symmetry of the (x2, t) branch and bounds (issue 12)
    ("mirror_key_without_radius", "rigor_gyro/core/boxes.py",
     "        key = tuple((k, balls[k].mid().man_exp(), balls[k].rad().man_exp()) for k in sorted(balls))",
     "        key = tuple((k, balls[k].mid().man_exp()) for k in sorted(balls))",
     "a box's ball handed back for a wider box with the same (mirrored) midpoint"),
    ("mirror_for_every_law", "rigor_gyro/kinds/lyapunov/model.py",
     "    return even_in(f, \"u\") if law_is_odd(g.law) else f", "    return even_in(f, \"u\")",
     "the x2 -> -x2 symmetry used for a law not declared odd"),
    # the relay boxes' root classification and c* against the region (issue 11, 2026-12-02)
    ("spurious_grid_point_possibly", "rigor_gyro/kinds/periodic_orbit/claims.py",
     "            bt = beta(t)\n            if certainly_negative(bt):",
     "            bt = beta(t)\n            if not certainly_positive(bt):",
     "a root called spurious at a point where beta is only possibly negative"),
    ("centred_jacobian_drops_theta", "rigor_gyro/kinds/periodic_orbit/jacobian_box.py",
     "directions = [(theta - theta_c, arb_mat(6, 6), N * E)]", "directions = []",
     "the box Jacobian's mean-value form without its theta term (theta* spread over the box ignored)"),
    ("centred_jacobian_skips_parameters", "rigor_gyro/kinds/periodic_orbit/jacobian_box.py",
     "            if dev.is_zero():\n                continue", "            if not dev.is_zero():\n                continue",
     "the box Jacobian's mean-value form without the parameters' terms (a box treated as its centre)"),
    ("eigen_coordinates_drop_terms", "rigor_gyro/kinds/periodic_orbit/jacobian_box.py",
     "K = K + (Vi * acb_mat(dJ) * V) * acb(dev)", "K = K",
     "the box multipliers from the centre's Jacobian alone (the box's spread dropped in eigenvector coordinates)"),
    ("cylinder_margin_checker_accepts", "rigor_gyro/kinds/lyapunov/check.py",
     "stored_interval(q[\"cylinder_margin_lower\"])[1] <= _lower(own)", "True",
     "the checker accepts any stored c* margin against the region's side"),
    # mutmut over the relay attempt (issue 10, 2026-12-03)
    ("unstable_refutation_unconditional", "rigor_gyro/kinds/periodic_orbit/claims.py",
     "st = (Status.REFUTED, text, unstable) if exhaustive else (Status.INCONCLUSIVE, text + beyond)",
     "st = (Status.REFUTED, text, unstable)",
     "stability refuted from the unstable orbits found in (0, T_max], a stable one beyond unsearched"),
    ("psi_counterexample_outside_region", "rigor_gyro/kinds/lyapunov/model.py",
     "        return None\n    Rq = exact_fraction(R.lower())\n    for shrink",
     "        return None\n    Rq = exact_fraction(R.upper())\n    for shrink",
     "a Psi counterexample placed in the disc of the radius ball's upper end (outside the region for smaller radii)"),
    ("vdot_witness_outside_region", "rigor_gyro/kinds/lyapunov/model.py",
     "    Rq = exact_fraction(R.lower())\n    for x2 in x2_points:",
     "    Rq = exact_fraction(R.upper())\n    for x2 in x2_points:",
     "a Vdot > 0 witness searched on circles of the radius ball's upper end (outside the region for smaller radii)"),
    ("max_lower_end_from_upper", "rigor_gyro/core/subdivision.py",
     "    best = f(best_pt).lower()          # max >= best",
     "    best = f(best_pt).upper()          # max >= best",
     "the lower end of a maximum's enclosure taken from f's upper end at a point (above the maximum when f's values are wide)"),
    ("max_first_guess_outside", "rigor_gyro/core/subdivision.py",
     "    best_pt = ((a0 + b0) / 2).mid()\n    best = f(best_pt)",
     "    best_pt = ((a0 - b0) / 2).mid()\n    best = f(best_pt)",
     "enclose_max's first guess taken outside [lo, hi] (the maximum's lower end from a point not in the interval)"),
    # mutmut over the checkers (issue 10, 2026-12-04): the steps an independent re-check rests on
    ("checker_cover_with_a_gap", "rigor_gyro/kinds/lyapunov/check.py",
     "        if a > reach:\n            return False", "        if False:\n            return False",
     "the Lyapunov checker accepts stored pieces with a gap as a cover of their range"),
    ("checker_point_range_outer_ends", "rigor_gyro/kinds/lyapunov/check.py",
     "(xl, xh), (_, lh), (hl, _) = exact_endpoints(x), exact_endpoints(lo), exact_endpoints(hi)",
     "(xl, xh), (lh, _), (_, hl) = exact_endpoints(x), exact_endpoints(lo), exact_endpoints(hi)",
     "a stored point counted in a range if it meets the balls of its ends (not certainly in the range)"),
    ("checker_max_from_one_half", "rigor_gyro/kinds/lyapunov/check.py",
     "    best = a if (not a.is_finite() or (b.is_finite() and certainly_le(b, a))) else b",
     "    best = a",
     "the checker's re-bounded maximum taken from the left half of a piece only"),
    ("eig_checker_root_without_sign_change", "rigor_gyro/kinds/eigenfrequencies/check.py",
     "    if pa == 0 or pb == 0 or _sign(pa) == _sign(pb):\n        return None",
     "    if pa == 0 or pb == 0:\n        return None",
     "the eigenfrequency checker accepts a stored root interval without an exact sign change of Q"),
    ("eig_checker_branch_inside_on_one_end", "rigor_gyro/kinds/eigenfrequencies/check.py",
     "inside = [certainly_lt(lo, w) and (hi is None", "inside = [certainly_lt(lo, w) or (hi is None",
     "the eigenfrequency checker re-proves a root inside its branch from one end of the branch"),
    ("eig_checker_branch_always_empty", "rigor_gyro/kinds/eigenfrequencies/check.py",
     "empty = {2: nus_exactly_equal(ident[2], ident[3])", "empty = {2: nus_exactly_equal(ident[3], ident[3])",
     "the eigenfrequency checker takes the branch (nu2, nu3) as exactly empty (any refutation naming omega_2 confirmed)"),
    ("eig_checker_nu_bounds_one_side", "rigor_gyro/kinds/eigenfrequencies/check.py",
     "holds = all(certainly_le(bounds[k][0], nus[k]) and certainly_le(nus[k], bounds[k][1])",
     "holds = all(certainly_le(bounds[k][0], nus[k]) or certainly_le(nus[k], bounds[k][1])",
     "the eigenfrequency checker confirms the bounds (5) from one side of each"),
    ("relay_checker_tiling_skips_last_junction", "rigor_gyro/kinds/periodic_orbit/check.py",
     'for i in range(len(pcs) - 1))', 'for i in range(len(pcs) - 2))',
     "the relay checker's tiling test skips the junction before the last piece (a gap there unseen)"),
    ("relay_checker_tail_bound_possibly_positive", "rigor_gyro/kinds/periodic_orbit/check.py",
     "certainly_positive(tail_bound(sp, T).lower())", "certainly_positive(tail_bound(sp, T).upper())",
     "the relay checker accepts the tail bound beyond T when it is only possibly positive"),
    ("relay_checker_unique_piece_unchecked", "rigor_gyro/kinds/periodic_orbit/check.py",
     "                pieces_ok = pieces_ok and ok", "                pieces_ok = pieces_ok or ok",
     "the relay checker lets a 'unique' piece whose Newton test fails pass"),
    ("relay_checker_genuine_without_half_period", "rigor_gyro/kinds/periodic_orbit/check.py",
     'if rw["kind"] == "genuine"] if half_ok else []', 'if rw["kind"] == "genuine"] if True else []',
     "the relay checker takes a root's stored 'genuine' label without the half-period witness re-verified"),
    ("relay_checker_multipliers_of_other_orbits", "rigor_gyro/kinds/periodic_orbit/check.py",
     "(moduli_main is not None and len(other_moduli) == len(others))",
     "(moduli_main is not None or len(other_moduli) == len(others))",
     "the relay checker confirms the multipliers claim without the main orbit's multipliers"),
    ("lyap_checker_h_equilibrium_x1_sign", "rigor_gyro/kinds/lyapunov/check.py",
     "points.append(Equilibrium(-g.f(root) / c.k, root,", "points.append(Equilibrium(g.f(root) / c.k, root,",
     "the Lyapunov checker re-derives an equilibrium where k H + C0 sin x2 f(x2) = 0 at x1 = +f/k (not -f/k)"),
    ("lyap_checker_cos_equilibrium_classified_elsewhere", "rigor_gyro/kinds/lyapunov/check.py",
     'sgn * pi / 2, "cos x2 = 0"', 'sgn * pi / 3, "cos x2 = 0"',
     "the Lyapunov checker classifies the equilibria x2 = +-pi/2 at +-pi/3 (their stated text still pi/2)"),
    # issue 10, 2026-12-05: mutmut survivors of the Lyapunov claims, the largest sublevel set and the relay
    # near-zero series, each a false statement on some input and none killed before this session
    ("v_positive_refuted_on_v_le_1", "rigor_gyro/kinds/lyapunov/claims.py",
     "            if certainly_le(v, 0):", "            if certainly_le(v, 1):",
     "v_positive refuted at a psi witness where V <= 1 (not V <= 0): a false counterexample"),
    ("sublevel_faces_refute_below_1", "rigor_gyro/kinds/lyapunov/sublevel.py",
     "if face.is_finite() and certainly_le(face, 0):", "if face.is_finite() and certainly_le(face, 1):",
     "largest_sublevel refuted on the faces' level <= 1 (not <= 0)"),
    ("sublevel_origin_counterexample_A_le_1", "rigor_gyro/kinds/lyapunov/sublevel.py",
     "if A.is_finite() and certainly_le(A, 0) and not A.contains(0):",
     "if A.is_finite() and certainly_le(A, 1) and not A.contains(0):",
     "the origin counterexample of largest_sublevel taken where A(0, t) <= 1 (not < 0)"),
    ("sublevel_point_without_vdot", "rigor_gyro/kinds/lyapunov/sublevel.py",
     "(x1 != 0 or x3 != 0) and certainly_le(abs(x2), xs) and certainly_positive(g.vdot(x1, x2, x3))",
     "(x1 != 0 or x3 != 0) and certainly_le(abs(x2), xs) or certainly_positive(g.vdot(x1, x2, x3))",
     "a point of {Vdot > 0} for c_max's upper bound accepted without Vdot > 0 certified"),
    ("direct_upper_point_without_vdot", "rigor_gyro/kinds/lyapunov/claims.py",
     "        if certainly_le(abs(x2p), xs) and certainly_positive(g.vdot(x1, x2p, x3)):",
     "        if certainly_le(abs(x2p), xs) or certainly_positive(g.vdot(x1, x2p, x3)):",
     "the direct test's upper bound of the supremum taken at a point without Vdot > 0 certified"),
    ("mu_decimal_inside_one_end", "rigor_gyro/kinds/lyapunov/claims.py",
     "if certainly_lt(lo, _q(_fmpq(Fraction(cand)))) and certainly_lt(", "if certainly_lt(lo, _q(_fmpq(Fraction(cand)))) or certainly_lt(",
     "the decimal chosen for mu_best checked against one end of (16) only"),
    ("equilibrium_inside_without_v", "rigor_gyro/kinds/lyapunov/claims.py",
     "            elif certainly_le(abs(e.x2), xs) and certainly_lt(e.x1 * e.x1, R * R) and \\\n",
     "            elif certainly_le(abs(e.x2), xs) and certainly_lt(e.x1 * e.x1, R * R) or \\\n",
     "an equilibrium called inside the estimate without V < c_set certified"),
    ("near_zero_cauchy_at_near_end", "rigor_gyro/kinds/periodic_orbit/flow.py",
     "        c = abs(center).upper()", "        c = abs(center).lower()",
     "the near-zero series' Cauchy bound at a ball taken at its near end (the tail shrunk)"),
    ("near_zero_tail_constant_shrunk", "rigor_gyro/kinds/periodic_orbit/flow.py",
     "self.tail = (2 * arb.pi() ** 2 / 3) * abs(S)", "self.tail = (2 * arb.pi() ** 2 / 4) * abs(S)",
     "a constant of the near-zero series' tail bound shrunk (2 pi^2/3 -> 2 pi^2/4)"),
    # issue 10, 2026-12-05 (second session): mutmut survivors of the margins layer and the checker's own
    # gates, each letting a false statement through on some input and none killed before this session
    ("paving_check_point_status_unread", "rigor_gyro/margins/check.py",
     '            if got != p["status"]:', '            if False:',
     "the paving checker re-runs a stored point proof but never compares its status with the stored one"),
    ("paving_check_tiles_ignore_frozen", "rigor_gyro/margins/check.py",
     "    return tiles_by_bisection(whole, boxes, frozen)", "    return tiles_by_bisection(whole, boxes)",
     "the paving checker rebuilds the bisection tree splitting edges the paving never splits"),
    ("paving_check_skips_after_undecided", "rigor_gyro/margins/check.py",
     '            if s == "undecided":\n                continue', '            if s == "undecided":\n                break',
     "the paving checker stops re-evaluating decided sub-boxes at the first undecided one"),
    ("threshold_ends_swapped", "rigor_gyro/margins/threshold.py",
     '    p, r = (lo_q, hi_q) if ends[lo_q] == "proved" else (hi_q, lo_q)', "    p, r = (hi_q, lo_q)",
     "a threshold search takes its lower end for the refuted one: 'proved at' a refuted point when the "
     "claim is proved below"),
    ("threshold_bracket_one_end_twice", "rigor_gyro/margins/threshold.py",
     '"bracket": [fraction_text(b[0]), fraction_text(b[1])] if b else None,',
     '"bracket": [fraction_text(b[1]), fraction_text(b[1])] if b else None,',
     "the threshold file's bracket written with its upper end twice"),
    ("scan_domain_checked_off_the_ends", "rigor_gyro/margins/scan.py",
     "    for x in (values[0], values[-1]):", "    for x in (values[1], values[-1]):",
     "a scan checks the second point's domain instead of the first end's (proofs start outside the domain)"),
    ("check_gate_unknown_status_passes", "rigor_gyro/check.py",
     '        add(CheckResult("claims", False, f"unknown status(es) {bad_status}"))',
     '        add(CheckResult("claims", True, f"unknown status(es) {bad_status}"))',
     "the checker's gate on claim statuses passes an unknown status"),
    ("check_gate_refuted_verdict_unread", "rigor_gyro/check.py",
     '    verdict = ("refuted" if "refuted" in statuses else',
     '    verdict = ("refuted" if "refuted" in statuses and False else',
     "the checker re-derives a verdict without its refuted case (a refuted certificate relabelled "
     "inconclusive passes)"),
    ("sublevel_vertex_bound_raised", "rigor_gyro/kinds/lyapunov/model.py",
     "        return a - b * b / (4 * glo)", "        return a - b * b / (5 * glo)",
     "the lower bound of V over {Vdot >= 0} at the quadratic's vertex raised (b^2/4g -> b^2/5g): c_max too high"),
    ("v_polar_gamma_scaled", "rigor_gyro/kinds/lyapunov/model.py",
     "    gamma = ((h * ct + c.mu * st) ** 2 + g.S(x2) * st * st) / 2\n",
     "    gamma = ((h * ct + c.mu * st) ** 2 + g.S(x2) * st * st) / 3\n",
     "V's r^2 coefficient along a ray scaled by 2/3 (V along every ray misstated)"),
    ("slice_extent_x1_scaled", "rigor_gyro/kinds/lyapunov/model.py",
     "sqrt_of_nonnegative(2 * d * (S + mu * mu) / S)) / (g.c.H * x2.cos() / g.c.B0)",
     "sqrt_of_nonnegative(2 * d * (S + mu * mu) / S)) * (g.c.H * x2.cos() / g.c.B0)",
     "the invariant set's x1 extent multiplied by h instead of divided (a wrong certified extent; the "
     "checker shares the formula)"),
    ("psi_mu_term_scaled", "rigor_gyro/kinds/lyapunov/model.py",
     "(c.mu * c.H - self.q(x2)) + c.mu ** 2 * (self.f1(x2) - c.mu)",
     "(c.mu * c.H - self.q(x2)) + c.mu * 2 * (self.f1(x2) - c.mu)",
     "psi's mu^2 term written 2 mu: v_positive decided on a function without the sign of V's minimum "
     "(the checker shares psi)"),
    ("check_x2_extent_floor_raised", "rigor_gyro/kinds/lyapunov/check.py",
     "                                if \"extent_x2_axis\" in verified else arb(0))",
     "                                if \"extent_x2_axis\" in verified else arb(1))",
     "with no verified slice point the checker's x2 extent is the hull of 1 and x2* instead of [0, x2*]: a "
     "stored extent of the invariant set starting above 0, which nothing certifies, is confirmed"),
    ("check_x2_axis_root_unbracketed", "rigor_gyro/kinds/lyapunov/check.py",
     "root_in = certainly_le(lo_b, xs) and \\",
     "root_in = certainly_le(lo_b, xs) or \\",
     "the x2 axis segment confirmed on lo <= x2* alone: a segment that misses the root of mu F = c_set "
     "(the set's end on the axis) is confirmed"),
    ("direct_margin_centre_off_the_box", "rigor_gyro/kinds/lyapunov/model.py",
     "        um, sm = arb(U.mid()), arb(S.mid())",
     "        um, sm = arb(0), arb(S.mid())",
     "the direct test's mean-value form centred at u = 0, off the box: the derivative is bounded over the box "
     "only, so the form is no enclosure and a box can be certified positive where A - R|B| is not"),
    ("check_cylinder_bound_upper_ends", "rigor_gyro/kinds/lyapunov/check.py",
     "                v = lb(_b(p)).lower()",
     "                v = lb(_b(p)).upper()",
     "the Lyapunov checker bounds V on the cylinder by each piece's upper end: where the cylinder binds, a "
     "c_set above the certified lower bound of c* is confirmed"),
    ("check_r_sup_point_beyond_range", "rigor_gyro/kinds/lyapunov/check.py",
     "        if not _within(abs(x), arb(0), xs):\n            continue",
     "        if False:\n            continue",
     "the Lyapunov checker bounds R_sup over (16) with stored x2 points beyond x2* too, where rho is larger: "
     "an upper bound of R_sup far below its value is confirmed"),
    ("check_r_sup_rounded_down", "rigor_gyro/kinds/lyapunov/check.py",
     '    return (1 / L).upper() if certainly_positive(L) else arb("inf")',
     '    return (1 / L).lower() if certainly_positive(L) else arb("inf")',
     "the checker's bound of R_sup on a mu piece, 1 / rho_lower, rounded down (the lower end of its ball)"),
    ("check_mu_cover_short_of_mu_max", "rigor_gyro/kinds/lyapunov/check.py",
     '    return _covers(pieces, K["mu_min"].lower(), K["mu_max"].upper())',
     '    return _covers(pieces, K["mu_min"].lower(), K["mu_max"].lower())',
     "mu pieces ending inside mu_max's ball accepted as a cover of (16): values of mu that may lie in (16) left "
     "unbounded"),
    ("check_direct_point_vdot_possibly", "rigor_gyro/kinds/lyapunov/check.py",
     "if certainly_le(abs(x2), xs) and certainly_positive(g.vdot(x1, x2, x3)):",
     "if certainly_le(abs(x2), xs) or certainly_positive(g.vdot(x1, x2, x3)):",
     "R_direct_upper confirmed from a stored point where Vdot > 0 is not certain (or beyond x2*): a bound of "
     "the direct test's radius below its certified value is confirmed"),
    ("check_damping_without_constants", "rigor_gyro/kinds/lyapunov/check.py",
     '            if K is None:\n                say(cid, False, "needs the re-verified constants")',
     '            if K is None:\n                say(cid, True, "needs the re-verified constants")',
     "the damping condition confirmed when the constants it compares could not be re-verified"),
    ("check_faces_refutation_below_one", "rigor_gyro/kinds/lyapunov/check.py",
     "certainly_le(_face_level(g, xs), 0)", "certainly_le(_face_level(g, xs), 1)",
     "a refutation of the largest sublevel set at the faces confirmed where phi(+-x2*) is positive (up to 1)"),
    ("check_psi_point_x1_sign", "rigor_gyro/kinds/lyapunov/check.py",
     "    return c0 + c1 * x1 + c3 * x3", "    return c0 - c1 * x1 + c3 * x3",
     "a Psi counterexample decided on Psi with its x1 term's sign flipped: a refutation of a true Vdot <= 0 "
     "can be confirmed"),
    ("check_sublevel_confirmed_by_default", "rigor_gyro/kinds/lyapunov/check.py",
     'sub_ok, sub_msg = False, "no stored boxes"', 'sub_ok, sub_msg = True, "no stored boxes"',
     "a proved largest sublevel set without its witness confirmed"),
    ("check_cylinder_samples_beyond_range", "rigor_gyro/kinds/lyapunov/model.py",
     "for x2 in (arb(0), xs / 2, xs) for c, s_ in CIRCLE_DIRECTIONS]",
     "for x2 in (arb(0), xs * 2, xs) for c, s_ in CIRCLE_DIRECTIONS]",
     "the upper end of c* (prover and checker) from V sampled at |x2| = 2 x2*, beyond the cylinder piece c* is "
     "the minimum over"),
    ("cylinder_samples_off_the_circle", "rigor_gyro/kinds/lyapunov/model.py",
     "((1 - t * t) / (1 + t * t), 2 * t / (1 + t * t))", "((1 - t * t) / (1 + t * t), t / (1 + t * t))",
     "the sample directions off the unit circle (s halved): V sampled inside the disc, an upper end of c* "
     "that may lie below it"),
    ("check_x2_axis_capped_on_mu_over_F", "rigor_gyro/kinds/lyapunov/check.py",
     "capped = certainly_lt(c.mu * g.F(xs), cl)", "capped = certainly_lt(c.mu / g.F(xs), cl)",
     "the x2 axis segment taken as capped at x2* on a wrong test: a segment around x2*, above the root of "
     "mu F = c_set, is confirmed"),
    ("check_cylinder_margin_on_a_product", "rigor_gyro/kinds/lyapunov/check.py",
     "    return (cyl / c_star_up - 1).lower()", "    return (cyl * c_star_up - 1).lower()",
     "the checker's bound of the cylinder margin min V / c* - 1 computed as cyl c* - 1: a margin far above the "
     "true one is confirmed"),
    ("check_x2_extent_beyond_on_either", "rigor_gyro/kinds/lyapunov/check.py",
     "if _covers(beyond, start, xs) and _all_positive(", "if _covers(beyond, start, xs) or _all_positive(",
     "the x2 extent ended below x2* when the pieces beyond do not cover the rest: an extent of the set that "
     "is too short is confirmed"),
    ("check_invariant_without_vdot", "rigor_gyro/kinds/lyapunov/check.py",
     'proved = vdot_ok and v_ok and ic.get("status") == "proved"',
     'proved = vdot_ok and v_ok or ic.get("status") == "proved"',
     "the invariant estimate confirmed when Vdot <= 0 or V > 0, which it rests on, is not"),
    ("check_faces_inside_m3_twice", "rigor_gyro/kinds/lyapunov/model.py",
     "    return certainly_lt(m1 ** 2 + m3 ** 2, R ** 2)", "    return certainly_lt(m1 ** 2 + m3 * 2, R ** 2)",
     "the faces' minimiser taken as inside the disc where it is not (m3 < 0): c*'s upper end from the faces' "
     "closed form, which then need not bound V's minimum over the region's face"),
    ("check_extent_cover_either", "rigor_gyro/kinds/lyapunov/check.py",
     'if we_ and _covers(we_.get("cover", []), arb(0), xs):', 'if we_ or _covers(we_.get("cover", []), arb(0), xs):',
     "an extent of the invariant set bounded above over stored pieces that do not cover [0, x2*]: an extent "
     "too short is confirmed"),
    ("check_x2_extent_beyond_phi_plus_c", "rigor_gyro/kinds/lyapunov/check.py",
     "lambda y: g.phi(y) - cl, x, cert_prec), beyond):", "lambda y: g.phi(y) + cl, x, cert_prec), beyond):",
     "the pieces beyond the x2 extent's end checked on phi + c_set > 0 (always) instead of phi > c_set: an "
     "extent that ends before the set does is confirmed"),
    ("check_direct_point_beyond_range", "rigor_gyro/kinds/lyapunov/check.py",
     "if certainly_le(abs(x2), xs) and certainly_positive(g.vdot(x1, x2, x3)):",
     "if True and certainly_positive(g.vdot(x1, x2, x3)):",
     "R_direct_upper confirmed from a point beyond x2* (outside the region the direct test is about), where "
     "Vdot > 0 at a radius below R_direct"),
    ("check_rho_at_point_rounded_up", "rigor_gyro/kinds/lyapunov/check.py",
     "    return rho(x2).lower() if _within(abs(x2), arb(0), xs) else arb(0)",
     "    return rho(x2).upper() if _within(abs(x2), arb(0), xs) else arb(0)",
     "rho at R_sup(mu_best)'s point rounded up: the enclosure of R_sup(mu_best) may end below it"),
    ("check_slice_point_beyond_range", "rigor_gyro/kinds/lyapunov/check.py",
     "    if _within(abs(pt), arb(0), xs) and slice_in_region(g, cl, R, pt):",
     "    if _within(abs(pt), arb(0), xs) or slice_in_region(g, cl, R, pt):",
     "an extent's lower end taken from a stored slice point beyond x2* (outside the region) whose slice lies in "
     "the disc: a lower end from outside the set"),
    ("check_slice_point_rounded_up", "rigor_gyro/kinds/lyapunov/check.py",
     "        return value(pt).lower()\n    return fallback", "        return value(pt).upper()\n    return fallback",
     "an extent's lower end from a slice point rounded up: it may lie beyond the set's extent"),
    ("check_cylinder_margin_rounded_up", "rigor_gyro/kinds/lyapunov/check.py",
     "    return (cyl / c_star_up - 1).lower()", "    return (cyl / c_star_up - 1).upper()",
     "the checker's bound of the cylinder margin min V / c* - 1 rounded up: a stored margin above the true one "
     "by up to the ball's width is confirmed"),
    ("c_star_lower_from_cylinder_alone", "rigor_gyro/kinds/lyapunov/model.py",
     "    return face.lower().min(cyl) if inside else cyl", "    return cyl",
     "c*'s lower bound from the cylinder alone where the faces' minimiser is inside the disc: a c_set above the "
     "faces' level (below the cylinder's) is confirmed, and the sublevel set may cross the faces"),
    ("c_star_lower_from_face_upper", "rigor_gyro/kinds/lyapunov/model.py",
     "    return face.lower().min(cyl) if inside else cyl", "    return face.upper().min(cyl) if inside else cyl",
     "c*'s lower bound from the faces' value's upper end: a c_set within that ball's width above c* is certified "
     "(prover) and confirmed (checker)"),
    ("c_star_upper_from_an_outside_minimiser", "rigor_gyro/kinds/lyapunov/model.py",
     "    return upper.upper().min(face.upper()) if inside else upper.upper()",
     "    return upper.upper().min(face.upper())",
     "c*'s upper bound lowered to phi(x2*) when the faces' minimiser lies outside the disc, where phi(x2*) bounds "
     "nothing of c*: a stored c* enclosure below the true c* is confirmed"),
    ("c_star_upper_from_lower_ends", "rigor_gyro/kinds/lyapunov/model.py",
     "    return upper.upper().min(face.upper()) if inside else upper.upper()",
     "    return upper.lower().min(face.upper()) if inside else upper.upper()",
     "c*'s upper bound from the cylinder samples' lower ends (the faces' minimiser inside, the cylinder binding): "
     "a bound up to a ball's width below c*"),
    ("check_counterexample_region_unit_disc", "rigor_gyro/kinds/lyapunov/check.py",
     "certainly_lt(x1 * x1 + x3 * x3, R * R))", "certainly_lt(x1 * x1 + x3 * x3, R / R))",
     "a Vdot or Psi counterexample accepted anywhere in the unit disc, not the region's disc of radius R: a "
     "refutation of a true Vdot <= 0 over the region is confirmed"),
    ("check_psi_counterexample_up_to_one", "rigor_gyro/kinds/lyapunov/check.py",
     'ok = in_region and certainly_le(psi_at_point(g, ce["psi"], x1, x2, x3), 0)',
     'ok = in_region and certainly_le(psi_at_point(g, ce["psi"], x1, x2, x3), 1)',
     "a Psi counterexample confirmed where Psi is positive up to 1: a refutation of the statement's Psi test "
     "at a point where it holds"),
    ("check_extent_cover_from_above_0", "rigor_gyro/kinds/lyapunov/check.py",
     'if we_ and _covers(we_.get("cover", []), arb(0), xs):', 'if we_ and _covers(we_.get("cover", []), arb(1), xs):',
     "an x1 or x3 extent bounded above over stored pieces that need not start at 0: the slices near x2 = 0 left "
     "unbounded, an extent too short confirmed"),
    ("check_origin_refutation_at_t_0", "rigor_gyro/kinds/lyapunov/check.py",
     "vdot_polar(g, arb(0), arb.pi() * arb(fmpq_of(t)))[0] if t", "vdot_polar(g, arb(0), arb(0))[0] if t",
     "a refutation of the largest sublevel set at the origin decided at t = 0 whatever t it states: a stored "
     "counterexample direction where A(0, t) > 0 is confirmed"),
    ("check_x2_extent_up_to_x2_star_lower_end", "rigor_gyro/kinds/lyapunov/check.py",
     "                    up = xs.upper()", "                    up = xs.lower()",
     "the x2 extent's upper end, without pieces beyond, taken at x2*'s lower end: an extent ending inside x2*'s "
     "ball, below pi/6, is confirmed"),
    ("check_x2_extent_floor_from_axis_upper_end", "rigor_gyro/kinds/lyapunov/check.py",
     'arb(fmpq_of(stored_interval(q["extent_x2_axis"])[0]))', 'arb(fmpq_of(stored_interval(q["extent_x2_axis"])[1]))',
     "the x2 extent's lower end, without a verified slice point, from the axis segment's stored upper end: an "
     "extent starting above the verified one is confirmed"),
    ("check_v_counterexample_up_to_one", "rigor_gyro/kinds/lyapunov/check.py",
     "off_origin and certainly_le(g.V(x1, x2, x3), 0)", "off_origin and certainly_le(g.V(x1, x2, x3), 1)",
     "a V counterexample confirmed where V is positive up to 1: a refutation of V > 0 at a point where it holds"),
    ("sine_G_c0_zero_halved", "rigor_gyro/kinds/lyapunov/moments.py",
     "            return a * x.sin() ** 2 / (2 * A0)", "            return a * x.sin() ** 2 / (4 * A0)",
     "the sine law's G halved when C0 = 0 (its own branch): V's potential term, and every bound built on it, "
     "for a gimbal without C0"),
    ("log1m_tail_shrunk", "rigor_gyro/kinds/lyapunov/moments.py",
     "    return r ** n / ((n + 1) * (1 - r))", "    return r ** n / ((n + 2) * (1 - r))",
     "the series tail of L(u) = -log(1 - u)/u (q's closed form for the sine law) shrunk below the remainder"),
    ("direct_bound_from_first_piece", "rigor_gyro/kinds/lyapunov/direct_mu.py",
     "        if not u.is_finite() or (U.is_finite() and certainly_gt(u, U)):",
     "        if not u.is_finite() and (U.is_finite() and certainly_gt(u, U)):",
     "the bound of R_dsup over (16) taken from the heap's first piece, not the largest by exact comparison: a "
     "misordered key lowers the certified bound"),
    # issue 36 part 3: the direct test's box function with |B| taken at its midpoint
    ("direct_margin_abs_b_radius_dropped", "rigor_gyro/kinds/lyapunov/model.py",
     "        direct = A - R * abs(B)\n", "        direct = A - R * abs(B).mid()\n",
     "the radius of |B| dropped from A - R |B| (direct_margin: vdot_direct, best_mu_direct and the checker): a "
     "box's lower bound above the minimum of A - R |B| over it, so Vdot < 0 certified where it may fail"),
    # issue 36 part 1: the checker's re-derivation of what a certificate or a paving states
    ("texts_not_compared", "rigor_gyro/reproduce.py",
     "        where = _first_difference(stored.get(key), derived.get(key), key)\n", "        where = None\n",
     "a certificate's reasons, details, counterexamples, extra and notes confirmed without comparing them with "
     "the prover's re-derivation (the forged texts of the tamper corpus confirmed)"),
    ("paving_points_waived_without_a_stop", "rigor_gyro/margins/check.py",
     '        if isinstance(data.get("stopped"), str) and data["stopped"] and not stored:',
     "        if not stored:",
     "a paving with its point proofs (the refuted boxes' re-checkable counterexamples) removed confirmed, "
     "though no time limit stopped it"),
    ("paving_reasons_not_compared", "rigor_gyro/margins/check.py",
     '        ok = c.get("reasons") == dict(sorted(reasons.items()))', "        ok = True",
     "a paving's reasons (the report's 'why' of each sub-box status) confirmed without re-deriving them"),
    # issue 38: anytime and resumable pavings (margins/order.py, resume.py; tests/test_paving_anytime.py)
    ("paving_pending_stated_refuted", "rigor_gyro/margins/paving.py",
     '        boxes = list(cp.boxes) + [(b, "undecided") for g in pending if c in g.claims for b in g.boxes]',
     '        boxes = list(cp.boxes) + [(b, "refuted") for g in pending if c in g.claims for b in g.boxes]',
     "a paving stopped by a budget states its pending (never evaluated) boxes refuted: a budget refutes"),
    ("paving_pending_check_accepts_decided", "rigor_gyro/margins/check.py",
     '                    if leaves.get(c, {}).get(b.edges) != "undecided":',
     "                    if False:",
     "the paving checker, and so --resume, accepts a pending (never evaluated) box stated proved"),
    ("paving_pending_without_a_stop", "rigor_gyro/margins/check.py",
     "    if not stopped:\n        return CheckResult(\"pending\", False,",
     "    if False:\n        return CheckResult(\"pending\", False,",
     "a paving that ran its course with a pending list confirmed: resume re-opens boxes it states decided"),
    ("resume_trusts_the_paving", "rigor_gyro/margins/resume.py",
     "    verify_paving(data, executor)\n", "",
     "--resume continues a paving without checking it: a tampered sub-box or pending list is carried on"),
    ("resume_pending_kept_as_leaves", "rigor_gyro/margins/resume.py",
     "                continue                                    # pending: queued again below",
     "                pass",
     "--resume keeps a pending box as a leaf beside its evaluated halves (the sub-boxes overlap)"),
    ("lyap_inside_point_beyond_the_end", "rigor_gyro/kinds/lyapunov/model.py",
     "        if x.rad().is_zero() and certainly_positive(x) and certainly_le(x, xs):\n            out.append(x)",
     "        out.append(arb(fmpq(*_pair(exact_fraction(w.upper())))))",
     "a v_positive / Psi counterexample placed at the upper end of the x2* ball (beyond the range |x2| <= x2*)"),
    ("lyap_no_rational_point_inside", "rigor_gyro/kinds/lyapunov/model.py",
     "    for j in INSIDE_STEPS:      # lo,", "    for j in ():      # lo,",
     "no rational point inside the range tried: v_positive stays inconclusive where psi <= 0 reaches x2* (issue 37)"),
    # issue 37 part 2, tracked objects: the relay option orbit (the root of g nearest a given half-period)
    ("tracked_nearest_possibly", "rigor_gyro/kinds/periodic_orbit/tracked.py",
     "ok = reach.is_finite() and all(certainly_lt(reach, d) for d, _ in rivals)",
     "ok = reach.is_finite() and all(not certainly_lt(d, reach) for d, _ in rivals)",
     "the tracked root certified nearest on 'possibly nearer' (a tie accepted)"),
    ("tracked_reach_to_nearest_point", "rigor_gyro/kinds/periodic_orbit/tracked.py",
     "    reach = (t - lo).max(hi - t)", "    reach = (t - lo).min(hi - t)",
     "the tracked root's distance bounded by its enclosure's nearest point, not its farthest"),
    ("tracked_undecided_pieces_ignored", "rigor_gyro/kinds/periodic_orbit/tracked.py",
     "    for a, b in unknown:\n", "    for a, b in ():\n",
     "a root in an undecided piece of the range ignored when certifying the nearest root"),
    ("tracked_unsearched_roots_ignored", "rigor_gyro/kinds/periodic_orbit/tracked.py",
     "    if beyond is not None:\n        rivals", "    if False:\n        rivals",
     "roots beyond T_max (not searched) ignored when certifying the nearest root"),
    ("tracked_claims_without_nearness", "rigor_gyro/kinds/periodic_orbit/tracked_claims.py",
     "    if not nr.certified:\n        return all_of(", "    if False:\n        return all_of(",
     "the tracked claims decided about a root not certified nearest the option"),
    ("tracked_checker_nearness_unchecked", "rigor_gyro/kinds/periodic_orbit/check.py",
     "certified = tracked is not None and tracked[0].certified", "certified = tracked is not None",
     "the relay checker confirms a tracked claim without re-certifying that its root is the nearest"),
    ("tracked_checker_unstable_possibly", "rigor_gyro/kinds/periodic_orbit/check.py",
     "and any(certainly_gt(m, 1) for m in moduli_main)", "and any(not certainly_lt(m, 1) for m in moduli_main)",
     "the relay checker confirms a tracked 'stable' refutation on a modulus only possibly > 1"),
    ("lyap_box_face_wrong_end", "rigor_gyro/kinds/lyapunov/box_forms.py",
     "sub[k] = LO if d.d >= 0 else HI", "sub[k] = HI if d.d >= 0 else LO",
     "a Lyapunov box lower bound taken at the face where h is largest, not smallest, of a monotone parameter"),
    ("lyap_box_w_face_wrong_end", "rigor_gyro/kinds/lyapunov/box_forms.py",
     "W = arb(W.lower()) if d.d >= 0 else arb(W.upper())", "W = arb(W.upper()) if d.d >= 0 else arb(W.lower())",
     "the maximum w = A0 m fixed at the wrong end of its enclosure in a Lyapunov box lower bound"),
    ("lyap_box_centred_term_dropped", "rigor_gyro/kinds/lyapunov/box_forms.py",
     'mv = mv + d * ((W - w_mid) if k == "w" else self.width[k])', "mv = mv",
     "the centred form's derivative terms dropped (the midpoint value taken for the whole box)"),
    ("lyap_w_enclosure_is_m", "rigor_gyro/kinds/lyapunov/box_forms.py",
     "return abs(x.cos() * law.df(a, x)) / (1 - r * s * s)", "return abs(x.cos() * law.df(a, x)) / (pb.A0 - pb.C0 * s * s)",
     "the box enclosure of w = A0 m computed as m (R2 of (14) then far too large over a box)"),
    ("lyap_damping_lower_wrong_mu_end", "rigor_gyro/kinds/lyapunov/box_quantities.py",
     "klo / (mhi * A0hi)]", "klo / (mlo * A0hi)]",
     "the damping margin's lower bound over a box taken at mu's lower end (k/(mu A0) decreases in mu)"),
    ("lyap_c_star_box_face_ignored", "rigor_gyro/kinds/lyapunov/box_levels.py",
     "lower = arb(face_lo).min(arb(cyl_lb))", "lower = arb(cyl_lb)",
     "c* over a box bounded below by the cylinder alone, where the faces' minimum inside the disc is smaller"),
    ("lyap_v_margin_max_of_parts", "rigor_gyro/kinds/lyapunov/box_levels.py",
     "return (1 - c.mu / f1).min(g.psi(x2) / pos)", "return (1 - c.mu / f1).max(g.psi(x2) / pos)",
     "the v_positive margin over a box taken as the larger, not the smaller, of its two parts"),
    ("threshold_witness_inconclusive_refutes", "rigor_gyro/margins/threshold_witness.py",
     '            if st == "refuted":\n                self.keep(point)', '            if st != "proved":\n                self.keep(point)',
     "a robust threshold step refuted at a box point where the point proof was only inconclusive"),
    ("threshold_check_witness_outside_box", "rigor_gyro/margins/threshold.py",
     "if want != \"refuted\" or box is None or not in_box(box, point):", "if want != \"refuted\" or box is None:",
     "the threshold checker accepts a refuting witness that is not a point of the other parameters' box"),
    ("threshold_check_witness_not_reproved", "rigor_gyro/margins/threshold.py",
     "st, why = point_status(scene, param, x, claim, point)", "st, why = \"refuted\", \"\"",
     "the threshold checker takes a stored witness's refutation without proving it again"),
    ("curve_cell_partly_proved_is_proved", "rigor_gyro/margins/threshold_curve.py",
     'if kinds == {"proved"}:', 'if "proved" in kinds:',
     "a threshold curve's cell called proved at a value where only part of the cell's leaves are proved"),
    ("curve_check_cells_not_tiling", "rigor_gyro/margins/threshold_curve.py",
     "and all(ends[i][1] == ends[i + 1][0] for i in range(len(ends) - 1)))", ")",
     "the curve checker accepts cells that leave a gap in the range of the second parameter"),
    ("curve_check_not_repaved", "rigor_gyro/margins/threshold_curve.py",
     "st, why = cell_status(scene, param, x, along, cell, claim)", "st, why = want, \"\"",
     "the curve checker takes each cell's stored proved and refuted values without paving the cell again"),
    ("system_bracket_every_def", "rigor_gyro/kinds/eigenfrequencies/system_model.py",
     "for name, e in self.defs_needed((lo, hi)):", "for name, e in self.defs:",
     "a [system] bracket refuted by a def it does not use (a certainly negative sqrt elsewhere)"),
    ("system_box_bracket_failed_def_ignored", "rigor_gyro/kinds/eigenfrequencies/system_boxes.py",
     "            if used:\n                raise failed[used[0]]", "            if False:\n                raise failed[used[0]]",
     "a [system] bracket over a box that uses a def with no real value is not refuted (and crashes)"),
    ("expressions_degree_unbounded", "rigor_gyro/core/expressions.py",
     "    if _degree(tree) > MAX_DEGREE:", "    if False:",
     "nested powers parsed without a bound: exact arithmetic exhausts memory (abort) or hangs"),
    ("system_check_counterexample_unchecked", "rigor_gyro/kinds/eigenfrequencies/system_check.py",
     'say(f"{cid} counterexample", *counterexample_ok(c["counterexample"], P, mu, odd, Q, model.zero_roots))',
     'say(f"{cid} counterexample", True, "")',
     "the [system] checker confirms a refutation without re-deriving its counterexample data"),
    ("lyap_psi_margin_bisection_swapped", "rigor_gyro/kinds/lyapunov/box_quantities.py",
     "        if holds(m):\n            a = m\n        else:\n            b = m",
     "        if holds(m):\n            b = m\n        else:\n            a = m",
     "the Psi margin's lower end over a box raised where ci0 - (1 + t) R |.| > 0 was not proved"),
    ("relay_box_continues_a_tracked_orbit", "rigor_gyro/kinds/periodic_orbit/box_orbit.py",
     '    if not wanted or getattr(model, "orbit", None) is not None:', "    if not wanted:",
     "a tracked orbit continued over a box without certifying it is the root nearest the option"),
    # the nutation cubic's roots over a wide box by parametric Newton (issue 37: tau +-5 % and wider)
    ("poly_root_box_newton_radius_dropped", "rigor_gyro/core/implicit_roots.py",
     "            out = pred_value + (acb(arb(0, r)) if is_real else acb(arb(0, r), arb(0, r)))",
     "            out = pred_value",
     "a polynomial root over a box enclosed by its linear predictor's range alone, without the Newton radius"),
    ("poly_root_box_centre_residual_dropped", "rigor_gyro/core/implicit_roots.py",
     "    h = centred(poly(coefficients, Jet(pred_value, slope)), poly(centre_coefficients, z0))",
     "    h = centred(poly(coefficients, Jet(pred_value, slope)), acb(0))",
     "the predictor's residual at the centre taken as 0 (the start assumed to be the centre's root)"),
    ("poly_root_box_mignitude_upper", "rigor_gyro/core/implicit_roots.py",
     "    return arb(out.lower())\n", "    return arb(out.upper()) * 4\n",
     "the smallest |C'| over the band replaced by an upper bound (the Newton radius too small)"),
    ("relay_cubic_product_derivative_no_conjugate", "rigor_gyro/kinds/periodic_orbit/parametric.py",
     "        for o in ([mu] if j != idx else []) + ([mu.conjugate()] if w == 2 else []):",
     "        for o in ([mu] if j != idx else []):",
     "C'(lambda) as a product of root differences without the complex roots' conjugates"),
    ("relay_cubic_scaled_coefficient_wrong_power", "rigor_gyro/kinds/periodic_orbit/parametric.py",
     "        scaled = [c[0] / (s * s * s), c[1] / (s * s), c[3], c[3]]",
     "        scaled = [c[0] / (s * s * s), c[1] / s, c[3], c[3]]",
     "the cubic in the scaled variable w = z / c_2 with a wrong coefficient (not the same roots)"),
    ("relay_sign_extend_without_certificate", "rigor_gyro/kinds/periodic_orbit/continuation.py",
     "        if certainly_lt(a, b) and holds(a, b):", "        if certainly_lt(a, b) or holds(a, b):",
     "a monotone stretch of beta extended over a piece where beta's derivative sign was not certified"),
    ("ranges_outer_hull_first_tile", "rigor_gyro/margins/ranges.py",
     '        lo = min(_pair(v["value"])[0] for _, v in enclosed)', '        lo = _pair(enclosed[0][1]["value"])[0]',
     "a quantity's certified lower end taken from one sub-box instead of all that tile the box"),
    ("ranges_inner_without_full_cover", "rigor_gyro/margins/ranges.py",
     "            if covered == 1 and v_low[1] <= v_high[0]:", "            if v_low[1] <= v_high[0]:",
     "an inner range stated where the quantity is not enclosed on the whole box (continuity unproved)"),
    # parametric forms over a box (issue 37 part 1, eigenfrequencies: core.dual_balls, centred_forms, implicit_roots)
    ("dual_product_rule_one_term", "rigor_gyro/core/dual_balls.py",
     "        return Dual(u * v, _add(_scale(self.grad, v), _scale(o.grad, u)))",
     "        return Dual(u * v, _scale(self.grad, v))", "forward-mode AD in balls drops one term of the product rule"),
    ("dual_plain_arb_as_constant", "rigor_gyro/core/dual_balls.py",
     "    if isinstance(x, fmpq):\n        return arb(x)\n", "    if isinstance(x, (fmpq, arb)):\n        return arb(x)\n",
     "a plain arb (gradient unknown) taken as a constant in Dual arithmetic"),
    ("centred_form_gradient_dropped", "rigor_gyro/core/centred_forms.py",
     "                centred = centred + g * (box.ball(k) - exact_ball(mid[k]))", "                centred = centred",
     "the centred form without its gradient term (the midpoint's value taken for the whole box)"),
    ("monotone_face_wrong_end", "rigor_gyro/core/centred_forms.py",
     "                at_lo = signed[k] * side < 0", "                at_lo = signed[k] * side > 0",
     "a monotone function's minimum taken on the face where it is largest"),
    ("sign_strict_ignored", "rigor_gyro/core/centred_forms.py",
     "        return certainly_gt(v, 0) if strict else certainly_le(0, v)", "        return certainly_le(0, v)",
     "a strict sign condition f > 0 proved from f >= 0"),
    ("implicit_gradient_sign_flipped", "rigor_gyro/core/implicit_roots.py",
     "    out = Dual(X, {k: -v / gx for k, v in D.grad.items() if k != ROOT})",
     "    out = Dual(X, {k: v / gx for k, v in D.grad.items() if k != ROOT})",
     "the implicit function theorem's derivative -G_p / G_x with the wrong sign"),
    ("parametric_newton_radius_dropped", "rigor_gyro/core/implicit_roots.py",
     "                return centre + arb(0, r)", "                return centre",
     "the parametric Newton root ball without the Newton radius (the linear predictor's range alone)"),
    ("eig_box_gap_undecided_refutes", "rigor_gyro/kinds/eigenfrequencies/boxes.py",
     '        if st == "negative":\n            return "refuted"', '        if st != "positive":\n            return "refuted"',
     "an eigenfrequency box claim refuted where one of its gaps was only not proved positive"),
    # the bracket gaps' second-order form (issue 37, the bracket (8) layer: kinds/eigenfrequencies/second_order.py)
    ("jet2_product_diagonal_halved", "rigor_gyro/kinds/eigenfrequencies/second_order.py",
     "                t = u * w if i != j else 2 * u * w", "                t = u * w",
     "second-order AD in balls: the product rule's u_i v_i + u_i v_i counted once on the Hessian's diagonal"),
    ("jet2_sqrt_second_sign", "rigor_gyro/kinds/eigenfrequencies/second_order.py",
     "        return self._unary(s, 1 / (2 * s), -1 / (4 * s * v))", "        return self._unary(s, 1 / (2 * s), 1 / (4 * s * v))",
     "second-order AD in balls: sqrt's second derivative with the wrong sign"),
    ("jet2_reciprocal_second_half", "rigor_gyro/kinds/eigenfrequencies/second_order.py",
     "        return self._unary(r, -r * r, 2 * r * r * r)", "        return self._unary(r, -r * r, r * r * r)",
     "second-order AD in balls: 1/v's second derivative 2/v^3 halved"),
    ("implicit_hessian_qww_dropped", "rigor_gyro/kinds/eigenfrequencies/second_order.py",
     "            h[(i, j)] = -(qij + qwi * wi[j] + qwj * wi[i] + qww * wi[i] * wi[j]) / qw",
     "            h[(i, j)] = -(qij + qwi * wi[j] + qwj * wi[i]) / qw",
     "the implicit root's Hessian without the Q_ww w_i w_j term"),
    ("gap_form_linear_term_dropped", "rigor_gyro/kinds/eigenfrequencies/second_order.py",
     "        out += gM.g.get(k, arb(0)) * d[k]", "        out += 0",
     "the second-order form of a gap without its gradient term at the midpoint"),
    ("gap_sign_straddle_refutes", "rigor_gyro/kinds/eigenfrequencies/second_order.py",
     "    if hi < 0:\n", "    if lo < 0:\n",
     "a bracket gap whose second-order form straddles 0 taken as negative on the whole box"),
    ("box8_second_form_other_gap", "rigor_gyro/kinds/eigenfrequencies/boxes.py",
     '("lower", "upper")[i]', '("upper", "lower")[i]',
     "a bracket's lower gap decided by the second-order form of its upper gap"),
    # counterexamples searched over the whole box (issue 38: margins/counterexamples.py, core/halton.py)
    ("cx_probe_is_a_counterexample", "rigor_gyro/margins/counterexamples.py",
     '    return [p for p in proofs if p["status"] == "refuted"]\n',
     '    return [p for p in proofs if p["status"] == "refuted" or p.get("probe") == "refuted"]\n',
     "a candidate the low-precision probe refuted counted as a certified counterexample without a refuted point proof"),
    ("cx_leaf_contradiction_ignored", "rigor_gyro/margins/counterexamples.py",
     '        if {leaf_status, res["status"]} == {"proved", "refuted"}:\n', "        if False:\n",
     "a point proof refuting a claim inside a leaf stored proved (two rigorous paths disagreeing) passes silently"),
    ("cx_candidate_leaf_unchecked", "rigor_gyro/margins/counterexamples.py",
     "        if not contains(leaves[c.leaf][0], c.point):\n", "        if False:\n",
     "a counterexample reported in a leaf that does not contain it"),
    ("cx_contains_first_edge_only", "rigor_gyro/margins/counterexamples.py",
     "    return all(lo <= point[k] <= hi for k, lo, hi in box.edges)\n",
     "    return all(lo <= point[k] <= hi for k, lo, hi in box.edges[:1])\n",
     "a point counted inside a leaf when only its first coordinate is"),
    ("cx_agreement_always", "rigor_gyro/margins/counterexamples.py",
     "    ok = float(lo_c) <= hi and lo <= float(hi_c)\n", "    ok = True\n",
     "the Monte Carlo cross-check reports agreement with a paving whatever the two say"),
    ("cx_unknown_samples_dropped", "rigor_gyro/margins/counterexamples.py",
     "        _, hi = wilson_interval(k + u, samples, confidence)\n",
     "        _, hi = wilson_interval(k, samples, confidence)\n",
     "the Monte Carlo interval's upper end ignores the samples the classifier left undecided"),
    ("halton_point_in_first_box", "rigor_gyro/core/halton.py",
     "        box = boxes[k]\n", "        box = boxes[0]\n",
     "a volume-weighted Halton point placed in the first box while reported in the box it picked"),
    # the checker's side of the counterexample search and the Monte Carlo cross-check (issue 38)
    ("cxc_reproof_unread", "rigor_gyro/margins/counterexample_check.py",
     "            if got.get(key) != p.get(key):\n", "            if False:\n",
     "a stored search point's status, reason or precision accepted without the point prover giving them again"),
    ("cxc_leaf_containment_skipped", "rigor_gyro/margins/counterexample_check.py",
     "        if not contains(box, point):\n", "        if False:\n",
     "a stored counterexample accepted in a leaf that does not contain it"),
    ("cxc_leaf_status_unchecked", "rigor_gyro/margins/counterexample_check.py",
     "        if p.get(\"leaf_status\") != status:\n", "        if False:\n",
     "a search point's stored leaf status accepted without comparing it with the leaf"),
    ("cxc_contradiction_ignored", "rigor_gyro/margins/counterexample_check.py",
     "        if {status, got[\"status\"]} == _CONTRADICTORY:\n", "        if False:\n",
     "the checker accepts a counterexample inside a leaf stored proved"),
    ("cxc_counts_unchecked", "rigor_gyro/margins/counterexample_check.py",
     "    if search.get(\"refuted\") != refuted or search.get(\"leaves\") != sorted(refuted_leaves):\n",
     "    if False:\n", "a search's stated number of counterexamples and their leaves not re-derived from its proofs"),
    ("cxc_mc_interval_unchecked", "rigor_gyro/margins/counterexample_check.py",
     "        if not (_close(stored[\"fraction\"], k / n if n else 0.0) and _close(lo_s, lo) and _close(hi_s, hi)):\n",
     "        if False:\n", "a Monte Carlo fraction or interval that does not follow from its counts accepted"),
    ("cxc_mc_rerun_ignored", "rigor_gyro/margins/counterexample_check.py",
     "        if (fresh[\"samples\"], fresh[\"failing\"], fresh[\"unknown\"]) != (n, k, u):\n", "        if False:\n",
     "a Monte Carlo estimate whose counts a re-run with its seed does not give accepted"),
    ("eig_system_odd_terms_ignored", "rigor_gyro/kinds/eigenfrequencies/system_model.py",
     "    if mu != z or odd:\n", "    if mu != z:\n",
     "a damped system's odd terms ignored: its even part taken as the frequency polynomial (stability proved)"),
    ("eig_system_zero_roots_unchecked", "rigor_gyro/kinds/eigenfrequencies/system_model.py",
     "    if mu != z or odd:\n", "    if odd:\n",
     "the multiplicity of lambda = 0 not compared with zero_roots (an undeclared double zero root stripped)"),
    ("eig_system_skew_diagonal_unchecked", "rigor_gyro/kinds/eigenfrequencies/system_model.py",
     "        for j in range(i, n):\n", "        for j in range(i + 1, n):\n",
     "G's diagonal not checked: a G that is not skew accepted as gyroscopic"),
    ("eig_system_singular_mass_accepted", "rigor_gyro/kinds/eigenfrequencies/system_model.py",
     "    if Mq.det() == 0:\n", "    if False:\n", "a singular M accepted (P of lower degree, roots lost)"),
    ("eig_system_nonreal_ignored", "rigor_gyro/kinds/eigenfrequencies/system_claims.py",
     "            if pr.nonreal or bad_real:\n", "            if bad_real:\n",
     "non-real omega (flutter) not refuting: the real roots alone proved stable"),
    ("eig_system_multiple_root_unrefuted", "rigor_gyro/kinds/eigenfrequencies/system_claims.py",
     "        if not pr.squarefree:\n", "        if False:\n",
     "a multiple root of Q (lambda not simple) not refuted exactly"),
    ("eig_system_bracket_one_side", "rigor_gyro/kinds/eigenfrequencies/system_claims.py",
     "        if certainly_le(lo, w) and certainly_le(w, hi):\n", "        if certainly_le(lo, w):\n",
     "a user bracket proved from its lower bound alone"),
    ("eig_system_checker_sturm_skipped", "rigor_gyro/kinds/eigenfrequencies/system_check.py",
     "    holds = structural_ok and squarefree and positive == m\n", "    holds = structural_ok and squarefree\n",
     "the [system] checker accepts stability without counting the positive real roots (Sturm)"),
    ("eig_system_checker_odd_ignored", "rigor_gyro/kinds/eigenfrequencies/system_check.py",
     "    if mu != model.zero_roots or odd:\n", "    if mu != model.zero_roots:\n",
     "the [system] checker forms Q from the even terms of a damped system"),
    ("eig_system_checker_no_sign_change", "rigor_gyro/kinds/eigenfrequencies/system_check.py",
     "    if pa == 0 or pb == 0 or (pa > 0) == (pb > 0):\n", "    if pa == 0 or pb == 0:\n",
     "the [system] checker accepts a stored omega interval without an exact sign change of Q"),
    ("eig_system_checker_bracket_one_side", "rigor_gyro/kinds/eigenfrequencies/system_check.py",
     "                if certainly_le(lo, w) and certainly_le(w, hi):\n", "                if certainly_le(lo, w):\n",
     "the [system] checker re-proves a bracket from its lower bound alone"),
    ("eig_system_expansion_sign", "rigor_gyro/core/polymat.py",
     "            sign = -sign\n", "            sign = sign\n",
     "the checker's Laplace expansion without alternating signs (a wrong determinant)"),
    ("eig_system_expr_negative_power", "rigor_gyro/core/expressions.py",
     "                    return number(Fraction(1)) / base ** (-n)\n", "                    return base ** (-n)\n",
     "x^-n read as x^n in a model entry"),
    ("eig_system_box_zero_rows_assumed", "rigor_gyro/kinds/eigenfrequencies/system_boxes.py",
     "    low = [k for k in range(z) if not c[k].is_zero()]\n", "    low = []\n",
     "over a box, lambda^z taken to divide P without its lowest coefficients being the zero polynomial"),
    ("eig_system_box_damping_assumed_even", "rigor_gyro/kinds/eigenfrequencies/system_boxes.py",
     "    odd = [k for k in range(z + 1, 2 * n + 1, 2) if not c[k].is_zero()]\n", "    odd = []\n",
     "over a box, a damped system's P taken as even"),
    ("eig_system_box_bracket_wrong_side", "rigor_gyro/kinds/eigenfrequencies/system_boxes.py",
     "        if certainly_gt(lo, w) or certainly_gt(w, hi):\n", "        if certainly_gt(lo, w) or certainly_lt(w, hi):\n",
     "over a box, a bracket refuted when the root is certainly below its upper bound"),
    ("eig_system_box_centred_offset_dropped", "rigor_gyro/kinds/eigenfrequencies/system_boxes.py",
     "        for g, o in zip(parts, offsets):\n            c += g * o\n",
     "        for g, o in zip(parts, offsets):\n            pass\n",
     "the box family's centred form without the parameters' offsets (the midpoint's value for every member)"),
    ("eig_system_box_symmetry_unchecked", "rigor_gyro/kinds/eigenfrequencies/system_boxes.py",
     "                if not _mirrored(a.tree, b.tree, sign):\n", "                if False:\n",
     "over a box, M symmetric / G skew taken from the midpoint alone (a pair toleranced apart accepted)"),
    # issue 39: the paper's own chain and the two-reference classifier (group audit)
    ("audit_edit_distance_ignored", "rigor_gyro/core/digit_edits.py",
     "        return dist >= t and c >= k + 1\n", "        return c >= k + 1\n",
     "an edit inside the computation's noise (a last digit a few units off) counts as evidence of a misprint"),
    ("audit_edit_constrained_digits_ignored", "rigor_gyro/core/digit_edits.py",
     "        return dist >= t and c >= k + 1\n", "        return dist >= t\n",
     "an edit against a window wider than the print's digits counts as evidence of a misprint"),
    ("audit_slack_ignored", "rigor_gyro/core/chain_classify.py",
     "        pad = h + 2 * h * slack\n", "        pad = h\n",
     "the author's own rounding beyond the chain is not allowed: his arithmetic becomes a misprint or unexplained"),
    ("audit_exact_agreement_skipped", "rigor_gyro/core/chain_classify.py",
     "    if status.value == \"agrees\":\n", "    if False:\n",
     "a print that rounds the exact value is judged against the chain only"),
    ("audit_identity_decides_alone", "rigor_gyro/core/chain_classify.py",
     "    refs = [(chain.value, True)] + ([(chain.computed, False)] if chain.computed is not None else [])\n",
     "    refs = [(chain.value, True)]\n",
     "an identity read from another print rejects the paper's arithmetic without the computed chain"),
    ("audit_rounding_interval_a_point", "rigor_gyro/core/paper_chain.py",
     "    lo, hi = x - h, x + h\n", "    lo, hi = x, x\n",
     "a printed input is read as exact, not as the interval of its rounding: the chain is no enclosure"),
    ("audit_identity_narrowing_unchecked", "rigor_gyro/kinds/periodic_orbit/paper_chain.py",
     "                if a <= b and (b - a) < (win[1] - win[0]):\n",
     "                if (b - a) < (win[1] - win[0]):\n",
     "an identity narrows a chain it contradicts (disjoint from the computed chain's window)"),
    ("audit_quartic_root_radius_dropped", "rigor_gyro/kinds/periodic_orbit/paper_chain.py",
     "        return x + arb(0, r.upper())\n", "        return x\n",
     "the roots of the printed quartic lose their Rouche radius: no enclosure over the coefficient intervals"),
    ("audit_eps_scale_fit_unchecked", "rigor_gyro/kinds/eigenfrequencies/paper_scale.py",
     "    if all(certainly_lt(l_, hi) for l_ in los) and all(certainly_lt(lo, h_) for h_ in his):\n",
     "    if True:\n",
     "Rudenko's 'exact' values are said to share one Hz scale at an eps where the scale ranges do not meet"),
    ("audit_candidate_without_downstream_evidence", "rigor_gyro/kinds/periodic_orbit/paper_chain.py",
     "        if gained and not (base - got - {rid}):\n", "        if True:\n",
     "a non-evidential edit becomes a misprint without a downstream row reproduced only with it"),
    # relay plants written in the scene ([plant], issue 42 part 1: periodic_orbit/plant_*.py)
    ("plant_tail_remainder_dropped", "rigor_gyro/kinds/periodic_orbit/plant_orbit.py",
     "        B += 2 * m.weight * abs(sp.S * m.rc / m.lam) * q / (1 - q)", "        B += 0 * q",
     "a plant's tail bound without the decaying modes' remainder: (T, oo) called root-free too early"),
    ("plant_integrator_residue_dropped", "rigor_gyro/kinds/periodic_orbit/plant_orbit.py",
     "            self.r0c = ball(Nc[0] / d0) if Nc.degree() >= 0 else arb(0)", "            self.r0c = arb(0)",
     "a pure integrator's term S r_0 theta / 2 left out of g"),
    ("plant_saltation_dropped", "rigor_gyro/kinds/periodic_orbit/plant_orbit.py",
     "            P[i, k] = -(E[i, k] - f1[i] * cE[k] / cf1)", "            P[i, k] = -E[i, k]",
     "a plant's multipliers without the switching-time correction"),
    ("plant_near_zero_tail_ignored", "rigor_gyro/kinds/periodic_orbit/plant_orbit.py",
     "    return certainly_positive(abs(ball(lead)) - S * ball(C) * arb(2) / 3 * (ball(L) / pi) ** (2 * j0) * geo)",
     "    return certainly_positive(abs(ball(lead)))",
     "(0, rho] called root-free from g's leading term alone, without the series' tail"),
    ("plant_imaginary_axis_unchecked", "rigor_gyro/kinds/periodic_orbit/plant_model.py",
     "    if _imaginary_axis_roots(p):", "    if False:",
     "a plant with an undamped mode accepted: g has poles on the real axis"),
    ("plant_repeated_eigenvalue_unchecked", "rigor_gyro/kinds/periodic_orbit/plant_model.py",
     "    if p.gcd(p.derivative()).degree() > 0:", "    if False:",
     "a plant with a repeated eigenvalue accepted (the residue form needs simple eigenvalues)"),
    ("plant_genuine_middle_unchecked", "rigor_gyro/kinds/periodic_orbit/plant_claims.py",
     "    if certainly_lt(lo, hi):\n        pos = certify_positive(phi, lo, hi, max_pieces=50000, record=middle)",
     "    if False:\n        pos = certify_positive(phi, lo, hi, max_pieces=50000, record=middle)",
     "a plant's root called genuine without c . x + h > 0 on the middle of (0, theta)"),
    ("plant_check_empty_trusted", "rigor_gyro/kinds/periodic_orbit/plant_check.py",
     '    if st == "empty" or _monotone_root_free(G, lo, hi):\n        return True\n    if depth >= SPLIT_DEPTH:',
     "    return True\n    if depth >= SPLIT_DEPTH:",
     "the plant checker takes a stored root-free piece on trust"),
    ("plant_check_spurious_witness_unchecked", "rigor_gyro/kinds/periodic_orbit/plant_check.py",
     "            ok = certainly_positive(t) and certainly_lt(t, theta) and certainly_negative(phi(t))",
     "            ok = certainly_positive(t) and certainly_lt(t, theta)",
     "the plant checker confirms a spurious root without c . x + h < 0 at its witness"),
    ("plant_check_tail_ignored", "rigor_gyro/kinds/periodic_orbit/plant_check.py",
     '            steps.append(("tail bound beyond T", d.tail_ok(T)))',
     '            steps.append(("tail bound beyond T", True))',
     "the plant checker confirms (T, oo) root-free without the tail bound"),
    ("plant_check_monotone_one_end", "rigor_gyro/kinds/periodic_orbit/plant_check.py",
     "    if s0 == 0 or _sign(b[0]) != s0:", "    if s0 == 0:",
     "the plant checker calls a monotone piece root-free without g's sign at its far end"),
    # issue 40: the validated Taylor integrator (core/validated_flow.py; group flow) and the lyapunov trajectory
    # claims (kinds/lyapunov/trajectories.py, trajectory_claims.py; group lyapunov_trajectories)
    ("flow_picard_containment_ignored", "rigor_gyro/core/validated_flow.py",
     "        if verified(Y, W, Zx, Zw):\n", "        if True:\n",
     "the a-priori enclosure over [0, h] accepted without the Picard test's containment"),
    ("flow_verified_accepts_anything", "rigor_gyro/core/validated_flow.py",
     "    return all(z.is_finite() and contains(y, z) for y, z in zip(Y, Zx)) and \\\n",
     "    return True or \\\n",
     "the Picard test's decision says 'contained' for any new enclosure"),
    ("flow_step_remainder_dropped", "rigor_gyro/core/validated_flow.py",
     "    hb = _q(h)\n    out = top\n", "    hb = _q(h)\n    out = 0 * top\n",
     "the step end without the Lagrange remainder h^(n+1) F_(n+1)(Y): the Taylor polynomial taken as the value"),
    ("flow_lohner_correction_dropped", "rigor_gyro/core/validated_flow.py",
     "    err = [Pc[i] - c2[i] + sum(((M[i][j] - B2[i][j]) * S.r0[j] for j in range(n)), arb(0)) for i in range(n)]\n",
     "    err = [Pc[i] - c2[i] for i in range(n)]\n",
     "the mean-value form keeps mid(J B) r0 and drops (J B - mid(J B)) r0: a box's image loses its corners"),
    ("traj_outside_region_possibly", "rigor_gyro/kinds/lyapunov/trajectories.py",
     "    return certainly_gt(x1 * x1 + x3 * x3, R * R) or certainly_gt(abs(x2), xs)\n",
     "    return not certainly_le(x1 * x1 + x3 * x3, R * R) or certainly_gt(abs(x2), xs)\n",
     "an enclosure that only possibly left region (17) counts as having left it"),
    ("traj_exit_start_unchecked", "rigor_gyro/kinds/lyapunov/trajectories.py",
     "    if not certainly_inside_region(box, R, xs):\n", "    if False:\n",
     "the exit of region (17) certified from a start that is not in the region"),
    ("traj_estimate_reach_ignored", "rigor_gyro/kinds/lyapunov/trajectories.py",
     "    return certainly_le(abs(x2), reach) and certainly_lt(g.V(x1, x2, x3), level)\n",
     "    return certainly_lt(g.V(x1, x2, x3), level)\n",
     "a box with V < c beyond the certified reach taken to be in the component of {V < c} around 0"),
    ("traj_estimate_level_possibly", "rigor_gyro/kinds/lyapunov/trajectories.py",
     "    return certainly_le(abs(x2), reach) and certainly_lt(g.V(x1, x2, x3), level)\n",
     "    return certainly_le(abs(x2), reach) and not certainly_le(level, g.V(x1, x2, x3))\n",
     "a box only possibly below the level taken to be inside the estimate"),
    ("traj_equilibrium_origin_counted", "rigor_gyro/kinds/lyapunov/trajectories.py",
     "    if x2_over_pi is None or Fraction(x1) != 0 or Fraction(x3) != 0 or x2_over_pi == 0:\n",
     "    if x2_over_pi is None or Fraction(x1) != 0 or Fraction(x3) != 0:\n",
     "the origin counted as an equilibrium other than 0: convergence to it refuted"),
    ("traj_check_point_unmatched", "rigor_gyro/kinds/lyapunov/trajectory_claims.py",
     "    if point[1].pi_power or tuple(p.rational for p in point) != stored:\n", "    if point[1].pi_power:\n",
     "the checker re-runs a stored integration from a point other than the scene's initial_point"),
    ("paving_gain_counts_overlapping", "rigor_gyro/kinds/lyapunov/attraction_paving.py",
     "    return sum((b.area() for b in boxes if b.status == \"enters\" and b.outside), Fraction(0))\n",
     "    return sum((b.area() for b in boxes if b.status == \"enters\"), Fraction(0))\n",
     "entering boxes that overlap the sublevel set's slice counted as area gained"),
    ("paving_outside_unchecked", "rigor_gyro/kinds/lyapunov/attraction_paving.py",
     "    if b.outside and not above_level(g, b.x1, b.x3, level):\n        return False\n",
     "    if False:\n        return False\n",
     "the checker takes a stored box's 'outside the sublevel slice' on trust"),
    ("paving_above_level_possibly", "rigor_gyro/kinds/lyapunov/attraction_paving.py",
     "    if certainly_gt(g.V(*balls), level):\n        return True\n",
     "    if not certainly_le(g.V(*balls), level):\n        return True\n",
     "a rectangle only possibly above the level taken to be disjoint from the sublevel set"),
    ("gimbal_lock_square_lower_end_high", "rigor_gyro/kinds/lyapunov/model.py",
     "    lo = arb(0) if x.contains(0) else a.lower()\n", "    lo = a.upper()\n",
     "near the gimbal lock, a square from the ball's ends starts at the larger end: gamma's enclosure misses values"),
    # issue 37: relay boxes of all six parameters on their similar box (similarity.py) and stable by the
    # Gershgorin discs (norm_stability.py, normed_orbit.py; group relay_box6)
    ("similar_box_a_lower_corner_wrong", "rigor_gyro/kinds/periodic_orbit/similarity.py",
     "    a = (H[0] ** 2 * tau[0] ** 2 / (A[1] * B[1]),", "    a = (H[0] ** 2 * tau[0] ** 2 / (A[0] * B[1]),",
     "the similar box's B' edge from a corner that is not the extreme of H^2 tau^2/(A B): members left out"),
    ("similar_box_s_ends_swapped", "rigor_gyro/kinds/periodic_orbit/similarity.py",
     "    s = (sigma[0] / tau[1], sigma[1] / tau[0])", "    s = (sigma[0] / tau[0], sigma[1] / tau[1])",
     "sigma/tau's range from the wrong corners: the similar box misses members"),
    ("similar_box_b_lower_corner_wrong", "rigor_gyro/kinds/periodic_orbit/similarity.py",
     "    b = (n[0] * tau[0] / A[1], n[1] * tau[1] / A[0])", "    b = (n[0] * tau[0] / A[0], n[1] * tau[1] / A[0])",
     "n tau/A's lower end from the wrong corner: the similar box misses members"),
    ("similar_point_n_without_tau", "rigor_gyro/kinds/periodic_orbit/similarity.py",
     "n=P.n * P.tau * Ac / (P.A * tc),", "n=P.n * Ac / P.A,",
     "the similar member's n' without the time scale: a different invariant n tau/A"),
    ("conjugacy_matrix_unchecked", "rigor_gyro/kinds/periodic_orbit/similarity.py",
     "    return lhs == N and c > 0 and", "    return c > 0 and",
     "the exact conjugacy check passes for points with other invariants"),
    ("gershgorin_radius_dropped", "rigor_gyro/kinds/periodic_orbit/norm_stability.py",
     "                R = R + abs(e) * s", "                R = R + 0 * s",
     "the spectral radius bounded by the largest diagonal entry alone (the discs' radii dropped)"),
    ("gershgorin_lower_end_without_isolation", "rigor_gyro/kinds/periodic_orbit/norm_stability.py",
     "            if j != i and not certainly_positive(abs(ci - K[j, j]) - ri - Rj):",
     "            if False:",
     "the largest modulus's lower end from a disc that overlaps others (it may hold no eigenvalue)"),
    ("normed_stable_possibly_below_1", "rigor_gyro/kinds/periodic_orbit/normed_orbit.py",
     "    if best is not None and certainly_lt(best, 1):", "    if best is not None and best.lower() < 1:",
     "stable over a box where the disc bound of the spectral radius only possibly stays below 1"),
]


def read_kills(path: Path = KILLS) -> dict[str, dict]:
    """The record of tools/mutant_kills.json (empty if the file is missing)."""
    return json.loads(path.read_text(encoding="utf-8")) if path.is_file() else {}


def write_kills(kills: dict[str, dict], path: Path = KILLS) -> None:
    """One mutant a line, in the record's own order (new names last), so that a run's diff is its changes."""
    lines = [f"  {json.dumps(name)}: {json.dumps(entry, ensure_ascii=False)}" for name, entry in kills.items()]
    path.write_text("{\n" + ",\n".join(lines) + "\n}\n", encoding="utf-8")


def killer_hints(path: Path = KILLS) -> dict[str, str]:
    """name -> the node id (or test file) that killed the mutant last time, from ``path``; only an order
    hint for tools/pytest_first.py (a stale one moves nothing), never an outcome."""
    return {name: e["killed_by"] for name, e in read_kills(path).items() if e.get("killed_by")}


def record_kills(rows: list[tuple[str, str, str, float]], group: str | None, targeted: bool,
                 path: Path = KILLS, today: str | None = None) -> dict[str, dict]:
    """Update ``path`` with the outcomes of ``rows`` (name, what, outcome, seconds), as ``--record`` says."""
    kills = read_kills(path)
    files = {name: file for name, file, *_ in MUTANTS}
    today = today or datetime.date.today().isoformat()
    for name, _what, outcome, _secs in rows:
        if outcome.startswith("killed by "):
            killed_by = outcome.removeprefix("killed by ").removesuffix(" (error)")
        elif outcome == "SURVIVED":
            killed_by = None
        else:                       # NOT APPLIED / NOT RUN: nothing was measured
            continue
        entry = kills.get(name)
        if entry is None:
            same_file = [e["group"] for n, e in kills.items() if files.get(n) == files.get(name)]
            entry = {"group": group or (max(set(same_file), key=same_file.count) if same_file else "ungrouped")}
        entry.update(killed_by=killed_by, run="targeted" if targeted else "whole", date=today)
        kills[name] = entry
    write_kills(kills, path)
    return kills


def run(names: list[str] | None, out: str | None, tests: list[str] | None = None, in_order: bool = False,
        record: bool = False, group: str | None = None, committed: bool = False) -> int:
    rows, survivors = [], []
    # one snapshot of the tree, taken now: edits made while the mutants run do not leak into them
    snapshot = Path(tempfile.mkdtemp(prefix="mutants-snapshot-"))
    # every file git tracks, as it is in the working tree (the tests also read README.md, tools/ and
    # proofs/: a snapshot of rigor_gyro/ and tests/ alone failed test_readme for every mutant)
    if committed:       # HEAD's tree (others' uncommitted edits in the work tree stay out)
        archive = subprocess.run(["git", "archive", "HEAD"], cwd=ROOT, capture_output=True, check=True).stdout
        subprocess.run(["tar", "-x", "-C", str(snapshot)], input=archive, check=True)
    else:
        tracked = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True).stdout
        for rel in filter(None, tracked.decode().split("\0")):
            src = ROOT / rel
            if src.is_file():
                (snapshot / rel).parent.mkdir(parents=True, exist_ok=True)
                shutil.copy2(src, snapshot / rel)
    # the unmutated snapshot must pass the same tests: a test that fails there (one that reads a file
    # the snapshot does not hold, say) would "kill" every mutant and the run would measure nothing
    env = dict(os.environ, PYTHONPATH=str(snapshot) + os.pathsep + str(snapshot / "tools"), HYPOTHESIS_PROFILE="ci")
    base = subprocess.run([*PYTEST, "-p", "pytest_first", *(tests or [])],
                          cwd=snapshot, env=env, capture_output=True, text=True)
    if base.returncode != 0:
        print("the unmutated snapshot fails its tests, so every kill would be void:\n" + base.stdout[-2000:])
        shutil.rmtree(snapshot, ignore_errors=True)
        return 4
    print("the unmutated snapshot passes its tests", flush=True)
    hints = {} if in_order else killer_hints()
    for name, path, old, new, what in MUTANTS:
        if names and name not in names:
            continue
        text = (snapshot / path).read_text()
        if text.count(old) != 1:
            rows.append((name, what, "NOT APPLIED (text not found once: update the mutant)", 0.0))
            survivors.append(name)
            continue
        with tempfile.TemporaryDirectory() as tmp:
            shutil.copytree(snapshot, tmp, dirs_exist_ok=True)
            (Path(tmp) / path).write_text(text.replace(old, new))
            env = dict(os.environ, PYTHONPATH=tmp + os.pathsep + str(Path(tmp) / "tools"), HYPOTHESIS_PROFILE="ci",
                       PYTEST_FIRST=hints.get(name, ""))
            t0 = time.time()
            r = subprocess.run([*PYTEST, "-p", "pytest_first", *(tests or [])], cwd=tmp,
                               env=env, capture_output=True, text=True)
            secs = time.time() - t0
        if r.returncode in (4, 5):      # pytest's usage error / no tests: the run is broken, nothing was tested
            rows.append((name, what, f"NOT RUN (pytest exit {r.returncode}: {r.stdout[-200:]!r})", secs))
            survivors.append(name)
            print(f"{name}: NOT RUN (pytest exit {r.returncode})", flush=True)
            continue
        killed = r.returncode != 0     # 1 a test failed, 2 a collection error, 3 an internal error
        # the first failing test, or the first erroring one (a fixture that raised: an internal check fired)
        failed = next((ln.split(" ", 1)[1].split(" - ")[0] + (" (error)" if ln.startswith("ERROR ") else "")
                       for ln in r.stdout.splitlines() if ln.startswith(("FAILED ", "ERROR "))), "")
        rows.append((name, what, f"killed by {failed}" if killed else "SURVIVED", secs))
        if not killed:
            survivors.append(name)
        print(f"{name}: {'killed' if killed else 'SURVIVED'} ({secs:.0f} s) {failed}", flush=True)
    shutil.rmtree(snapshot, ignore_errors=True)
    table = ["| mutant | what it breaks | outcome | seconds |", "|---|---|---|---|"]
    table += [f"| `{n}` | {w} | {o} | {s:.0f} |" for n, w, o, s in rows]
    killed = sum(1 for r in rows if r[2].startswith("killed"))
    table.append("")
    table.append(f"{killed} of {len(rows)} named soundness mutants killed by the default tests.")
    text = "\n".join(table)
    print(text)
    if out:
        Path(out).write_text(text + "\n")
    if record:
        record_kills(rows, group, targeted=bool(tests))
        print(f"recorded in {KILLS.relative_to(ROOT)}")
    return 1 if survivors else 0


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--only", nargs="*")
    ap.add_argument("--list", action="store_true")
    ap.add_argument("--out")
    ap.add_argument("--tests", nargs="*", help="run only these test files (a quick targeted run; the default "
                                                "is the README's whole test command)")
    ap.add_argument("--in-order", action="store_true", help="pytest's own order (not last time's killers first)")
    ap.add_argument("--record", action="store_true", help="write the outcomes into tools/mutant_kills.json")
    ap.add_argument("--group", help="with --record: the group of the mutants run (for names new to the file)")
    ap.add_argument("--committed", action="store_true", help="snapshot HEAD's tree, not the work tree (when others "
                    "are editing it: their half-done files stay out)")
    args = ap.parse_args()
    if args.list:
        for name, path, *_rest, what in MUTANTS:
            print(f"{name:36s} {path}: {what}")
        return 0
    return run(args.only, args.out, args.tests, args.in_order, args.record, args.group, args.committed)


if __name__ == "__main__":
    sys.exit(main())
