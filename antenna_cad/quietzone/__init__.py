"""The quiet zone: a cylinder behind the lens scanned on several planes, as compact ranges specify it.

Numerics only (plain arrays in, figures out): the kind adapters hand it their aperture fields and
rays (:mod:`antenna_cad.asbuilt.patterns`)."""
