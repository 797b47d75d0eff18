"""Properties: one per catalog row, named by its ID, runnable on any implementation.

A :class:`Property` couples a Hypothesis strategy of examples with a check
``check(impl, example)`` that raises :class:`PropertyFailure` naming the catalog
ID, the implementation, the (shrunk) mesh, the offending element and the
expected vs observed values.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import Any, Callable

from .profiles import example_time_limit
from .protocol import _epsilon, implementation_name, machine_epsilon


class PropertyFailure(AssertionError):
    """A property does not hold for an implementation on an example."""

    def __init__(self, property_id: str, impl, message: str, *, mesh=None,
                 element=None, expected=None, observed=None):
        self.property_id = property_id
        self.implementation = implementation_name(impl)
        self.message = message
        self.mesh = mesh                # (V, F) as nested lists, when there is one
        self.element = element
        self.expected = expected
        self.observed = observed
        super().__init__(str(self))

    def __str__(self) -> str:
        lines = [f"[{self.property_id}] {self.implementation}: {self.message}"]
        if self.element is not None:
            lines.append(f"  at: {self.element}")
        if self.expected is not None or self.observed is not None:
            lines.append(f"  expected: {self.expected!r}")
            lines.append(f"  observed: {self.observed!r}")
        if self.mesh is not None:
            V, F = self.mesh
            lines.append(f"  mesh: {len(V)} vertices, {len(F)} faces; F = {F}")
        return "\n".join(lines)


@dataclass(frozen=True)
class Property:
    id: str                      # catalog ID as in THEOREMS.md, e.g. "D1.6"
    name: str                    # python name of the check function
    statement: str               # what it checks, one line
    needs: frozenset[str]        # protocol methods the implementation must have
    strategy: Callable[[], Any]  # () -> hypothesis strategy of examples
    check: Callable[[Any, Any], None] = field(repr=False)

    def applies_to(self, caps: frozenset[str]) -> bool:
        return self.needs <= caps


PROPERTIES: dict[str, Property] = {}


def prop(catalog_id: str, statement: str, *, needs, strategy):
    """Register ``check(impl, example)`` as the property of ``catalog_id``."""
    def register(check):
        if catalog_id in PROPERTIES:
            raise ValueError(f"property {catalog_id} registered twice")

        @functools.wraps(check)
        def checked(impl, example):
            # tolerances inside the check read the implementation's own epsilon
            token = _epsilon.set(machine_epsilon(impl))
            try:
                with example_time_limit(f"[{catalog_id}] {implementation_name(impl)}"):
                    check(impl, example)
            finally:
                _epsilon.reset(token)

        PROPERTIES[catalog_id] = Property(
            catalog_id, check.__name__, statement, frozenset(needs), strategy, checked)
        check.property_id = catalog_id
        return check
    return register


#: Modules whose import registers properties, one per chapter topic.
PROPERTY_MODULES = ("topology", "curvature", "laplacian", "delaunay")


def all_properties() -> list[Property]:
    """Every registered property, in catalog order of registration."""
    import importlib
    for m in PROPERTY_MODULES:
        importlib.import_module(f"{__package__}.{m}")
    return list(PROPERTIES.values())
