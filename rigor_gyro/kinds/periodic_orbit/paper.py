"""Roitenberg (1947), the paper's side of the periodic-orbit kind: its forms in the paper's variables
(:mod:`.paper_model`), the audit of every number its example prints (:mod:`.paper_audit`: two
references per number, the exact value and the paper's own chain of :mod:`.paper_chain`), the silent
corrections (:mod:`.paper_silent`). This module gathers the names the kind uses.
"""
from __future__ import annotations

from .paper_audit import audit, g_from_printed_row
from .paper_audit import g_from_printed_row as _g_from_printed_row  # noqa: F401  (the name the tests know)
from .paper_model import (PAPER_SCHEMA, determinant_12, formula_table, orbit_quantities, paper_coefficients)

__all__ = ["PAPER_SCHEMA", "formula_table", "paper_coefficients", "orbit_quantities", "determinant_12", "audit",
           "g_from_printed_row"]
