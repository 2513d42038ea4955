"""CPU time of one sweep variant (``figures`` mode: the ``design`` and ``asbuilt`` tasks a worker runs),
for the shipped sweep recipes, in this process after a warm-up variant (imports and caches excluded).

    python benchmarks/sweep_cost.py [COUNT]      # COUNT variants per recipe, spread over the sweep (default 6)
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

from antenna_cad.sweep.model import load_sweep
from antenna_cad.sweep.tasks import run_part
from antenna_cad.sweep.variants import expand

ROOT = Path(__file__).resolve().parents[1]


def variant_cpu_s(spec: dict) -> float:
    """CPU seconds of one variant's two tasks (this process: a worker runs one task at a time; a
    variant that fails costs what it took to fail)."""
    start = time.process_time()
    for stage in ("design", "asbuilt"):
        run_part(stage, {"spec": spec})
    return time.process_time() - start


def main(count: int = 6) -> None:
    for path in sorted((ROOT / "recipes" / "sweeps").glob("*.yaml")):
        variants = [v for v in expand(load_sweep(path)) if v.key]
        variant_cpu_s(variants[0].spec)                               # warm-up: imports, caches
        picked = variants[:: max(1, len(variants) // count)][:count]
        costs = sorted(variant_cpu_s(v.spec) for v in picked)
        print(f"{path.name}: {len(variants)} variants, CPU s per variant over {len(costs)}: "
              f"min {costs[0]:.2f}, median {costs[len(costs) // 2]:.2f}, max {costs[-1]:.2f}; "
              f"whole sweep ≈ {sum(costs) / len(costs) * len(variants) / 60:.1f} CPU min")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 6)
