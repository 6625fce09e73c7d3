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

/// Splits `FILE#GROUP` at the first `#` after which the file part exists (so a group name
/// may contain `#` itself: `block.msh#top#2` selects the group `top#2` of `block.msh`), at
/// the last `#` when no such file exists (the reader then names the missing file); a plain
/// `FILE` selects the whole file. A file whose own name contains `#` is taken whole when it
/// exists.
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
    let Some(last) = arg.rsplit_once('#') else {
        return Ok(InterfaceArg {
            path: whole,
            group: None,
        });
    };
    let (file, group) = arg
        .match_indices('#')
        .map(|(i, _)| (&arg[..i], &arg[i + 1..]))
        .find(|(file, _)| std::path::Path::new(file).is_file())
        .unwrap_or(last);
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A group whose name contains `#` can be selected: the argument is split at the first
    /// `#` whose file part exists, not at the last `#`.
    #[test]
    fn a_group_name_may_contain_a_hash() {
        let dir = std::env::temp_dir().join(format!("mortar-hash-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("block.msh");
        std::fs::write(&file, "").unwrap();
        let arg = format!("{}#top#2", file.display());
        let a = parse_interface_arg(&arg).unwrap();
        assert_eq!(a.path, file);
        assert_eq!(a.group.as_deref(), Some("top#2"));
        // No such file: split at the last '#', the reader will name the missing file.
        let b = parse_interface_arg("nowhere.msh#a#b").unwrap();
        assert_eq!(b.path, PathBuf::from("nowhere.msh#a"));
        assert_eq!(b.group.as_deref(), Some("b"));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
