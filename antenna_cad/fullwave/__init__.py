"""Full-wave check of lenses of revolution: MIT Meep in cylindrical coordinates run in a
subprocess (:mod:`.runner`, :mod:`.solver`), decks from the CAD's profiles (:mod:`.deck`, :mod:`.lens`),
aperture statistics (:mod:`.aperture`), the fast sub-wavelength model (:mod:`.fastmodel`), the stage and
its phase model (:mod:`.verify`), the multilayer-sphere reference (:mod:`.mie`). Imports no CAD library."""
