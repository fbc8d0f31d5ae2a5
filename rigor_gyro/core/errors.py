"""The two kinds of failure, kept apart.

* :class:`ParameterError` / :class:`SceneError`: bad input. Raised at once, naming the parameter and
  the condition it breaks. The CLI maps them to exit status 2.
* :class:`CertificationFailed`: the input was fine but a claim could not be decided. Raised only by
  ``Certificate.require()``; the certificate itself records ``inconclusive`` with the reason and what
  to try (higher ``--maxprec``, finer subdivision).
"""
from __future__ import annotations

__all__ = ["RigorGyroError", "ParameterError", "SceneError", "CertificationFailed"]


class RigorGyroError(Exception):
    """Base class of every error rigor_gyro raises on purpose."""


class ParameterError(RigorGyroError, ValueError):
    """A parameter is missing, malformed or outside the model's domain."""


class SceneError(RigorGyroError, ValueError):
    """A scene file is unreadable, or names an unknown kind, claim or option."""


class CertificationFailed(RigorGyroError):
    """A certificate did not prove every claim; ``.certificate`` holds it."""

    def __init__(self, certificate, message: str):
        super().__init__(message)
        self.certificate = certificate
