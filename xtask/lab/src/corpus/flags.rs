//! The third-party family: country flags no one here drew, from Debian's
//! `iso-flags-svg` ([`install::lab_art`] says where they are), dedicated to
//! the public domain by their author. Each flag is imported by
//! `svg_import` exactly as a user's `--svg` file is (its default options:
//! curves and stroke outlines within 0.1 px, the 4:3 flag fitted to
//! 320x200 and centred); every fill and stroke of it is one polygon, with
//! its fill rule, in the flag's order, and the flags follow one another.

use std::path::Path;

use anyhow::{bail, Context, Result};
use install::{FLAGS_DIR, FLAGS_PACKAGE};

use super::family::{Family, Group};

/// The flags drawn, by their ISO 3166 code, in the order the corpus takes
/// them: each has a coat of arms or an emblem of many vertices (Bhutan's
/// dragon, Montenegro's and Serbia's eagles: outlines of over 1,000
/// vertices; Serbia's of up to 180 contours, Spain's 100).
pub const FLAGS: [&str; 12] = ["bt", "me", "rs", "es", "mp", "ad", "bm", "ky", "mx", "ec", "af", "do"];

/// The first `count` flags of [`FLAGS`] as the family `name`.
pub(super) fn flags(name: &'static str, description: &'static str, count: usize) -> Result<Family> {
    let polygons = flags_in(Path::new(FLAGS_DIR), &FLAGS[..count.min(FLAGS.len())])?;
    Ok(Family { name, group: Group::Real, description, polygons, tilings: vec![], sweep: None })
}

/// Every polygon of the flags `codes` in `dir`, imported.
fn flags_in(dir: &Path, codes: &[&str]) -> Result<Vec<raster::Polygon>> {
    let mut polygons = Vec::new();
    for code in codes {
        let path = dir.join(format!("{code}.svg"));
        if !path.is_file() {
            bail!(
                "{} is missing: the lab's flags come from Debian's {FLAGS_PACKAGE}, which `cargo xtask lab` installs",
                path.display()
            );
        }
        let imported = svg_import::import_file(&path, &svg_import::Options::default())
            .with_context(|| format!("the lab's flag {code} was not imported"))?;
        polygons.extend(imported.scene.polygons().cloned());
    }
    Ok(polygons)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Bhutan's flag: its dragon's outline has over 1,000 vertices, and
    /// several of its polygons have more than one contour.
    #[test]
    fn a_flag_gives_many_vertex_outlines() {
        let bhutan = flags_in(Path::new(FLAGS_DIR), &["bt"]).unwrap();
        assert!(bhutan.len() > 100, "{}", bhutan.len());
        assert!(bhutan.iter().any(|p| p.vertex_count() > 1000));
        assert!(bhutan.iter().any(|p| p.contours.len() > 1));
        let bhutan_and_montenegro = flags_in(Path::new(FLAGS_DIR), &["bt", "me"]).unwrap();
        assert_eq!(bhutan_and_montenegro[..bhutan.len()], bhutan[..]);
    }

    #[test]
    fn a_missing_flag_names_the_package() {
        let empty = tempfile::tempdir().unwrap();
        let error = flags_in(empty.path(), &["bt"]).unwrap_err().to_string();
        assert!(error.contains("bt.svg is missing") && error.contains(FLAGS_PACKAGE), "{error}");
    }
}
