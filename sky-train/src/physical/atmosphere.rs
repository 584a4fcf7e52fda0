//! The parameters of a clear atmosphere, their defaults and their valid ranges, and Preetham's
//! turbidity as an aerosol optical depth.

use std::fmt;

use super::constituents::{
    self, Coefficients, DOBSON_UNIT, N_WAVELENGTHS, OZONE_CROSS_SECTION, wavelength_nm,
};

/// A clear atmosphere. Everything else (the planet, air's density profile, the ozone layer's
/// shape, the cross-sections) is fixed in [`constituents`].
///
/// The default is [`Preset::default`]'s. Every preset is a clear (cloudless) mid-latitude
/// continental atmosphere with these constituents:
/// - the aerosol of OPAC's "continental average" type at 80 % relative humidity (Hess, Koepke
///   & Schult 1998, "Optical Properties of Aerosols and Clouds: The Software Package OPAC",
///   BAMS 79, Table 4): single-scattering albedo 0.925 and asymmetry 0.703 at 550 nm;
///   Ångström exponent 1.3 (Ångström 1929's typical continental value, the one Preetham et
///   al. 1999 use); exponential profile with a 1.2 km scale height (Bruneton 2017's demo: the
///   boundary layer); the optical depth at 550 nm is the preset's;
/// - ozone column 300 DU (about the global mean total ozone; Bruneton 2017's default);
/// - Lambertian ground albedo 0.2 (grass and soil, broadband);
/// - air: the US Standard Atmosphere 1976, 360 ppm CO₂ (fixed, [`constituents`]), above the
///   ground at the site's elevation (0 m, sea level, unless given): a site at altitude z has
///   the standard's air and ozone above z, so its surface pressure is the standard's P(z) and
///   the Rayleigh optical depth and the air's share of every path scale with it (the
///   aerosol's profile starts at the ground; the planet's radius is unchanged, 0.04 % at
///   2.5 km).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Atmosphere {
    /// Aerosol optical depth at 550 nm (0 to 5).
    pub aod_550: f64,
    /// Ångström exponent α of τ_a(λ) = τ_550 (λ / 550 nm)^−α (0 to 3).
    pub angstrom: f64,
    /// Aerosol single-scattering albedo (0 to 1).
    pub aerosol_ssa: f64,
    /// Henyey-Greenstein asymmetry parameter of the aerosol (−0.95 to 0.95).
    pub aerosol_g: f64,
    /// Aerosol scale height, m (100 to 20,000).
    pub aerosol_scale_height_m: f64,
    /// Total ozone column, Dobson units (0 to 1000).
    pub ozone_du: f64,
    /// Lambertian ground albedo (0 to 1).
    pub ground_albedo: f64,
    /// The ground's elevation above sea level, m (−500 to 6,000): the air and ozone above it
    /// are the US Standard Atmosphere 1976's above that altitude ([`Self::air_density`]).
    pub site_elevation_m: f64,
}

impl Default for Atmosphere {
    fn default() -> Self {
        Preset::default().atmosphere()
    }
}

/// OPAC's continental-average aerosol optical depth at 550 nm (Hess, Koepke & Schult 1998,
/// Table 4): today's clean clear sky.
pub const CLEAN_AOD_550: f64 = 0.151;

/// The aerosol optical depth at 550 nm of the clear-sky record: the value that brings the
/// global horizontal illuminance closest to USNO Circular 171's curve (least squares of
/// ln(E / E_USNO) over sun elevations 0-90°, `sky-train fit-aod`, rounded to 0.01), every other
/// constituent at [`Atmosphere`]'s published values.
pub const RECORD_AOD_550: f64 = 0.38;

/// The named atmospheres of `--atmosphere`: the constituents of [`Atmosphere`]'s list, each
/// preset with its aerosol optical depth.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum Preset {
    /// The measured clear-sky record's (the default): τ₅₅₀ = 0.38 (`RECORD_AOD_550`), fitted
    /// to USNO Circular 171 (Brown 1952's cloudless but, by today's standards, turbid skies).
    #[default]
    Record,
    /// Today's clean clear continental sky: OPAC's continental average, τ₅₅₀ = 0.151
    /// (`CLEAN_AOD_550`).
    Clean,
}

