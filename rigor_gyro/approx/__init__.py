"""Float and high-precision *non-rigorous* cross-checks: ``approx_*`` functions.

Nothing here decides a verdict. These modules import numpy, scipy and mpmath; the rigorous modules
never import them (a test checks that proving a scene imports neither numpy nor scipy).
"""
