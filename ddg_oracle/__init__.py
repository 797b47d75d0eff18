"""ddg-oracle: an exact reference for discrete differential geometry, and the tools to
check an implementation against it.

Five layers, in the order data flows, each a folder of the repository:

- :mod:`ddg_oracle.reference` (``reference/``): exact definitions and theorems of
  Bobenko's notes (standard library only);
- :mod:`ddg_oracle.protocol` (``protocol/``): what a checked implementation provides;
- :mod:`ddg_oracle.properties` (``properties/``): Hypothesis strategies and one
  implementation-agnostic property per catalog ID (``check_implementation``);
- :mod:`ddg_oracle.oracles` (``oracles/``): adapters putting libraries and programs on
  the reference's conventions;
- :mod:`ddg_oracle.application` (``application/``): the ``ddg-oracle`` command, its job
  runner, isolation, reports, mesh files and the pytest plugin.

Importing this package imports nothing else and changes nothing.
"""

import os as _os

__version__ = "0.2.0"

# A checkout used without installing (``python -m ddg_oracle`` from its root, say): the
# layers are the folders beside this one, which an install maps to ddg_oracle.* (the
# package-dir table of pyproject.toml); here the package looks for them there too.
_root = _os.path.dirname(_os.path.dirname(_os.path.abspath(__file__)))
if _os.path.isfile(_os.path.join(_root, "pyproject.toml")) and all(
        _os.path.isfile(_os.path.join(_root, layer, "__init__.py"))
        for layer in ("reference", "protocol", "properties", "oracles", "application")):
    __path__.append(_root)
del _root
