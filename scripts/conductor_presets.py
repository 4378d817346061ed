#!/usr/bin/env python3
"""Prints the conductor `material` presets of Mitsuba 3's RGB variants as steradian's
`CONDUCTOR_PRESETS` table (crates/steradian/src/bsdf/ior.rs): η and k per linear sRGB channel,
read back from Mitsuba's own `conductor` plugin (which reduces its measured spectra to RGB and
clamps negative components to 0), so that the two renderers use the same numbers.

    pip install mitsuba && python3 scripts/conductor_presets.py > /tmp/presets.rs
"""
import mitsuba as mi

# Mitsuba 3's list of conductor spectra (its `material` parameter); names it refuses are skipped
NAMES = """a-C Ag Al AlAs AlAs_palik AlSb AlSb_palik Au Au_palik Be Be_palik Cr CsI CsI_palik Cu
Cu_palik Cu2O Cu2O_palik CuO CuO_palik d-C d-C_palik Hg Hg_palik HgTe HgTe_palik Ir Ir_palik K
K_palik Li Li_palik MgO MgO_palik Mo Mo_palik Na_palik Nb Nb_palik Ni_palik Rh Rh_palik Se
Se_palik SiC SiC_palik SnTe SnTe_palik Ta Ta_palik Te Te_palik ThF4 ThF4_palik TiC TiC_palik TiN
TiN_palik TiO2 TiO2_palik VC VC_palik V_palik VN VN_palik W W_palik""".split()

mi.set_variant("scalar_rgb")
mi.set_log_level(mi.LogLevel.Error)
print(f"// Mitsuba {mi.__version__} scalar_rgb")
print('    ConductorPreset { name: "none", eta: [0.0, 0.0, 0.0], k: [1.0, 1.0, 1.0] },')
for name in NAMES:
    try:
        params = mi.traverse(mi.load_dict({"type": "conductor", "material": name}))
    except Exception:
        continue
    eta, k = (list(params[key]) for key in ("eta.value", "k.value"))
    fmt = lambda v: "[" + ", ".join(repr(float(mi.Float(x))) for x in v) + "]"
    print(f'    ConductorPreset {{ name: "{name}", eta: {fmt(eta)}, k: {fmt(k)} }},')
