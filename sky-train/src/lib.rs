//! The host side of the sky library: every sky model behind one [`sources::SkySource`] trait,
//! rendering to OpenEXR and PNG, sampling to CSV, and benchmarks. The `sky-train` binary is a
//! thin command-line front over this library.

pub mod bench;
pub mod cli;
pub mod dispatch;
pub mod image_io;
pub mod plot;
pub mod render;
pub mod sh;
pub mod sources;
