"""Long fuzz of `make-lens validate` as a script (the mutations of tests/fuzz_specs.py): N cases from
hypothesis seed SEED, each outcome appended to OUT as one JSON line (valid / clean / anything else,
with the output and the start of the spec of anything else), so the counts can be read while it runs:

    PYTHONPATH=$PWD ANTENNA_CAD_MEEP_PYTHON=/usr/bin/false python benchmarks/fuzz_validate.py 1600 1 s1.jsonl

Measured 2026-11-27 (2 seeds × 1,600, load average ~5 on 2 cores, validate building the solid model):
3,200 cases, 176 valid, 3,024 clean errors, 0 tracebacks / unclean / hangs / written; the slowest case
12.3 CPU s. A hang is over 60 CPU seconds, or ten times that of wall time (a blocked read).
"""
import json
import resource
import sys
import tempfile
from pathlib import Path

from hypothesis import HealthCheck, given, seed, settings

from tests.fuzz_specs import mutated_spec, outcome

n, s, out = int(sys.argv[1]), int(sys.argv[2]), Path(sys.argv[3])


@seed(s)
@settings(max_examples=n, deadline=None, database=None, suppress_health_check=list(HealthCheck))
@given(mutated_spec())
def case(raw: bytes) -> None:
    with tempfile.TemporaryDirectory() as folder:
        spec = Path(folder) / "fuzz.yaml"
        spec.write_bytes(raw)
        cpu = resource.getrusage(resource.RUSAGE_SELF)
        kind, output = outcome(["validate", str(spec)], spec)
        after = resource.getrusage(resource.RUSAGE_SELF)
        cpu_s = after.ru_utime + after.ru_stime - cpu.ru_utime - cpu.ru_stime
        written = sorted(p.name for p in spec.parent.iterdir()) != ["fuzz.yaml"]
        with out.open("a") as fh:
            fh.write(json.dumps({"outcome": kind, "written": written, "cpu_s": round(cpu_s, 2),
                                 "output": output[-400:] if kind not in ("valid", "clean") else "",
                                 "spec": raw[:4000].decode("utf-8", "replace") if kind not in ("valid", "clean")
                                 else ""}) + "\n")


case()
