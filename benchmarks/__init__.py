"""Benchmarks of the exact reference (issue 7): ``python -m benchmarks [GROUP ...] [--quick]``.

Groups: ``cotan`` (exact cotan weights and Laplacian, peers side by side),
``curvature`` (exact angle defects and the Gauss-Bonnet decision), ``flips``
(intrinsic flips to Delaunay on rational-metric surfaces), ``r3`` (flips on
rational surfaces in R^3, where square roots accumulate), ``hypothesis``
(examples per second of a reference-vs-libigl property), ``suite`` (test suite
and ``ddg-oracle check`` wall times; long, so only when named or with ``--all``).

Every timing is the median of several runs of one process's CPU time
(``time.process_time``, started after a full garbage collection: robust on a shared
machine; the benchmarked code is single-threaded), except ``suite``, which measures wall time of subprocesses.
Results go to ``docs/perf/results.json`` (merged by group, so one group can
be rerun alone); ``docs/performance.md`` and the plots ``docs/perf/*.png`` are
regenerated from it.  See ``docs/performance.md``.
"""
