//! Helpers shared by the statistical tests. Each test binary uses only part of them.
#![allow(dead_code)]

pub mod blocks;
pub mod bsdfs;
pub mod chi2;
pub mod lambert;
pub mod lights;