impl Preset {
    /// The preset's atmosphere.
    #[must_use]
    pub fn atmosphere(self) -> Atmosphere {
        let aod_550 = match self {
            Self::Record => RECORD_AOD_550,
            Self::Clean => CLEAN_AOD_550,
        };
        Atmosphere {
            aod_550,
            angstrom: 1.3,
            aerosol_ssa: 0.925,
            aerosol_g: 0.703,
            aerosol_scale_height_m: 1200.0,
            ozone_du: 300.0,
            ground_albedo: 0.2,
            site_elevation_m: 0.0,
        }
    }
}

/// A parameter outside its range, named as the command line names it.
#[derive(Debug, Clone, PartialEq)]
pub struct AtmosphereError {
    /// The parameter's flag (`--aod`, `--ozone-du`, ...).
    pub flag: &'static str,
    /// The value given.
    pub value: f64,
    /// The valid range.
    pub range: (f64, f64),
}

impl fmt::Display for AtmosphereError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} {} is outside the valid range [{}, {}]",
            self.flag, self.value, self.range.0, self.range.1
        )
    }
}

impl std::error::Error for AtmosphereError {}

/// The site elevations an atmosphere takes, m: from below the Dead Sea's shore to the highest
/// inhabited sites; the US Standard Atmosphere's first layer holds throughout.
pub const SITE_ELEVATION_RANGE_M: (f64, f64) = (-500.0, 6000.0);

/// The turbidities [`Atmosphere::from_turbidity`] accepts (β ≥ 0 needs T ≥ 0.9952).
pub const TURBIDITY_RANGE: (f64, f64) = (1.0, 10.0);

