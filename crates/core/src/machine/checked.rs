//! How the second opinion reads the programs of a post: the post's family mapped to
//! `millpath-verify`'s reading rules (verify knows nothing of posts, the post crate nothing of
//! verify). A family verify has no reader for is refused where the post is chosen
//! (`load/settings.rs`), never written unchecked.

use millpath_post::{ArcMode, Family, Post};
use millpath_verify::Dialect as VerifyDialect;

/// verify's reading of one post's programs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Reading {
    /// The family's rules in verify.
    pub dialect: VerifyDialect,
    /// An error finding stops the write (every controller's program; the reference's are
    /// byte-identical to PathDxf2GCode's and only warned about).
    pub strict: bool,
    /// The post writes arcs as lines: an arc in its program is a finding.
    pub arcs_as_lines: bool,
}

/// A post whose family the checker cannot read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct NotRead {
    pub post: String,
    pub family: Family,
}

impl Reading {
    /// [`Reading::of`], the error naming the post.
    pub fn checked(dialect: super::Dialect, post: &Post) -> Result<Reading, NotRead> {
        Reading::of(dialect, post).map_err(|family| NotRead {
            post: post.name.clone(),
            family,
        })
    }

    /// The reading of the programs `post` writes in `dialect`; `Err(family)`: verify cannot
    /// read that family yet.
    pub fn of(dialect: super::Dialect, post: &Post) -> Result<Reading, Family> {
        let arcs_as_lines = post.format.arcs == ArcMode::Lines;
        let (dialect, strict) = match (dialect, post.family) {
            (super::Dialect::Reference, _) => (VerifyDialect::Reference, false),
            (_, Family::Rs274) => (VerifyDialect::LinuxCnc, true),
            (_, Family::Grbl) => (VerifyDialect::Grbl, true),
            (_, Family::Marlin) => (VerifyDialect::Marlin, true),
            (_, Family::Xcam) => (VerifyDialect::Xcam, true),
        };
        Ok(Reading {
            dialect,
            strict,
            arcs_as_lines,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn post(family: &str, arcs: &str) -> Post {
        let text = millpath_post::builtin::source("linuxcnc")
            .unwrap()
            .replace("family = \"rs274\"", &format!("family = \"{family}\""))
            .replace("name = \"linuxcnc\"", "name = \"mine\"")
            .replace("arcs = \"ij\"", &format!("arcs = \"{arcs}\""));
        millpath_post::load("mine.toml", &text).unwrap()
    }

    #[test]
    fn every_family_is_read() {
        use super::super::Dialect as Ours;
        for (family, read) in [
            ("rs274", VerifyDialect::LinuxCnc),
            ("grbl", VerifyDialect::Grbl),
            ("marlin", VerifyDialect::Marlin),
            ("xcam", VerifyDialect::Xcam),
        ] {
            let r = Reading::of(Ours::LinuxCnc, &post(family, "ij")).unwrap();
            assert_eq!((r.dialect, r.strict, r.arcs_as_lines), (read, true, false));
        }
        let r = Reading::of(Ours::Reference, &post("rs274", "lines")).unwrap();
        assert_eq!(
            (r.dialect, r.strict, r.arcs_as_lines),
            (VerifyDialect::Reference, false, true)
        );
    }
}
