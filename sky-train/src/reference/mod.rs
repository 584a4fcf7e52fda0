//! Independent f64 references of the models, written from the papers' text with no code from
//! sky-core: the measure of sky-core's accuracy, and of what its approximations cost. The
//! end-to-end tests (`tests/`) and `sky-train bench` use them.

pub mod aoas;
