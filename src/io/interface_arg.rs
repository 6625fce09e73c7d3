//! `FILE[#GROUP]` arguments.

use std::fmt;
use std::path::PathBuf;

use super::error::IoError;

/// One side of an interface on the command line: a mesh file and, optionally, the physical
/// group in it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InterfaceArg {
    /// The mesh file.
    pub path: PathBuf,
    /// The physical group (name or tag), if given.
    pub group: Option<String>,
}

impl fmt::Display for InterfaceArg {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.group {
            Some(g) => write!(f, "{}#{g}", self.path.display()),
            None => write!(f, "{}", self.path.display()),
        }
    }
}

/// Splits `FILE#GROUP` at its last `#`; a plain `FILE` selects the whole file. A file whose
/// own name contains `#` is taken whole when it exists.
///
/// ```
/// let a = mortar::io::parse_interface_arg("meshes/block.msh#contact top").unwrap();
/// assert_eq!(a.path, std::path::PathBuf::from("meshes/block.msh"));
/// assert_eq!(a.group.as_deref(), Some("contact top"));
/// assert_eq!(mortar::io::parse_interface_arg("a.msh").unwrap().group, None);
/// ```
///
/// # Errors
/// [`IoError::InvalidArgument`] for an empty file name or an empty group after `#`.
pub fn parse_interface_arg(arg: &str) -> Result<InterfaceArg, IoError> {
    let invalid = |reason: &str| IoError::InvalidArgument {
        arg: arg.to_string(),
        reason: reason.to_string(),
    };
    if arg.is_empty() {
        return Err(invalid("no file name"));
    }
    let whole = PathBuf::from(arg);
    let Some((file, group)) = arg.rsplit_once('#') else {
        return Ok(InterfaceArg {
            path: whole,
            group: None,
        });
    };
    if whole.is_file() {
        return Ok(InterfaceArg {
            path: whole,
            group: None,
        });
    }
    if file.is_empty() {
        return Err(invalid("no file name before '#'"));
    }
    if group.is_empty() {
        return Err(invalid(
            "no group name after '#' (write FILE#GROUP, or FILE alone for the whole file)",
        ));
    }
    Ok(InterfaceArg {
        path: PathBuf::from(file),
        group: Some(group.to_string()),
    })
}
