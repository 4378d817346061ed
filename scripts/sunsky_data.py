#!/usr/bin/env python3
"""Writes crates/steradian/src/emitter/sunsky_rgb.bin, the tables of Mitsuba 3's `sunsky`
emitter that its RGB variants evaluate (the Hosek-Wilkie sky and sun model, 3-clause BSD,
Lukas Hosek and Alexander Wilkie 2012-2013: see sunsky_rgb.LICENSE beside it), from the
TensorFiles of the pip `mitsuba` package (data/sunsky/), Mitsuba 3.9.1's.

    pip install mitsuba numpy
    python3 scripts/sunsky_data.py

The file is four float32 arrays, little-endian, C order, one after the other (Mitsuba reads
the float64 tables into float32 too):

    sky_params  [10, 2, 6, 3, 9]   turbidity 1..10, albedo 0 and 1, Bezier control point of
                                   the sun elevation, channel R G B, Hosek-Wilkie parameter
    sky_radiance [10, 2, 6, 3]     the same, mean radiance
    sun_irradiance [10, 30, 3]     turbidity, sun elevation 2 + 3 i degrees, channel: the
                                   11-wavelength solar irradiance projected on Mitsuba's
                                   linear sRGB colour-matching functions, (1/11) sum CMF E
    sun_radiance [10, 45, 3, 4, 6] turbidity, elevation segment, channel, power of the
                                   elevation offset, power of cos psi (limb darkening baked in;
                                   `complex_sun`)
"""
import os
import struct
import sys

import numpy as np

# Mitsuba TensorFile dtype codes (Struct::Type) seen in these files
_TF_DTYPES = {10: '<f4', 11: '<f8'}

# Mitsuba's linear_rgb_rec(lambda) (ITU-R BT.709 linear RGB colour matching
# functions, float32) at the 11 model wavelengths 320, 360, ..., 720 nm.
# 320 nm lies outside Mitsuba's CIE range [360, 830] and evaluates to 0.
WAVELENGTHS = [320, 360, 400, 440, 480, 520, 560, 600, 640, 680, 720]
RGB_CMF_11 = np.array([
    # R
    [0.0, 0.00011275510769337416, 0.011936938390135765, 0.2222689986228943,
     -0.3090592324733734, -0.925361692905426, 0.39505624771118164,
     2.471696138381958, 1.1823992729187012, 0.12542563676834106,
     0.007785812020301819],
    # G
    [0.0, -9.337100345874205e-05, -0.010307585820555687, -0.22182385623455048,
     0.20188356935977936, 1.2738804817199707, 1.2905504703521729,
     0.15423989295959473, -0.10583049058914185, -0.013440251350402832,
     -0.0008460275130346417],
    # B
    [0.0, 0.0006472656968981028, 0.07245408743619919, 1.8618738651275635,
     0.8364972472190857, -0.05861509218811989, -0.1658165454864502,
     -0.06879597902297974, -0.010761640034615993, -0.0008660743478685617,
     -5.2291277825133875e-05],
], dtype=np.float32)


def read_tensor_file(path):
    """Parse a Mitsuba TensorFile: returns {name: ndarray}."""
    with open(path, 'rb') as f:
        b = f.read()
    if b[:12] != b'tensor_file\0':
        raise ValueError('%s: not a Mitsuba TensorFile' % path)
    version, count = struct.unpack_from('<HI', b, 12)
    if version != 1:
        raise ValueError('%s: unsupported TensorFile version %d' % (path, version))
    o = 18
    out = {}
    for _ in range(count):
        (name_len,) = struct.unpack_from('<H', b, o); o += 2
        name = b[o:o + name_len].decode('ascii'); o += name_len
        ndim, dtype, offset = struct.unpack_from('<HBQ', b, o); o += 11
        shape = struct.unpack_from('<%dQ' % ndim, b, o); o += 8 * ndim
        if dtype not in _TF_DTYPES:
            raise ValueError('%s: field %s has unknown dtype code %d'
                             % (path, name, dtype))
        n = int(np.prod(shape))
        arr = np.frombuffer(b, dtype=_TF_DTYPES[dtype], count=n, offset=offset)
        out[name] = arr.reshape(shape).copy()
    return out




def main():
    import mitsuba
    datadir = os.path.join(os.path.dirname(mitsuba.__file__), 'data', 'sunsky')
    sky = read_tensor_file(os.path.join(datadir, 'sunsky_datasets.bin'))
    sampling = read_tensor_file(os.path.join(datadir, 'sampling_data.bin'))
    sun_irradiance = np.einsum('cl,til->tic', RGB_CMF_11.astype(np.float64),
                               sampling['sun_irradiance'].astype(np.float64)) / 11.0
    arrays = [
        (sky['sky_params_rgb'], (10, 2, 6, 3, 9)),
        (sky['sky_rad_rgb'], (10, 2, 6, 3)),
        (sun_irradiance, (10, 30, 3)),
        (sky['sun_rad_rgb'], (10, 45, 3, 4, 6)),
    ]
    out = os.path.join(os.path.dirname(__file__), '..', 'crates', 'steradian', 'src', 'emitter',
                       'sunsky_rgb.bin')
    with open(out, 'wb') as f:
        for a, shape in arrays:
            assert a.shape == shape, (a.shape, shape)
            f.write(np.ascontiguousarray(a, dtype='<f4').tobytes())
    print(out, os.path.getsize(out), 'bytes')


if __name__ == '__main__':
    main()
