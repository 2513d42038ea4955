"""Toolpaths (DESIGN.md ``cam/``): hot-wire ruled surfaces (cones of taper-cut sheets, straight cuts),
drilling files for what a wire cannot reach, machine profiles and kerf tables, and the G-code
writer. Pure geometry (numpy/shapely), no CAD kernel."""
