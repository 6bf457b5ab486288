//! The command line: flags, their parsers, and the input files they name.

pub mod args;
pub mod inputs;
