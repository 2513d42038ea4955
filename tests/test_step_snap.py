"""The STEP text clean-up (export/step.py): near-zero reals and −0. snapped to 0. line by line gives
the same text as the patterns over the whole file (the reproducibility fix, made fast)."""

import random

from antenna_cad.export import step

CASES = ["-0.", "a\n-1.E-20\n", "--1.5E-12,-0.,(-0.E-11)", "x-0.\n-0.5\n-0.E+00\n1.E-10",
         "", "\n\n-0.", "(0.,-2.E-300,1.E-9)\n", "#7=CARTESIAN_POINT('',(-3.E-30,1.2,-0.));\n"]


def _whole_text(text: str) -> str:
    return step._NEGATIVE_ZERO.sub("0.", step._TINY.sub("0.", text))


def test_snap_near_zero_on_known_lines():
    assert step.snap_near_zero("#7=CARTESIAN_POINT('',(-3.E-30,1.2,-0.));\n#8=X(1.E-9,-0.5);") \
        == "#7=CARTESIAN_POINT('',(0.,1.2,0.));\n#8=X(1.E-9,-0.5);"


def test_snap_near_zero_equals_the_patterns_over_the_whole_text():
    tokens = ["-0.", "0.", "-0.5", "1.E-20", "-2.5E-11", "3.E-9", "E-", "x", ",", "(", "\n", "-", ".", "7"]
    rng = random.Random(16)
    texts = CASES + ["".join(rng.choice(tokens) for _ in range(60)) for _ in range(2000)]
    for text in texts:
        assert step.snap_near_zero(text) == _whole_text(text), text
