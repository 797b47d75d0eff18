"""properties/draws.py and the runner's strategies: a strategy is built once, not at every
draw (Hypothesis validates each new strategy object over its whole tree the first time it
is drawn from: the cost of an example, paid again and again)."""

import pytest
from hypothesis import HealthCheck, Phase, given, settings, strategies as st
from hypothesis.strategies import SearchStrategy

from ddg_oracle.properties import PROPERTIES
from ddg_oracle.properties.draws import once, spread
from ddg_oracle.properties.example import Example
from ddg_oracle.properties.precision import inputs_at
from ddg_oracle.properties.runner import strategy_of

# the same examples twice: derandomized, generation only
TWICE = settings(max_examples=4, database=None, deadline=None, derandomize=True,
                 phases=[Phase.generate], suppress_health_check=list(HealthCheck))


def _validated(strategy) -> list:
    """The strategy objects drawn from (validated) while drawing TWICE's examples."""
    seen, validate = [], SearchStrategy.validate

    def record(self):
        seen.append(self)          # the objects themselves: an id is reused once freed
        return validate(self)

    @TWICE
    @given(strategy)
    def draw(example):
        pass

    SearchStrategy.validate = record
    try:
        draw()
    finally:
        SearchStrategy.validate = validate
    return seen


@pytest.mark.parametrize("pid", sorted(PROPERTIES))
def test_drawing_the_same_examples_again_builds_no_strategy(pid):
    s = strategy_of(PROPERTIES[pid])
    assert strategy_of(PROPERTIES[pid]) is s
    kept = _validated(s)               # alive: a freed object's id could come back
    first = {id(x) for x in kept}
    again = [x for x in _validated(s) if id(x) not in first]
    assert not again, f"{pid}: strategies built at every draw: {again[:3]}"


def test_a_strategy_built_in_every_draw_is_seen():
    """The test above can fail: a composite that builds its inner strategy in the draw."""
    @st.composite
    def fresh(draw):
        return draw(st.sampled_from([1, 2, 3]))

    @st.composite
    def kept(draw):
        return draw(spread([1, 2, 3]))

    for strategy, built in ((fresh(), True), (kept(), False)):
        alive = _validated(strategy)
        first = {id(x) for x in alive}
        assert bool([x for x in _validated(strategy) if id(x) not in first]) is built


def _meshes(x):
    """The Examples (what an implementation receives as arrays) inside a drawn value."""
    if isinstance(x, Example):
        yield x
    elif isinstance(x, (tuple, list)):
        for y in x:
            yield from _meshes(y)


def _float32_meshes(strategy) -> list:
    """The meshes (V, F) a float32 implementation receives from TWICE's examples."""
    drawn = []

    @TWICE
    @given(strategy)
    def collect(example):
        drawn.extend(repr(m.mesh) for m in _meshes(example) if m.mesh is not None)

    with inputs_at(2.0 ** -23):
        collect()
    return drawn


@pytest.mark.parametrize("pid", sorted(PROPERTIES))
def test_a_kept_strategy_draws_for_the_format_of_each_run(pid):
    """A verdict: one strategy object serves float64 and float32 implementations alike, so
    the input format must be read when drawing, never when building: a float32
    implementation given float64 coordinates would fail for the input's rounding.  The
    kept strategy, built and drawn at float64 first, gives a float32 run what a strategy
    built for that run gives."""
    s = strategy_of(PROPERTIES[pid])
    _validated(s)                                     # built and drawn at float64 first
    with inputs_at(2.0 ** -23):
        fresh = PROPERTIES[pid].strategy()
    assert _float32_meshes(s) == _float32_meshes(fresh)


def test_once_gives_one_object_per_arguments():
    @once
    def between(a, b):
        return st.integers(a, b).map(lambda k: 2 * k)

    assert between(0, 3) is between(0, 3) and between(0, 3) is not between(0, 4)

    @once
    def one_of_these(values):
        return st.sampled_from(values)

    # a list cannot be a key: a new strategy, drawing as the tuple's does
    assert one_of_these([1, 2]) is not one_of_these([1, 2])
    assert one_of_these((1, 2)) is one_of_these((1, 2))
    assert spread(range(3)) is spread((0, 1, 2))
