"""The bundled recipes (YAML specs, data only): installed as the package ``antenna_cad.recipes``
(setup.py maps this folder); read them through :mod:`antenna_cad.catalog`."""
