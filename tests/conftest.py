"""Hypothesis profile for the project's own tests: ``ddg-oracle-ci`` when $CI is set, else
``ddg-oracle-default``.

``--hypothesis-profile ddg-oracle-thorough`` (Hypothesis's pytest plugin) overrides this.
This is our own test suite's choice: the package itself never loads a profile.
"""

import atexit
import os
import shutil
import tempfile

from hypothesis import settings

from ddg_oracle.application.containment import start_workers_from_a_forkserver
from ddg_oracle.properties.profiles import PREFIX, register_profiles

# the counterexample folders `ddg-oracle check` makes for its failing checks (thousands per
# run: a full disk failed a CI run's install) in one folder, removed when the run ends;
# xdist workers and the commands the tests start inherit it
if "DDG_COUNTEREXAMPLES" not in os.environ:
    os.environ["DDG_COUNTEREXAMPLES"] = tempfile.mkdtemp(prefix="ddgc-")
    atexit.register(shutil.rmtree, os.environ["DDG_COUNTEREXAMPLES"], True)

# the suite's own processes (xdist workers, the scripts and commands its tests start) load
# no third-party Hypothesis plugin: trio's, installed with selenium for the browser tests,
# made `import hypothesis` cost 0.27-0.36 s of CPU instead of 0.12-0.19 s at every start
# of a process (docs/check.md; the ddg-oracle command skips them too)
os.environ.setdefault("HYPOTHESIS_NO_PLUGINS", "1")
# and start their workers (in-process runs, isolated libraries) as the command does, from a
# forkserver that imported the properties once; a user's process spawns them, which the
# tests that run pytest, Python or the wheel in a process of their own keep covering
start_workers_from_a_forkserver()

register_profiles()
settings.load_profile(PREFIX + ("ci" if os.environ.get("CI") else "default"))

# lagrange first: pymeshlab bundles an older libtbb, and once it is loaded in a process
# lagrange's module fails with an undefined symbol (tests/test_oracles_lagrange.py would
# then be skipped by importorskip, depending on which test file an xdist worker imported
# first).  ddg-oracle itself runs each library in a process of its own.
try:
    import lagrange  # noqa: F401
except ImportError:
    pass
