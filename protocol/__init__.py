"""The implementation protocol: what a checked implementation may provide and how it is
called, the one thing properties, adapters and the application share.

- :mod:`.methods`: the protocol methods and their contracts (``METHODS``),
  ``OutsideDomain``, capabilities, declared precision and conventions;
- :mod:`.budget`: a task's wall-clock and crash budget, which every call respects;
- :mod:`.arrays`: the input arrays checked before a library sees them;
- :mod:`.answers`: the kind an answer must be of, checked before anything reads it;
- :mod:`.schema`: the JSON Schemas of the executable protocol (docs/protocol.md);
- :mod:`.processes`: how a process that ran an implementation ended.

It imports nothing of ours but the reference's errors and combinatorics: an isolated
library worker loads its adapter and this, not Hypothesis or the properties.
"""

from .methods import METHODS, OutsideDomain, capabilities

__all__ = ["METHODS", "OutsideDomain", "capabilities"]
