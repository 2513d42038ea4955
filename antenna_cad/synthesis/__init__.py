"""Pure physics (numpy/scipy only; never imports build123d/OCP). One module per seed system."""
