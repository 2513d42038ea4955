"""The verification stages shared by the kinds: the as-built trace of a lens of revolution
(:mod:`~antenna_cad.asbuilt.lens`), the lens handed to the full-wave stage
(:mod:`~antenna_cad.asbuilt.revolved`), the stock choice (:mod:`~antenna_cad.asbuilt.stock`), the
tolerance budget (:mod:`~antenna_cad.asbuilt.tolerance`), the quiet zone
(:mod:`~antenna_cad.asbuilt.quiet_zone`), the patterns (:mod:`~antenna_cad.asbuilt.patterns`,
:mod:`~antenna_cad.asbuilt.patterns_arrays`) and the taper-cut stack as GO sees it
(:mod:`~antenna_cad.asbuilt.taper`). The kind adapters (:mod:`antenna_cad.kinds`) call them; they call no
kind adapter, writer, CAD model or pipeline stage."""
