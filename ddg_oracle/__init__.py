"""ddg-oracle: an exact reference for discrete differential geometry, and the tools to
check an implementation against it.

The package has four parts, in the order data flows:

- :mod:`ddg_oracle.reference`: exact definitions and theorems of Bobenko's notes
  (standard library only);
- :mod:`ddg_oracle.properties`: Hypothesis strategies and one implementation-agnostic
  property per catalog ID (``check_implementation``);
- :mod:`ddg_oracle.oracles`: adapters putting libraries on the reference's conventions;
- the application beside them here: the ``ddg-oracle`` command (:mod:`.cli`), its job
  runner, isolation, reports, mesh files and the pytest plugin.

Importing this package imports nothing else and changes nothing.
"""

__version__ = "0.2.0"
