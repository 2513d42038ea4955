from pathlib import Path

import pytest

from antenna_cad.synthesis.checks import Check

ROOT = Path(__file__).resolve().parents[1]


def test_upper_check_statuses():
    assert Check.upper("x", 1.0, 2.0, "deg", "x", warn_margin=0.5).status == "pass"
    assert Check.upper("x", 1.8, 2.0, "deg", "x", warn_margin=0.5).status == "warn"
    assert Check.upper("x", 2.1, 2.0, "deg", "x", warn_margin=0.5).status == "fail"


@pytest.mark.parametrize("recipe", ["xps-collimator-0.5m", "bifocal-dielectric-160mm"])
def test_dissipative_loss_is_checked_for_every_lens_of_revolution(recipe):
    """seed-000 (1.3): a lossy material (tanδ 0.7 — a typing error) fails the lens; the recipe passes."""
    import yaml

    from antenna_cad.registry import synthesize
    from antenna_cad.spec import parse_spec
    data = yaml.safe_load((ROOT / "recipes" / f"{recipe}.yaml").read_text())
    status = {}
    for tan_delta in (None, 0.7):
        if tan_delta is not None:
            data["material"] = {"name": "lossy", "eps_r": 2.56 if "bifocal" in recipe else 1.047,
                                "tan_delta": tan_delta, "density_kg_m3": 30}
        _, checks = synthesize(parse_spec(data))
        status[tan_delta] = {c.name: c for c in checks}["dissipative_loss"]
    assert status[None].status == "pass" and status[None].value < 0.1
    assert status[0.7].status == "fail" and status[0.7].value > 3.0
