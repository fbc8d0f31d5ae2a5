"""The silent corrections: every place where the model reads Roitenberg (1947) otherwise than printed,
as an audit row (issue 39) with the printed form, the reading and why.

Each row has the status ``misprint`` and no value (class ``misprint-reading``: the report shows its
reading). Guarantee: none is a result; each says which evidence makes the reading necessary (a
derivative, the paper's own numbers, the dimension of a formula). Failure mode: none (text only);
rows are given only for the parts of the paper the scene prints.
"""
from __future__ import annotations

from typing import Any

from flint import fmpq

from ...core.outcome import AuditRow, AuditStatus

__all__ = ["silent_corrections", "SILENT_IDS"]

_ROWS = (
    ("reading: (7) the a17 S term of beta", "beta = ... + a16 D5 e^(-t/sigma) + a17 S",
     "beta = ... + a16 D5 e^(-t/sigma) + a17 S t",
     "beta' = ... + a17 S is its derivative, and the example's beta prints -0.45 t (a17 S = -3 x 0.15)"),
    ("reading: (16) the I-mode exponent", "(b116 I0 + b117) e^(-t/tau), likewise b216, b316, b416, and I = (I0 + b51) "
     "e^(-t/tau) + b52", "e^(-t/sigma)",
     "the I-mode of (2) decays with sigma (sigma I' + I = S sign beta), and b_G16 = a_G6, the -1/sigma mode's "
     "coefficients of (7)"),
    ("reading: the example's closed form, exponent", "beta = ... - 0.0868785 e^(-t/tau) ... (every row)",
     "e^(-t/sigma)", "(7) has e^(-t/sigma); 0.0868785 = a16 D5 and Table 2 reproduces only with 1/sigma = 7.61906"),
    ("reading: Table 1, second column c31..c35", "c31 = 0, c32 = 0, c33 = 0, c34 = eps4, c35 = -eps4 h54/sigma",
     "c51 .. c55", "the first column already defines c31..c35; these are the I row (x5 = I: I(theta) = (I0 + b51) "
                   "eps4 + b52), and Table 4 prints c51..c55 = 0, 0, 0, 0.348720, 0.590987"),
    ("reading: Table 1, h_G1 .. h_G3", "b_G1 beta'* + b_G2 Omega* + b_G3 I* + b_G4 I* + b_G5",
     "b_G1 beta'* + b_G2 Omega* + b_G3 i* + b_G4 I* + b_G5",
     "b_G3 multiplies i0 in (16); the printed h reproduce only with i* (the chain's h rows)"),
    ("reading: (24) second indices", "k_g2 = (c_{g+1,2} c15 - c_{g+1,6} c12)/c15, ... c_{g+1,7}, c_{g+1,8}",
     "k_gj = (c_{g+1,j} c15 - c_{g+1,5} c1j)/c15",
     "eliminating x5 from (21) with the first row: every k_gj uses c_{g+1,5}; c_{g+1,6..8} do not exist"),
    ("reading: the modulus label", "|lambda3| = |lambda4| = 0.589168", "|lambda2| = |lambda4|",
     "lambda3 = -0.000001048 is real; the complex pair is lambda2, lambda4 (sqrt(0.440829^2 + 0.390883^2) = 0.589168)"),
    ("reading: Table 4 label", "beta* 1.234394", "beta'*",
     "beta* = 0 on the switching surface; 1.234394 is beta'(0) (Table 2's t = 0 row)"),
)

#: the ids of the rows :func:`silent_corrections` can give (tests count them)
SILENT_IDS = tuple(r[0] for r in _ROWS) + ("reading: B",)


def silent_corrections(paper: dict[str, Any], P) -> list[AuditRow]:
    """The rows (module docstring); the B row only where the scene reads B = 2/15 for the printed 0.133."""
    if not paper.get("orbit") and not paper.get("table4"):
        return []
    out = [AuditRow(rid, printed, reading, None, AuditStatus.MISPRINT, why) for rid, printed, reading, why in _ROWS]
    if P.B == fmpq(2, 15):
        out.append(AuditRow("reading: B", "B = 0.133 kg m s^2", "B = 2/15 = 0.1333...", None, AuditStatus.MISPRINT,
                            "the printed cubic lambda^3 + 100 lambda^2 + 640 lambda + 60000 needs q^2 = H^2/(A B) = 600 "
                            "exactly; with B = 0.133, q^2 = 601.50... and the cubic's coefficients do not reproduce"))
    return out
