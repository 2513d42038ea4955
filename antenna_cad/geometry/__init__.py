"""Solids (OCCT through OCP, :mod:`antenna_cad.geometry.kernel`): the only package that builds CAD shapes."""
