"""The exact reference wrapped as an implementation of the protocol.

Answers are exact (topology is integers); float views of exact values are
correctly rounded.  This is what every other implementation is compared with.
"""

from __future__ import annotations

from reference.combinatorics import Triangulation


class ReferenceImplementation:
    name = "reference"

    @staticmethod
    def _t(V, F) -> Triangulation:
        return Triangulation.from_faces(F, n_vertices=len(V))

    def euler_characteristic(self, V, F) -> int:
        return self._t(V, F).euler_characteristic()

    def boundary_loops(self, V, F) -> list[list[int]]:
        return self._t(V, F).boundary_loops()

    def is_orientable(self, V, F) -> bool:
        return self._t(V, F).is_orientable()

    def genus(self, V, F) -> int:
        return self._t(V, F).classify().genus
