//! Named indices of refraction, as in Mitsuba 3.
//!
//! [`IOR_TABLE`] is Mitsuba's `ior.h` (Hecht, *Optics*; 0–20 °C, ≈589 nm), looked up
//! case-insensitively by [`lookup_ior`]. [`CONDUCTOR_PRESETS`] are the complex IORs
//! η + i·k of the conductor `material` presets as Mitsuba's RGB variants use them: the
//! measured spectra (`data/ior/<name>.{eta,k}.spd`, Palik/Luxpop data shipped with
//! Mitsuba) reduced to linear sRGB by `spectrum_list_to_srgb(…, bounded = false, d65 = false)`
//! after the `CIE_Y_NORMALIZATION` scaling of `ior_from_file`. The values were computed
//! with steradian-mitsuba's port of that routine; the gold entry reproduces the Au values
//! measured from Mitsuba to all printed digits. Only presets whose spectra were checked are
//! listed; other names are an error.

use crate::Spectrum;

/// Mitsuba's named dielectric IORs (dimensionless).
pub const IOR_TABLE: &[(&str, f32)] = &[
    ("vacuum", 1.0),
    ("helium", 1.000036),
    ("hydrogen", 1.000132),
    ("air", 1.000277),
    ("carbon dioxide", 1.00045),
    ("water", 1.3330),
    ("acetone", 1.36),
    ("ethanol", 1.361),
    ("carbon tetrachloride", 1.461),
    ("glycerol", 1.4729),
    ("benzene", 1.501),
    ("silicone oil", 1.52045),
    ("bromine", 1.661),
    ("water ice", 1.31),
    ("fused quartz", 1.458),
    ("pyrex", 1.470),
    ("acrylic glass", 1.49),
    ("polypropylene", 1.49),
    ("bk7", 1.5046),
    ("sodium chloride", 1.544),
    ("amber", 1.55),
    ("pet", 1.5750),
    ("diamond", 2.419),
];

/// The IOR called `name` (case-insensitive); the error lists the valid names.
pub fn lookup_ior(name: &str) -> Result<f32, String> {
    let lower = name.to_lowercase();
    IOR_TABLE.iter().find(|(n, _)| *n == lower).map(|&(_, v)| v).ok_or_else(|| {
        let names: Vec<&str> = IOR_TABLE.iter().map(|(n, _)| *n).collect();
        format!("unknown IOR name \"{name}\"; valid choices are: {}", names.join(", "))
    })
}

/// A conductor preset: name, η (real part) and k (imaginary part) per RGB channel.
pub struct ConductorPreset {
    pub name: &'static str,
    pub eta: [f32; 3],
    pub k: [f32; 3],
}

/// Conductor `material` presets (RGB-variant values). `none` is Mitsuba's default: η = 0,
/// k = 1, a 100 % reflecting mirror.
pub const CONDUCTOR_PRESETS: &[ConductorPreset] = &[
    ConductorPreset { name: "none", eta: [0.0, 0.0, 0.0], k: [1.0, 1.0, 1.0] },
    ConductorPreset {
        name: "Ag",
        eta: [0.155276, 0.116728, 0.138388],
        k: [4.82836, 3.12222, 2.14690],
    },
    ConductorPreset {
        name: "Al",
        eta: [1.65750, 0.880405, 0.521244],
        k: [9.22381, 6.26950, 4.83700],
    },
    ConductorPreset {
        name: "Au",
        eta: [0.143036, 0.375307, 1.44205],
        k: [3.98300, 2.38556, 1.60336],
    },
    ConductorPreset {
        name: "Cr",
        eta: [4.36967, 2.91651, 1.65490],
        k: [5.20655, 4.23131, 3.75470],
    },
    ConductorPreset {
        name: "Cu",
        eta: [0.201006, 0.923750, 1.10222],
        k: [3.91326, 2.45305, 2.14209],
    },
];

/// (η, k) of the conductor preset `name` (case-sensitive, like Mitsuba's file names).
pub fn conductor_preset(name: &str) -> Result<(Spectrum, Spectrum), String> {
    CONDUCTOR_PRESETS
        .iter()
        .find(|p| p.name == name)
        .map(|p| (Spectrum::from(p.eta), Spectrum::from(p.k)))
        .ok_or_else(|| {
            let names: Vec<&str> = CONDUCTOR_PRESETS.iter().map(|p| p.name).collect();
            format!(
                "unknown conductor material \"{name}\"; supported presets are: {}",
                names.join(", ")
            )
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lookups() {
        assert_eq!(lookup_ior("bk7").unwrap(), 1.5046);
        assert_eq!(lookup_ior("Air").unwrap(), 1.000277);
        assert_eq!(lookup_ior("water ice").unwrap(), 1.31);
        let e = lookup_ior("glass").unwrap_err();
        assert!(e.contains("bk7") && e.contains("diamond"), "{e}");
        let (eta, k) = conductor_preset("none").unwrap();
        assert_eq!((eta, k), (Spectrum::ZERO, Spectrum::ONE));
        let (eta, _) = conductor_preset("Au").unwrap();
        assert_eq!(eta, Spectrum::new(0.143036, 0.375307, 1.44205));
        let e = conductor_preset("Unobtainium").unwrap_err();
        assert!(e.contains("Cu") && e.contains("none"), "{e}");
    }
}
