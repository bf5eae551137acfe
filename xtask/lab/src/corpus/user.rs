//! The user's shapes (`lab --scene FILE`): the polygons of one scene,
//! measured in place of the corpus.
//!
//! Every `poly` of the scene is one polygon, kept as it is (its contours,
//! fill rule and colour); `clear` and `palette` lines draw no polygon and
//! are not measured. The polygons are split by their class
//! ([`raster::classify`]) into one family per class the scene holds, in
//! the scene's order within each: a partition, so every polygon is judged
//! and timed once, and totals over the families are the scene's. By class
//! because that is where the contenders part: a method or peer that takes
//! only some classes (one contour, triangles) declines the others, and its
//! time is then compared with `exact`'s on the same kind of polygon, not
//! on a mix it only partly drew.

use anyhow::{bail, Result};
use raster::{classify, Class, Polygon};
use scenes::Scene;

use super::family::{Family, Group};

/// How the report says the families were formed.
pub const FAMILIES_FORMED: &str = "Every polygon of the scene (each `poly` line; `clear` and `palette` lines \
     are not measured) is in one family, by its class (`raster::classify`): triangles, convex (one contour \
     monotone in y), simple (one contour whose edges do not cross), complex (self-intersecting, or several \
     contours) and degenerate (no area), one family for each class the scene holds, each in the scene's order. \
     A contender that takes only some classes (the integer peers one contour, embedded-graphics triangles) is \
     so compared with `exact` on polygons of the kind it draws.";

/// The classes in the order their families are listed, each with its
/// family's name and description.
const CLASSES: [(Class, &str, &str); 5] = [
    (Class::Triangle, "scene_triangles", "your scene's triangles"),
    (Class::Convex, "scene_convex", "your scene's polygons of one contour monotone in y (convex by Abrash's rule)"),
    (Class::Simple, "scene_simple", "your scene's polygons of one contour whose edges do not cross"),
    (Class::Complex, "scene_complex", "your scene's self-intersecting polygons and those of several contours"),
    (Class::Degenerate, "scene_degenerate", "your scene's polygons that enclose no area"),
];

/// The families of `scene`'s polygons, one per class it holds; an error
/// when it holds no polygon.
pub fn families(scene: &Scene) -> Result<Vec<Family>> {
    let polygons: Vec<&Polygon> = scene.polygons().collect();
    if polygons.is_empty() {
        bail!("scene `{}` has no polygon to measure (no `poly` line)", scene.name);
    }
    let classes: Vec<Class> = polygons.iter().map(|p| classify(p)).collect();
    Ok(CLASSES
        .iter()
        .map(|&(class, name, description)| Family {
            name,
            group: Group::UserScene,
            description,
            polygons: polygons.iter().zip(&classes).filter(|(_, c)| **c == class).map(|(p, _)| (*p).clone()).collect(),
            tilings: vec![],
            sweep: None,
        })
        .filter(|family| !family.polygons.is_empty())
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene(text: &str) -> Scene {
        scenes::file::parse("mine", text).unwrap()
    }

    /// A triangle, a square with a hole and a second triangle: two
    /// families, each polygon in one, in the scene's order.
    #[test]
    fn the_polygons_are_split_by_class_in_the_scenes_order() {
        let mine = scene(
            "clear 1\npoly color=2 0,0 10,0 5,8\npoly color=3 0,0 50,0 50,50 0,50 | 10,10 10,20 20,20 20,10\n\
             poly color=4 100,100 120,100 110,130\n",
        );
        let families = families(&mine).unwrap();
        let names: Vec<&str> = families.iter().map(|f| f.name).collect();
        assert_eq!(names, ["scene_triangles", "scene_complex"]);
        let colors: Vec<Vec<u8>> = families.iter().map(|f| f.polygons.iter().map(|p| p.color).collect()).collect();
        assert_eq!(colors, [vec![2, 4], vec![3]]);
        assert!(families.iter().all(|f| f.group == Group::UserScene && f.tilings.is_empty() && f.sweep.is_none()));
    }

    #[test]
    fn every_class_has_its_family() {
        let mine = scene(
            "poly color=1 0,0 10,0 5,8\npoly color=1 0,0 10,0 10,10 0,10\npoly color=1 0,0 30,0 30,30 15,10 0,30\n\
             poly color=1 0,0 10,10 10,0 0,10\npoly color=1 0,0 5,5 10,10\n",
        );
        let names: Vec<&str> = families(&mine).unwrap().iter().map(|f| f.name).collect();
        assert_eq!(names, CLASSES.map(|(_, name, _)| name));
    }

    #[test]
    fn a_scene_without_a_polygon_is_refused() {
        let error = families(&scene("clear 3\n# nothing else\n")).unwrap_err().to_string();
        assert!(error.contains("scene `mine` has no polygon"), "{error}");
    }
}
