"""Hypothesis profile for the project's own tests: ``ddg-oracle-ci`` when $CI is set, else
``ddg-oracle-default``.

``--hypothesis-profile ddg-oracle-thorough`` (Hypothesis's pytest plugin) overrides this.
This is our own test suite's choice: the package itself never loads a profile.
"""

import os

from hypothesis import settings

from ddg_oracle.properties.profiles import PREFIX, register_profiles

register_profiles()
settings.load_profile(PREFIX + ("ci" if os.environ.get("CI") else "default"))
