//! sky-core for browsers. For now this crate only proves that sky-core links into a wasm-ready
//! crate; the wasm-bindgen API and the demo page come with the sky-wasm issue.

#![no_std]

/// Linear sRGB of the Preetham sky towards (`view_zenith`, `view_azimuth`) for a sun at
/// (`sun_zenith`, `sun_azimuth`) and `turbidity`, all angles in radians, or `None` for invalid
/// parameters.
#[must_use]
pub fn preetham_rgb(
    sun_zenith: f32,
    sun_azimuth: f32,
    turbidity: f32,
    view_zenith: f32,
    view_azimuth: f32,
) -> Option<[f32; 3]> {
    let sun = sky_core::Sun::new(sun_zenith, sun_azimuth).ok()?;
    let sky = sky_core::PreethamSky::new(sun, turbidity).ok()?;
    Some(
        sky.rgb(sky_core::geom::direction(view_zenith, view_azimuth))
            .to_array(),
    )
}
