"""Printed graded-index lenses: one filament printed as a lattice whose local fill fraction sets the
effective permittivity. Pure numpy/scipy: lattice fill laws (:mod:`.lattice`) and the homogenization
that maps fill ↔ εr (:mod:`.homogenization`, tabulated from full-wave unit-cell runs by :mod:`.tabulate`).
"""
