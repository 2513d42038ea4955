"""A small two-grade Luneburg ring layup shared by the template tests."""

from antenna_cad.fabrication.rings import fabricate_rings, plan_rings
from antenna_cad.materials import Material


def two_grade_sphere(radius_mm: float, **plan_options):
    """(ring plan, fabrication with drawings) of a two-grade sphere of ``radius_mm`` in 100 mm sheets
    (``plan_options``: further :func:`plan_rings` arguments, e.g. a pedestal)."""
    R = radius_mm
    mats = [Material(f"g{k}", 2.0 - 0.2 * k, 1e-4, 100.0 - 10 * k) for k in range(2)]
    plan = plan_rings([0, 0.5 * R], [0.5 * R, R], mats, shape="sphere", height_mm=None, sheet_thickness_mm=100.0,
                      sizing="contain", kerf_mm=0.5, board_width_mm=600, board_length_mm=1200,
                      registration_hole_mm=6.0, **plan_options)
    return plan, fabricate_rings(plan, "t", drawings=True)
