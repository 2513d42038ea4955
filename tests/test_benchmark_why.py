"""benchmarks/why.py: the reasons the benchmark prints beside a missed budget."""

import cProfile
import pstats
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import why  # noqa: E402


def _busy(n: int) -> float:
    return sum(i * 0.5 for i in range(n))


def _idle() -> int:
    return 1


def test_function_names_are_module_paths_or_builtin_methods():
    assert why.function_name(("/v/lib/python3.11/site-packages/build123d/topology/shape_core.py", 9, "is_valid")) \
        == "build123d.topology.shape_core.is_valid"
    assert why.function_name(("/repo/antenna_cad/export/mesh.py", 40, "_triangulate")) == "export.mesh._triangulate"
    assert why.function_name(("~", 0, "<built-in method math.sqrt>")) == "built-in method math.sqrt"


def test_hot_spots_rank_the_function_that_takes_the_time_first():
    profile = cProfile.Profile()
    profile.enable()
    _busy(300_000)
    _idle()
    profile.disable()
    first = why.hot_spots(pstats.Stats(profile), count=1)
    assert first.startswith(("tests.test_benchmark_why.<genexpr>", "built-in method builtins.sum")), first
    assert "_idle" not in why.hot_spots(pstats.Stats(profile), count=2)
    share = float(first.rsplit(" ", 2)[-2])
    assert 30 <= share <= 100


def test_a_stage_that_waits_for_a_forked_writer_says_so():
    assert "forked STEP writer" in why.stage_reason({}, "step")
    assert why.stage_reason({}, "report") == "not profiled"
    assert why.rss_mb() > 10
