"""Geometrical-optics ray tracing (numpy): Snell refraction, path lengths, aperture phase."""
