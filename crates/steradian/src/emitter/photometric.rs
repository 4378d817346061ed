//! Photometric units, stated once.
//!
//! A lighting engineer gives light in photometric units: luminous intensity in candela
//! (cd = lm/sr), luminous flux in lumen (lm), luminance in cd/m² (lm/(m²·sr)), illuminance in
//! lux (lx = lm/m²). steradian turns each into the radiometric quantity of the same geometry
//! (W/sr, W, W/(m²·sr), W/m²) with the luminous efficacy [`LUMENS_PER_WATT`] applied to the
//! luminance Y of the linear Rec. 709 primaries (0.2126 R + 0.7152 G + 0.0722 B):
//!
//! > radiometric value (per channel) = photometric value × `color` / (683 lm/W × Y(`color`))
//!
//! so the light's luminous quantity is the number given whatever its `color` (default white),
//! and a white light has value/683 in each channel. Spectral assumption: steradian renders in
//! linear RGB, whose white (equal channels) is the equal-energy white; 683 lm/W is the
//! efficacy of the candela's definition (555 nm), so "1 W" here is the radiometric unit of an
//! RGB renderer in which Y = 1 means 683 lm, not a physical watt of a broadband spectrum. A
//! user who names an illuminant gives it as `color` (its RGB). Meters read back the same way:
//! illuminance = 683 × Y(irradiance) (`steradian measure --quantity illuminance`).
//!
//! Where each unit is accepted (each beside the plugin's radiometric parameter, never both):
//! `point` `luminous_intensity` (cd) or `luminous_flux` (lm, isotropic: I = Φ/4π), `spot`
//! `luminous_intensity` (cd on its axis), `area` and `constant` `luminance` (cd/m²),
//! `directional` `illuminance` (lx, on a plane facing the light), and `luminaire` (its file's
//! candela).

use super::LUMENS_PER_WATT;
use crate::spectrum::luminance;
use crate::Spectrum;

/// The radiometric value (per channel) of photometric `value` in light of colour `color`
/// (see the module documentation). Fails on a negative or non-finite value, and on a colour
/// with a negative channel or no luminance.
pub fn from_photometric(value: f32, color: Spectrum) -> Result<Spectrum, String> {
    if !(value.is_finite() && value >= 0.0) {
        return Err(format!("must be finite and non-negative, got {value}"));
    }
    let y = luminance(color);
    if !(color.is_finite() && color.min_element() >= 0.0 && y > 0.0) {
        return Err(format!(
            "its color must be non-negative with a positive luminance, got {color}"
        ));
    }
    Ok(color * (value / (LUMENS_PER_WATT * y)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn luminance_of_the_result_is_the_value_over_683() {
        for color in [Spectrum::ONE, Spectrum::new(1.0, 0.5, 0.2), Spectrum::new(0.0, 0.0, 3.0)] {
            let s = from_photometric(1000.0, color).unwrap();
            assert!((luminance(s) * LUMENS_PER_WATT / 1000.0 - 1.0).abs() < 1e-6, "{color}");
            // the colour's chromaticity is kept
            assert!((s / s.max_element() - color / color.max_element()).abs().max_element() < 1e-6);
        }
        assert_eq!(from_photometric(683.0, Spectrum::ONE).unwrap(), Spectrum::ONE);
        assert!(from_photometric(-1.0, Spectrum::ONE).is_err());
        assert!(from_photometric(f32::NAN, Spectrum::ONE).is_err());
        assert!(from_photometric(1.0, Spectrum::ZERO).is_err());
        assert!(from_photometric(1.0, Spectrum::new(1.0, -0.1, 1.0)).is_err());
    }
}
