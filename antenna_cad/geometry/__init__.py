"""Solids (build123d/OCP): the only package that imports CAD libraries."""
