from antenna_cad.synthesis.checks import Check


def test_upper_check_statuses():
    assert Check.upper("x", 1.0, 2.0, "deg", "x", warn_margin=0.5).status == "pass"
    assert Check.upper("x", 1.8, 2.0, "deg", "x", warn_margin=0.5).status == "warn"
    assert Check.upper("x", 2.1, 2.0, "deg", "x", warn_margin=0.5).status == "fail"
