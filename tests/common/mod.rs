//! Shared helpers for the integration tests.
//!
//! Not every test uses every helper, hence the blanket `dead_code` allowance.
#![allow(dead_code)]

pub mod reference;
pub mod spectral;
