"""Spec mutations for the fuzz tests: every recipe, with random values, wrong types (booleans,
strings, YAML 1.1 forms written unquoted: ``on``, ``4:00``, ``0x78``, ``'1e2'``), deleted and added
keys, and YAML oddities (alias bombs, deep nesting, non-UTF-8 bytes, duplicate
keys, tags, truncation). ``outcome`` runs ``make-lens validate`` (or ``build``) in-process and
classifies what happened; only "valid" and "clean" are allowed."""

from __future__ import annotations

import math
import os
import re
import signal
from collections import Counter
from pathlib import Path

import yaml
from hypothesis import HealthCheck, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from antenna_cad.cli import app

ROOT = Path(__file__).resolve().parents[1]
RECIPES = sorted((ROOT / "recipes").glob("*.yaml"))
EXAMPLES = int(os.environ.get("ANTENNA_FUZZ_EXAMPLES", "40"))        # long mode: e.g. 3000
BUILD_EXAMPLES = int(os.environ.get("ANTENNA_FUZZ_BUILD_EXAMPLES", "3"))
LONG = EXAMPLES > 40
TIMEOUT_S = 60                    # one validate's CPU seconds; a hang is an outcome of its own
TALLY: Counter = Counter()        # outcome → count, over the session (printed by the test's teardown)

FUZZ_SETTINGS = settings(max_examples=EXAMPLES, deadline=None, database=None, derandomize=not LONG,
                         suppress_health_check=list(HealthCheck), print_blob=True)

ODD_NUMBERS = [0, -0.0, -1, 5e-324, 1e-308, 1e-300, 1e-12, 1e-9, 1e-6, 1e6, 1e12, 1e300, 1.7976931348623157e308,
               2 ** 63, 10 ** 40, math.inf, -math.inf, math.nan]
SCALES = [1e-300, 1e-12, 1e-6, 1e-3, 0.01, 0.1, 0.5, 0.9, 1.1, 2, 10, 100, 1e4, 1e9, 1e300, -1]
numbers = st.one_of(st.sampled_from(ODD_NUMBERS), st.floats(allow_nan=True, allow_infinity=True),
                    st.integers(-10 ** 30, 10 ** 30))
leaves = st.one_of(numbers, st.text(max_size=20), st.booleans(), st.none(),
                   st.sampled_from(["auto", "sheet_layup", "solid", "shells", "xps", "ptfe", "dowels", "neck",
                                    "kinber", "nikulina", "cylinder", "sphere", "ladder", "classic", "machined_plates"]))
values = st.one_of(leaves, st.lists(leaves, max_size=6), st.dictionaries(st.text(max_size=8), leaves, max_size=3))
# a value's type changed as a hand-written YAML file would: written unquoted into the text
TYPE_TOKENS = ["on", "off", "yes", "no", "On", "TRUE", "false", "y", "4:00", "1:30:00", "190:20:30.15", "0x78",
               "0o17", "017", "0b101", "1_000", "'1e2'", '"12"', "'auto'", "1e2", "-1E-3", ".inf", "-.Inf", ".NaN",
               "~", "null", "''", "12 mm", "1,5", "[1]", "{a: 1}", "2001-12-14", "!!float '3'"]
RAW = "__raw_token_{}__"


def _paths(node, prefix=()):
    """Every key path of a nested mapping/list (inner nodes included)."""
    items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else ()
    for key, child in items:
        yield prefix + (key,)
        yield from _paths(child, prefix + (key,))


def _parent(data, path):
    for key in path[:-1]:
        data = data[key]
    return data


def _bomb(levels: int) -> str:
    rows = ["l0: &l0 [1, 1, 1, 1, 1, 1, 1, 1, 1]"]
    rows += [f"l{i}: &l{i} [{', '.join([f'*l{i - 1}'] * 9)}]" for i in range(1, levels)]
    return "\n".join(rows) + "\n"


