"""Hypothesis settings profiles: ``default`` (fast), ``ci`` (derandomized, more
examples) and ``thorough``.  Select one with pytest's ``--hypothesis-profile``,
``ddg-oracle check --profile``, or ``settings.load_profile(name)``.
"""

from __future__ import annotations

from hypothesis import HealthCheck, settings

PROFILES = ("default", "ci", "thorough")

# Mesh strategies build structure from a few small integers; building is not
# instant, so the too_slow and data_too_large checks only add noise.
_quiet = [HealthCheck.too_slow, HealthCheck.data_too_large]

settings.register_profile(
    "default", max_examples=25, deadline=None, suppress_health_check=_quiet)
settings.register_profile(
    "ci", max_examples=60, deadline=None, derandomize=True, database=None,
    suppress_health_check=_quiet, print_blob=True)
settings.register_profile(
    "thorough", max_examples=1000, deadline=None, suppress_health_check=_quiet)


def profile(name: str) -> settings:
    """The registered settings object of a profile, with a clear error for a typo."""
    if name not in PROFILES:
        raise ValueError(f"unknown Hypothesis profile {name!r}; choose one of {', '.join(PROFILES)}")
    return settings.get_profile(name)
