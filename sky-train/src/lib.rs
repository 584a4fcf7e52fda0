//! The host side of the sky library: every sky model behind one [`sources::SkySource`] trait,
//! rendering to OpenEXR and PNG, sampling to CSV, benchmarks, and independent f64 references
//! ([`reference`](mod@reference)). The `sky-train` binary is a thin command-line front over this library:
//! [`cli`] parses, [`commands`] has one module per subcommand, [`args`] the value parsers
//! they and the libraries share.

pub mod args;
pub mod bench;
pub mod captures;
pub mod cli;
pub mod commands;
pub mod controller;
pub mod csv_input;
pub mod csv_output;
pub mod daylight_planes;
pub mod daylight_sky;
pub mod daylight_tables;
pub mod dispatch;
pub mod eval;
pub mod export;
pub mod image_io;
pub mod output_path;
pub mod physical;
pub mod planckian;
pub mod plot;
pub mod reference;
pub mod render;
pub mod sampled_grid;
pub mod sh;
pub mod site;
pub mod sources;
pub mod study;
pub mod style_file;
pub mod train;
