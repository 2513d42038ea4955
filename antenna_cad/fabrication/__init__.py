"""Fabrication: layup slicing, sheet outlines, kerf, nesting on boards, cut list and templates."""
