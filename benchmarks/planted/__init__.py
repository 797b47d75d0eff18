"""The planted-bug benchmark's own implementation and its one-line variants (issue 40, item 5).

* :mod:`.numpy_all`: :class:`~.numpy_all.NumpyAll`, a correct plain numpy float64
  implementation of every protocol method, written in small steps (the hooks a variant
  replaces);
* :mod:`.variants`: one-line mistakes in it, each a subclass replacing one step (or one
  short method) with the line a developer actually writes, its ``planted`` methods, its
  ``bug_class`` (where the bug hides) and, when a real library had it, the finding ID of
  docs/findings.md.

``python -m benchmarks catch`` checks each variant with ``ddg-oracle check --impl
benchmarks.planted.variants:NAME`` on the properties that call its planted methods.
"""
