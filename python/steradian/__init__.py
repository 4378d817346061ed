"""steradian: physically based rendering and light measurement of Mitsuba 3 scenes.

Scenes are Mitsuba 3 XML; images come back as float32 NumPy arrays of shape (H, W, 3) in
physical units (radiance in W/(m²·sr), irradiance in W/m²), the same values, bit for bit, as
the EXR the ``steradian render`` command writes for the same scene, spp and seed.

>>> import steradian
>>> scene = steradian.load_file("scenes/cornell-box.xml")
>>> image = scene.render(spp=16)          # (H, W, 3) float32, W/(m²·sr)
>>> steradian.write_exr("cornell.exr", image)

``steradian.radiometry`` holds the closed-form formulas (solid angles, irradiance);
``steradian.distributed`` renders on a Ray cluster (``pip install ray``), bit for bit the image
of ``Scene.render``.
"""

import sys as _sys

from ._steradian import (
    Measurement,
    RenderResult,
    Scene,
    SceneError,
    Sums,
    __version__,
    load_file,
    load_string,
    radiometry,
    read_exr,
    write_exr,
    write_png,
)

# `radiometry` is made by the extension module: register it so that
# `import steradian.radiometry` and `from steradian.radiometry import ...` work too.
_sys.modules[__name__ + ".radiometry"] = radiometry

__all__ = [
    "Measurement",
    "RenderResult",
    "Scene",
    "SceneError",
    "Sums",
    "__version__",
    "load_file",
    "load_string",
    "radiometry",
    "read_exr",
    "write_exr",
    "write_png",
]
