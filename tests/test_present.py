"""The shared presentation rules (report.html, report.pdf, the terminal): names, units, rounding to
the figure's resolution, statuses with ``skip`` apart, verdicts first."""

import pytest

from antenna_cad.export import present
from antenna_cad.synthesis.checks import Check


@pytest.mark.parametrize("key, value, shown", [
    ("ideal_on_axis_gain_loss_db", 2.76046e-26, "0 dB"),          # numerical noise below the resolution
    ("pattern_ideal_on_axis_beam_deg", 7.0396e-09, "0°"),
    ("pattern_ideal_on_axis_beam_deg", -0.004, "0°"),
    ("pattern_fabricated_edge_squint_deg", -7.6621, "−7.66°"),
    ("thickness_mm", 350.0, "350 mm"),                              # no trailing zeros on a figure
    ("lens_volume_mm3", 12345678.9, "12\u202f350\u202f000 mm³"),    # 4 significant digits, grouped
    ("mass_kg", 6.98123, "6.981 kg"),
    ("edge_efficiency_taper", 0.98234567, "0.9823"),                # no unit: 4 significant digits
    ("relative_volume_error", 2.51e-05, "2.5 × 10⁻⁵"),             # ... and small ratios keep them
    ("slot_count", 3200, "3\u202f200"),
    ("feed_is_horn", True, "yes"),
    ("fullwave_seconds", float("nan"), "—"),
])
def test_values_are_rounded_to_their_resolution_with_units(key, value, shown):
    assert present.figure_value(key, value) == shown


@pytest.mark.parametrize("key, name", [
    ("pattern_fabricated_edge_efficiency_taper", "Pattern fabricated edge efficiency taper"),
    ("fullwave_stepped_minus_ideal_p2p_deg", "Full-wave stepped minus ideal peak-to-peak"),
    ("grade_eps_r", "Grade εr"),
    ("eps_r", "εr"),
    ("thickness_mm", "Lens thickness"),
])
def test_keys_read_as_names(key, name):
    assert present.figure_name(key) == name


def test_column_headings_carry_units_and_cells_keep_the_column_resolution():
    assert present.column_label("width_mm") == "Width (mm)"
    assert present.column_label("P-p deg") == "P-p (°)"            # headings written with a space too
    assert present.cell_text("width_mm", 12.0) == "12.00"
    assert present.cell_text("width_mm", 1e-12) == "0"


def _check(status, name="c", message="m"):
    return Check(name, status, 1.0, 2.0, "deg", message)


def test_skip_is_its_own_status_and_never_passes_or_fails_the_build():
    assert present.overall([_check("pass"), _check("skip")]) == "pass"
    assert present.overall([_check("skip"), _check("warn")]) == "warn"
    assert present.STATUS_LABEL["skip"] == "skipped" and present.STATUS_COLOUR["skip"] != present.STATUS_COLOUR["pass"]
    order = [c.status for c in present.by_urgency([_check(s) for s in ("pass", "skip", "fail", "warn")])]
    assert order == ["fail", "warn", "skip", "pass"]


def test_verdicts_open_with_what_to_buy_then_the_questions_then_other_warnings():
    checks = [_check("pass", "unsanded_step_phase_error", "9.0° p-p vs budget 22.5°"),
              _check("skip", "full_wave", "full-wave stage skipped: Meep not found"),
              _check("warn", "edge_margin", "the antenna rim sees the lens edge diffraction"),
              _check("pass", "rim_incidence_vs_tir", "no total reflection")]
    verdicts = present.verdicts(checks, {"xps": 3, "plywood": 1}, {"xps": 1.7, "plywood box": 3.5})
    assert [(v.question, v.status) for v in verdicts] == [
        ("What to buy", "info"), ("Sanding", "pass"), ("Full-wave confirmation", "skip"), ("Edge margin", "warn")]
    assert verdicts[0].answer.startswith("1 × plywood; 3 × xps") and "5.2 kg of material" in verdicts[0].answer


def test_check_value_names_its_limit_in_its_unit():
    assert present.check_value(Check("c", "pass", 8.987, 22.5, "deg", "")) == "8.99° (limit 22.5°)"
    assert present.check_value(Check("c", "pass", 2e-15, 1e-6, "", "")) == "2 × 10⁻¹⁵ (limit 1 × 10⁻⁶)"
