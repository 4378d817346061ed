//! [`PixelQuantity`]: what each pixel of a render holds.

/// What each pixel holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PixelQuantity {
    /// What the sensor measures (radiance for cameras, the meter's quantity for meters).
    #[default]
    Sensor,
    /// The irradiance (W/m²) on the surface point each camera pixel sees, on the side facing
    /// the camera (0 where the ray escapes): an irradiance map.
    SurfaceIrradiance,
    /// The same as illuminance (lx): 683 lm/W × the luminance of the irradiance (see
    /// [`Image::to_illuminance`](crate::film::Image::to_illuminance)).
    SurfaceIlluminance,
}

impl PixelQuantity {
    /// The names the command line and Python take, in order: `radiance` (what the sensor
    /// measures), `irradiance`, `illuminance`.
    pub const NAMES: [&'static str; 3] = ["radiance", "irradiance", "illuminance"];

    /// The quantity of one of [`PixelQuantity::NAMES`].
    pub fn from_name(name: &str) -> Option<PixelQuantity> {
        match name {
            "radiance" => Some(PixelQuantity::Sensor),
            "irradiance" => Some(PixelQuantity::SurfaceIrradiance),
            "illuminance" => Some(PixelQuantity::SurfaceIlluminance),
            _ => None,
        }
    }

    /// True for the maps of what a camera sees (irradiance, illuminance).
    pub fn is_surface_map(self) -> bool {
        self != PixelQuantity::Sensor
    }
}
