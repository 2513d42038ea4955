"""Scaling of the slot_array build with the guide count (not a unit test).

    python benchmarks/slot_array_scaling.py [--full]

Builds the Ka two-mirror recipe with 10, 20 and 40 guides (STL and templates off unless
``--full``) and prints seconds per stage and per slot; cost should stay linear in slot count.
"to STEP" is the issue's bar: synthesis, model, fabrication, verification and the STEP export,
after imports. The STL stage also holds the pipeline's validity check of every part.
"""

from __future__ import annotations

import json
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def main() -> None:
    t_import = time.perf_counter()
    import antenna_cad.geometry.kernel  # noqa: F401  (imports are not part of the measured build)

    from antenna_cad.pipeline import build
    from antenna_cad.spec import load_spec
    print(f"imports {time.perf_counter() - t_import:.1f} s")
    full = "--full" in sys.argv
    base = load_spec(ROOT / "recipes" / "ka-slot-array-two-mirror.yaml")
    stages = ["synthesize", "model", "fabricate", "verify", "step"] + (["stl", "templates"] if full else [])
    print(f"{'guides':>6} {'slots':>6} {'parts':>5} " + " ".join(f"{s:>10}" for s in stages)
          + f" {'to STEP':>8} {'total s':>8} {'ms/slot':>8}")
    for count in (10, 20, 40):
        outputs = base.outputs.model_copy(update={"stl": full, "templates": full})
        spec = base.model_copy(update={"array": base.array.model_copy(update={"count": count}),
                                       "outputs": outputs, "name": f"ka-scaling-{count}"})
        with tempfile.TemporaryDirectory() as tmp:
            result = build(spec, Path(tmp))
            parts = len(json.loads((result.out_dir / "manifest.json").read_text())["parts"])
        slots = int(result.figures["slot_count"])
        total = sum(result.seconds[s] for s in stages)
        to_step = sum(result.seconds[s] for s in stages[:5])
        print(f"{count:>6} {slots:>6} {parts:>5} " + " ".join(f"{result.seconds[s]:>10.2f}" for s in stages)
              + f" {to_step:>8.2f} {total:>8.2f} {1e3 * total / slots:>8.2f}")


if __name__ == "__main__":
    main()
