"""Hypothesis profile for the project's own tests: `ci` when $CI is set, else `default`.

`--hypothesis-profile NAME` (Hypothesis's pytest plugin) overrides this.
"""

import os

from hypothesis import settings

import properties.profiles  # noqa: F401  (registers the profiles)

settings.load_profile("ci" if os.environ.get("CI") else "default")
