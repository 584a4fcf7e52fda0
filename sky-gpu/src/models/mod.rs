//! One module per sky model: its shader's description and the packing of one sky's
//! parameters.

pub mod aoas;
pub mod daylight;
pub mod neural;
pub mod preetham;
pub mod sh;

use crate::ir::{Expr, float};

/// sky-core's one below-horizon rule (its crate docs, "Conventions"; `geom::below_horizon`)
/// for the unit view direction `d`: the condition `d.z >= -HORIZON_TOLERANCE` under which a
/// model's radiance is the sky's (0 elsewhere).
pub(crate) fn above_horizon(d: Expr) -> Expr {
    d.swizzle("z")
        .greater_equal(float(-sky_core::geom::HORIZON_TOLERANCE))
}
