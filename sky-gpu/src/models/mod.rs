//! One module per sky model: its shader's description and the packing of one sky's
//! parameters.

pub mod aoas;
pub mod neural;
pub mod preetham;
pub mod sh;
