"""Fuzz of the spec reader and the pipeline (hypothesis; cases in tests/fuzz_specs.py).

Default: a bounded, derandomised run (ANTENNA_FUZZ_EXAMPLES=40 validate cases, seconds). Long mode:
``ANTENNA_FUZZ_EXAMPLES=3000 ANTENNA_FUZZ_BUILD_EXAMPLES=20 pytest -s -m slow tests/test_fuzz.py``
(random; the tally of outcomes is printed). Every outcome must be a valid spec / a build, or exit 2
with one line per problem naming its field (or the line of the YAML) — never a traceback, a
warning, a hang or another exit code.
"""

import contextlib
import json
import os
import tempfile
from pathlib import Path

import pytest
import yaml
from hypothesis import assume, given
from hypothesis import strategies as st

from tests.fuzz_specs import (BUILD_EXAMPLES, FUZZ_SETTINGS, LONG, RECIPES, SCALES, TALLY, _parent, _paths,
                               mutated_spec, outcome)

FAILURES: list[dict] = []       # long mode records every bad outcome and reports them all at the end


def _record(kind: str, allowed: tuple[str, ...], output: str, raw: bytes) -> None:
    TALLY[kind] += 1
    if kind not in allowed:
        FAILURES.append({"outcome": kind, "output": output[-2000:], "spec": raw[:2000].decode("utf-8", "replace")})
        assert LONG, f"{kind}: {output[-2000:]}\n--- spec ---\n{raw[:600]!r}"


@contextlib.contextmanager
def spec_file(raw: bytes):
    """``raw`` written as fuzz.yaml alone in a fresh temporary folder (removed afterwards)."""
    with tempfile.TemporaryDirectory() as folder:
        spec = Path(folder) / "fuzz.yaml"
        spec.write_bytes(raw)
        yield spec


@FUZZ_SETTINGS
@given(mutated_spec())
def test_validate_never_crashes(raw: bytes):
    with spec_file(raw) as spec:
        kind, output = outcome(["validate", str(spec)], spec)
        _record(kind, ("valid", "clean"), output, raw)
        assert sorted(p.name for p in spec.parent.iterdir()) == ["fuzz.yaml"]      # nothing written


@st.composite
def valid_candidate(draw) -> bytes:
    """A recipe with 1–2 numbers scaled by a modest factor or optional keys removed (often valid)."""
    recipe = draw(st.sampled_from(RECIPES))
    data = yaml.safe_load(recipe.read_text(encoding="utf-8"))
    for _ in range(draw(st.integers(1, 2))):
        numeric = [p for p in _paths(data) if isinstance(_parent(data, p)[p[-1]], float | int)
                   and not isinstance(_parent(data, p)[p[-1]], bool)]
        path = draw(st.sampled_from(numeric))
        _parent(data, path)[path[-1]] *= draw(st.sampled_from([s for s in SCALES if 0.05 <= abs(s) <= 20]))
    data["outputs"] = dict(data.get("outputs", {}), report=False)        # the report is tested elsewhere
    return yaml.safe_dump(data, sort_keys=False).encode()


@pytest.mark.slow
@FUZZ_SETTINGS.__class__(FUZZ_SETTINGS, max_examples=BUILD_EXAMPLES)
@given(valid_candidate())
def test_build_of_valid_specs_never_crashes(raw: bytes):
    with spec_file(raw) as spec:
        kind, _ = outcome(["validate", str(spec)], spec)
        assume(kind == "valid")
        kind, output = outcome(["build", str(spec), "-o", str(spec.parent / "out")], spec, timeout_s=900)
        _record(f"build {kind}", ("build built", "build clean"), output, raw)


def test_fuzz_outcomes_are_all_allowed():
    """Runs after the fuzz tests (file order): the tally (ANTENNA_FUZZ_REPORT=path.json keeps it) and,
    in long mode, every bad outcome at once."""
    print(f"\nfuzz tally: {dict(sorted(TALLY.items()))}")
    if os.environ.get("ANTENNA_FUZZ_REPORT"):
        Path(os.environ["ANTENNA_FUZZ_REPORT"]).write_text(json.dumps({"tally": TALLY, "failures": FAILURES}, indent=1))
    assert not FAILURES, json.dumps(FAILURES[:5], indent=1)
