//! Field of view as Mitsuba's projective cameras specify it.

use crate::geometry::is_positive;
use crate::param::ParamError;
use std::fmt;

/// Which image axis a given `fov` applies to (`fov_axis`; default `x`, as in Mitsuba).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FovAxis {
    #[default]
    X,
    Y,
    Diagonal,
    Smaller,
    Larger,
}

impl FovAxis {
    pub fn parse(s: &str) -> Option<FovAxis> {
        Some(match s {
            "x" => FovAxis::X,
            "y" => FovAxis::Y,
            "diagonal" => FovAxis::Diagonal,
            "smaller" => FovAxis::Smaller,
            "larger" => FovAxis::Larger,
            _ => return None,
        })
    }
}

impl fmt::Display for FovAxis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            FovAxis::X => "x",
            FovAxis::Y => "y",
            FovAxis::Diagonal => "diagonal",
            FovAxis::Smaller => "smaller",
            FovAxis::Larger => "larger",
        })
    }
}

/// How the field of view was specified.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FieldOfView {
    /// `fov` in degrees along an axis.
    Angle { degrees: f32, axis: FovAxis },
    /// `focal_length` in mm of a 35 mm film equivalent (Mitsuba's default: 50 mm).
    FocalLength { mm: f32 },
}

impl FieldOfView {
    /// Default `focal_length` without `fov` (mm of a 35 mm film equivalent; Mitsuba's).
    pub const DEFAULT_FOCAL_LENGTH: f32 = 50.0;

    /// The horizontal field of view in radians for an image of `width`×`height` pixels.
    pub fn x_fov(&self, width: u32, height: u32) -> Result<f32, ParamError> {
        let aspect = width as f64 / height as f64;
        let diagonal_px = ((width as f64).powi(2) + (height as f64).powi(2)).sqrt();
        let (degrees, axis) = match *self {
            FieldOfView::Angle { degrees, axis } => (degrees as f64, axis),
            FieldOfView::FocalLength { mm } => {
                if !is_positive(mm) || !mm.is_finite() {
                    return Err(ParamError::new(
                        "focal_length",
                        format!("focal_length must be positive, got {mm} mm"),
                    ));
                }
                // diagonal field of view of a 36×24 mm frame
                let diag_35mm = (36.0f64 * 36.0 + 24.0 * 24.0).sqrt();
                ((diag_35mm / (2.0 * mm as f64)).atan().to_degrees() * 2.0, FovAxis::Diagonal)
            }
        };
        if !(degrees > 0.0 && degrees < 180.0) {
            return Err(ParamError::new(
                "fov",
                format!("fov must lie strictly between 0 and 180 degrees, got {degrees}"),
            ));
        }
        let axis = match axis {
            FovAxis::Smaller => {
                if aspect > 1.0 {
                    FovAxis::Y
                } else {
                    FovAxis::X
                }
            }
            FovAxis::Larger => {
                if aspect > 1.0 {
                    FovAxis::X
                } else {
                    FovAxis::Y
                }
            }
            a => a,
        };
        let t = (degrees.to_radians() / 2.0).tan();
        let tan_x = match axis {
            FovAxis::X => t,
            FovAxis::Y => t * aspect,
            FovAxis::Diagonal => t * width as f64 / diagonal_px,
            FovAxis::Smaller | FovAxis::Larger => unreachable!("resolved above"),
        };
        Ok((2.0 * tan_x.atan()) as f32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_focal_length_gives_mitsubas_fov() {
        // mitsuba-semantics.md item 8: 50 mm on a 768×576 film gives x_fov = 38.18°
        let fx = FieldOfView::FocalLength { mm: 50.0 }.x_fov(768, 576).unwrap();
        assert!((fx.to_degrees() - 38.18).abs() < 0.01, "{}", fx.to_degrees());
    }

    #[test]
    fn axis_conversions() {
        let y = FieldOfView::Angle { degrees: 30.0, axis: FovAxis::Y }.x_fov(200, 100).unwrap();
        assert!(((y / 2.0).tan() - 2.0 * (15f32.to_radians()).tan()).abs() < 1e-5);
        let s =
            FieldOfView::Angle { degrees: 30.0, axis: FovAxis::Smaller }.x_fov(200, 100).unwrap();
        assert_eq!(s, y);
        let l =
            FieldOfView::Angle { degrees: 30.0, axis: FovAxis::Larger }.x_fov(200, 100).unwrap();
        assert!((l.to_degrees() - 30.0).abs() < 1e-4);
        let sq =
            FieldOfView::Angle { degrees: 40.0, axis: FovAxis::Smaller }.x_fov(64, 64).unwrap();
        assert!((sq.to_degrees() - 40.0).abs() < 1e-4);
        assert!(FieldOfView::Angle { degrees: 180.0, axis: FovAxis::X }.x_fov(64, 64).is_err());
    }
}
