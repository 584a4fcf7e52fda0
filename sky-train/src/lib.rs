//! The host side of the sky library: every sky model behind one [`sources::SkySource`] trait,
//! rendering to OpenEXR and PNG, sampling to CSV, and benchmarks. The `sky-train` binary is a
//! thin command-line front over this library.

pub mod bench;
pub mod cli;
pub mod dispatch;
pub mod eval;
pub mod export;
pub mod fuzz;
pub mod image_io;
pub mod render;
pub mod sources;
pub mod train;
