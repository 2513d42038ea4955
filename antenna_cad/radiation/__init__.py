"""Aperture field → far field, directivity, efficiencies, test zone and the seed's pattern-distortion
criterion. Pure numpy/scipy; inputs are plain arrays (positions in mm, complex fields),
so a GO, full-wave or measured aperture field goes in the same way."""
