//! # mortar-app
//!
//! The `mortar` command ([`cli`]): couple two Gmsh surfaces, run scene files and the built-in
//! scenes, with a progress bar ([`progress`]) and Ctrl-C ([`interrupt`]). Its work is the library's
//! (`mortar`) and the scenes' (`mortar-scenes`); a program of one's own with its own elements
//! and laws calls [`cli::main_with`].

pub mod cli;
pub mod interrupt;
pub mod progress;
