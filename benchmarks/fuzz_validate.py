"""Long fuzz of `make-lens validate` as a script (the mutations of tests/fuzz_specs.py): N cases from
hypothesis seed SEED, each outcome appended to OUT as one JSON line (valid / clean / anything else,
with the output and the start of the spec of anything else), so the counts can be read while it runs:

    PYTHONPATH=$PWD ANTENNA_CAD_MEEP_PYTHON=/usr/bin/false python benchmarks/fuzz_validate.py 1600 1 s1.jsonl

Measured (2 seeds × 1,600, load average ~35 on 2 cores): 3,200 cases, 136 valid, 3,062 clean
errors, 0 tracebacks / unclean / written, 2 over the 60 s alarm (wall clock on that load; the alarm now
counts CPU seconds, with ten times that of wall time for a blocked read).
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
