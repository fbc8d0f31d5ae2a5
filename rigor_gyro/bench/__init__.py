"""Benchmarks: error against run time (``rigor-gyro bench``) and the stiff and extreme catalog
(``rigor-gyro bench --stress``).

This package *measures*; it never decides a verdict. It proves scenes with the prover at pinned
precisions (each proof is the same theorem the prover writes), times them, and compares the
uncertified float (numpy/scipy) and mpmath paths of each kind's ``approx`` module with the certified
values. It is float side: the rigorous modules never import it (tests/test_rules.py).

* :mod:`.workprecision`: one scene over a precision schedule: widths, bits lost, times, phases,
  pieces, and the float and mpmath paths' actual errors and times;
* :mod:`.stress`: the ``stress`` group of built-in scenes, run once each: the outcome, the precision
  that decided it, the time, and what the float path gets wrong;
* :mod:`.tables`: Markdown and JSON of both; :mod:`.plots`: the work-precision figures.
"""
