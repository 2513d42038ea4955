"""Writers: STEP assembly, per-part meshes, manifest."""