impl Atmosphere {
    /// The valid range of each parameter, with its flag.
    pub const RANGES: [(&'static str, (f64, f64)); 8] = [
        ("--aod", (0.0, 5.0)),
        ("--angstrom", (0.0, 3.0)),
        ("--aerosol-ssa", (0.0, 1.0)),
        ("--aerosol-g", (-0.95, 0.95)),
        ("--aerosol-scale-height", (100.0, 20_000.0)),
        ("--ozone-du", (0.0, 1000.0)),
        ("--albedo", (0.0, 1.0)),
        ("--elevation", SITE_ELEVATION_RANGE_M),
    ];

    fn values(&self) -> [f64; 8] {
        [
            self.aod_550,
            self.angstrom,
            self.aerosol_ssa,
            self.aerosol_g,
            self.aerosol_scale_height_m,
            self.ozone_du,
            self.ground_albedo,
            self.site_elevation_m,
        ]
    }

    /// Checks every parameter against [`Self::RANGES`] (NaN is out of range).
    ///
    /// # Errors
    /// The first parameter out of its range.
    pub fn validate(&self) -> Result<(), AtmosphereError> {
        for ((flag, range), value) in Self::RANGES.into_iter().zip(self.values()) {
            if !(range.0..=range.1).contains(&value) {
                return Err(AtmosphereError { flag, value, range });
            }
        }
        Ok(())
    }

    /// The default atmosphere with the aerosol of Preetham's turbidity `t` ([`Self::with_turbidity`]).
    ///
    /// # Errors
    /// For `t` outside [`TURBIDITY_RANGE`].
    pub fn from_turbidity(t: f64) -> Result<Self, AtmosphereError> {
        Self::default().with_turbidity(t)
    }

    /// This atmosphere with the aerosol of Preetham's turbidity `t`: Preetham, Shirley &
    /// Smits 1999 (appendix) relate turbidity to Ångström's turbidity coefficient,
    /// β = 0.04608 T − 0.04586, with α = 1.3, so τ_a(λ) = β (λ / 1 µm)^−1.3 and
    /// τ_550 = β · 0.55^−1.3 (0.100 at T = 2, 0.200 at T = 3).
    ///
    /// # Errors
    /// For `t` outside [`TURBIDITY_RANGE`].
    pub fn with_turbidity(self, t: f64) -> Result<Self, AtmosphereError> {
        if !(TURBIDITY_RANGE.0..=TURBIDITY_RANGE.1).contains(&t) {
            return Err(AtmosphereError {
                flag: "--turbidity",
                value: t,
                range: TURBIDITY_RANGE,
            });
        }
        let beta = 0.04608 * t - 0.04586;
        Ok(Self {
            aod_550: beta * 0.55_f64.powf(-1.3),
            angstrom: 1.3,
            ..self
        })
    }

    /// Aerosol optical depth at `nm`.
    #[must_use]
    pub fn aerosol_optical_depth(&self, nm: f64) -> f64 {
        self.aod_550 * (nm / 550.0).powf(-self.angstrom)
    }

    /// Peak ozone number density, m⁻³, of the column spread over the layer's shape.
    #[must_use]
    pub fn ozone_peak_density(&self) -> f64 {
        self.ozone_du * DOBSON_UNIT / constituents::OZONE_SHAPE_INTEGRAL_M
    }

    /// Air molecule number density at `z_m` above the ground, m⁻³: the US Standard
    /// Atmosphere's at `z_m` + [`Self::site_elevation_m`].
    #[must_use]
    #[inline]
    pub fn air_density(&self, z_m: f64) -> f64 {
        constituents::air_number_density(z_m + self.site_elevation_m)
    }

    /// Ozone number density at `z_m` above the ground, m⁻³: the column's layer
    /// ([`constituents::ozone_shape`], 10-40 km above sea level) at `z_m` +
    /// [`Self::site_elevation_m`].
    #[must_use]
    #[inline]
    pub fn ozone_density(&self, z_m: f64) -> f64 {
        self.ozone_peak_density() * constituents::ozone_shape(z_m + self.site_elevation_m)
    }

    /// The surface pressure at the site, Pa: the US Standard Atmosphere 1976's at
    /// [`Self::site_elevation_m`] (101,325 Pa at sea level).
    #[must_use]
    pub fn surface_pressure_pa(&self) -> f64 {
        constituents::us76(self.site_elevation_m).1
    }

    /// The per-wavelength coefficients of this atmosphere's constituents.
    #[must_use]
    pub fn coefficients(&self) -> Coefficients {
        let ext: [f64; N_WAVELENGTHS] = std::array::from_fn(|i| {
            self.aerosol_optical_depth(wavelength_nm(i)) / self.aerosol_scale_height_m
        });
        Coefficients {
            rayleigh: constituents::rayleigh_cross_sections(),
            aerosol_extinction: ext,
            aerosol_scattering: ext.map(|e| e * self.aerosol_ssa),
            ozone: OZONE_CROSS_SECTION,
            rayleigh_phase: constituents::rayleigh_phases(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn turbidity_mapping() {
        let t2 = Atmosphere::from_turbidity(2.0).unwrap_or_default();
        let t3 = Atmosphere::from_turbidity(3.0).unwrap_or_default();
        assert!((t2.aod_550 - 0.1007).abs() < 1e-3, "{}", t2.aod_550);
        assert!((t3.aod_550 - 0.2009).abs() < 1e-3, "{}", t3.aod_550);
        assert!(Atmosphere::from_turbidity(0.5).is_err());
    }

    #[test]
    fn validation_names_the_flag() {
        let bad = Atmosphere {
            ozone_du: f64::NAN,
            ..Atmosphere::default()
        };
        assert_eq!(bad.validate().map_err(|e| e.flag), Err("--ozone-du"));
        assert!(Atmosphere::default().validate().is_ok());
    }

    #[test]
    fn presets_differ_in_the_optical_depth_only() {
        let (record, clean) = (Preset::Record.atmosphere(), Preset::Clean.atmosphere());
        assert_eq!(Atmosphere::default(), record);
        assert_eq!(
            Atmosphere {
                aod_550: clean.aod_550,
                ..record
            },
            clean
        );
        assert!(record.aod_550 > clean.aod_550);
        // Turbidity replaces the optical depth and keeps the preset's other constituents.
        let t = Atmosphere {
            ground_albedo: 0.5,
            ..clean
        }
        .with_turbidity(3.0)
        .unwrap_or_default();
        assert!((t.aod_550 - 0.2009).abs() < 1e-3 && t.ground_albedo == 0.5);
    }
}