@st.composite
def mutated_spec(draw) -> bytes:
    """A recipe with 1–3 data mutations, dumped to YAML, then perhaps a text-level oddity."""
    recipe = draw(st.sampled_from(RECIPES))
    data = yaml.safe_load(recipe.read_text(encoding="utf-8"))
    tokens = []
    for _ in range(draw(st.integers(1, 3))):
        paths = list(_paths(data))
        path = draw(st.sampled_from(paths))
        parent, key = _parent(data, path), path[-1]
        op = draw(st.sampled_from(["value", "value", "scale", "scale", "delete", "add", "wrap", "string",
                                   "type", "type"]))
        if op == "type":
            parent[key] = RAW.format(len(tokens))
            tokens.append(draw(st.sampled_from(TYPE_TOKENS)))
        elif op == "value":
            parent[key] = draw(values)
        elif op == "scale" and isinstance(parent[key], (int, float)) and not isinstance(parent[key], bool):
            parent[key] = parent[key] * draw(st.sampled_from(SCALES))
        elif op == "delete":
            del parent[key]
        elif op == "add" and isinstance(parent, dict):
            parent[draw(st.text(min_size=1, max_size=12))] = draw(values)
        elif op == "wrap":
            parent[key] = [parent[key]]
        elif op == "string":
            parent[key] = str(parent[key])
    text = yaml.safe_dump(data, sort_keys=False, allow_unicode=True)
    for i, token in enumerate(tokens):
        text = text.replace(RAW.format(i), token)
    odd = draw(st.sampled_from(["none"] * 6 + ["bomb", "deep", "duplicate", "bytes", "truncate", "tag", "long_list",
                                                "anchor_reuse", "tab", "bom", "huge", "cycle"]))
    if odd == "bomb":
        text += _bomb(draw(st.integers(3, 12)))
    elif odd == "deep":
        n = draw(st.integers(10, 3000))
        text += f"deep: {'[' * n}{']' * n}\n"
    elif odd == "duplicate":
        first = text.split(":", 1)[0]
        text += f"{first}: {draw(st.sampled_from(['x', '1', '[1]']))}\n"
    elif odd == "bytes":
        raw = text.encode()
        at = draw(st.integers(0, len(raw)))
        return raw[:at] + draw(st.binary(min_size=1, max_size=4)) + raw[at:]
    elif odd == "truncate":
        text = text[:draw(st.integers(0, len(text)))]
    elif odd == "tag":
        tag = draw(st.sampled_from(["!!binary aGVsbG8=", "!!timestamp 2001-12-14", "!!set {a, b}",
                                    "!!python/object/apply:os.system ['true']", "!!float nan", "!custom 1"]))
        text += f"extra: {tag}\n"
    elif odd == "long_list":
        text += f"grades: [{', '.join(['1.5'] * draw(st.integers(100, 30000)))}]\n"
    elif odd == "anchor_reuse":
        text = text.replace("\n", " &a\n", 1) if "\n" in text else text
        text += "again: *a\n"
    elif odd == "tab":
        text = text.replace("  ", "\t", 1)
    elif odd == "bom":
        return b"\xef\xbb\xbf" + text.encode()
    elif odd == "huge":
        text += "# " + "x" * 300_000 + "\n"
    elif odd == "cycle":
        text += "loop: &c [1, *c]\n"
    return text.encode("utf-8")


class Hang(BaseException):
    """Raised by the alarms: a case over its CPU time or ten times that of wall time (never caught by the
    code under test)."""


def _alarm(*_):
    raise Hang()


LINE = re.compile(r"^[^\s:][^\n]*?: \S")          # where (a field, "line N, column M", "file size"): what


def outcome(args: list[str], spec_path: Path, timeout_s: int = TIMEOUT_S) -> tuple[str, str]:
    """("valid" | "built" | "clean" | "traceback" | "unclean" | "hang", output) of ``make-lens ARGS``.
    clean: exit 2 and every line ``SPEC: field-or-line: rule``, nothing else (no warning either).
    hang: over ``timeout_s`` of this process's CPU time (work that does not end: a busy machine slows
    the wall clock, not the work) or over ten times that of wall time (a blocked read)."""
    previous = {sig: signal.signal(sig, _alarm) for sig in (signal.SIGALRM, signal.SIGPROF)}
    signal.setitimer(signal.ITIMER_PROF, timeout_s)
    signal.alarm(10 * timeout_s)
    try:
        result = CliRunner().invoke(app, args)
    except Hang:
        return "hang", ""
    finally:
        signal.alarm(0)
        signal.setitimer(signal.ITIMER_PROF, 0)
        for sig, handler in previous.items():
            signal.signal(sig, handler)
    out = result.output
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        return "traceback", f"{type(result.exception).__name__}: {result.exception}"
    if "Warning" in out or "Traceback" in out:
        return "unclean", out
    if result.exit_code in (0, 1):
        return ("valid" if args[0] == "validate" else "built"), out
    lines = [ln for ln in out.splitlines() if ln.strip()]
    prefix = f"{spec_path}: "
    if result.exit_code == 2 and lines and all(ln.startswith(prefix) and LINE.match(ln[len(prefix):]) for ln in lines):
        return "clean", out
    return "unclean", f"exit {result.exit_code}: {out}"
