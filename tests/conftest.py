"""Test configuration: hypothesis profiles and a guard that every test leaves the precision as found.

Profiles (select with ``--hypothesis-profile=NAME`` or ``HYPOTHESIS_PROFILE=NAME``: the same thing in
every test file, which read example counts from the loaded profile; CI uses ``ci``, the default):

* ``ci``: derandomized, no deadline, bounded examples: the default test run stays short and
  reproducible on 2 cores.
* ``long``: many more examples, random seeds: a campaign, run by hand
  (``pytest --hypothesis-profile=long``).
"""
import os

import mpmath
import pytest
from flint import ctx
from hypothesis import HealthCheck, settings

settings.register_profile("ci", max_examples=40, derandomize=True, deadline=None, print_blob=True,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("long", max_examples=2000, deadline=None, print_blob=True,
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))


@pytest.fixture(autouse=True)
def _precision_is_restored():
    """Every test must leave flint's global precision and series cap as it found them. mpmath's working
    precision, which several reference computations set for their whole test (``mp.dps = 40``), is put
    back after each test, so that no test sees the digits another one chose."""
    before = ctx.prec, ctx.cap
    mp_prec = mpmath.mp.prec
    yield
    mpmath.mp.prec = mp_prec
    assert (ctx.prec, ctx.cap) == before, f"a test leaked ctx.prec, ctx.cap = {ctx.prec}, {ctx.cap} (was {before})"


@pytest.fixture(autouse=True)
def _reproductions_forgotten_around_patches(request):
    """The checker keeps its last re-proofs of a scene (rigor_gyro.reproduce): a test that patches the
    prover's code must neither see a re-proof made before its patch nor leave one made under it."""
    from rigor_gyro import reproduce
    patched = "monkeypatch" in request.fixturenames
    if patched:
        reproduce.forget()
    yield
    if patched:
        reproduce.forget()


def pytest_addoption(parser):
    parser.addoption("--runslow", action="store_true", default=False,
                     help="also run tests marked slow (long campaigns, stiff and extreme cases)")


def pytest_collection_modifyitems(config, items):
    """Tests marked ``slow`` run only with ``--runslow`` (or RIGOR_GYRO_SLOW=1): the default run stays short."""
    if config.getoption("--runslow") or os.environ.get("RIGOR_GYRO_SLOW") == "1":
        return
    skip = pytest.mark.skip(reason="slow: run with --runslow")
    for item in items:
        if "slow" in item.keywords:
            item.add_marker(skip)


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    """List the float findings the property tests collected (a float result outside its tolerance of
    the certified ball is a finding about floats, never a test failure: floats never decide)."""
    import sys
    for name, module in sorted(sys.modules.items()):
        findings = getattr(module, "FLOAT_FAILURES", None) if name.startswith(("tests.", "test_")) else None
        if findings:
            terminalreporter.write_line(f"{name}: {len(findings)} float finding(s), first: "
                                        f"{next(iter(findings.values()))}"[:300])
