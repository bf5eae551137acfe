//! The scene group: the demo scenes' polygons.

use raster::Polygon;
use scenes::{builtin, Op};

use super::family::{Family, Group};

pub(super) fn demo_scenes() -> Family {
    let mut polygons: Vec<Polygon> = Vec::new();
    for page in &builtin::ALL {
        for op in page.scene().ops {
            // Pages are cumulative: keep each polygon once.
            if let Op::Fill(p) = op {
                if !polygons.contains(&p) {
                    polygons.push(p);
                }
            }
        }
    }
    Family {
        name: "demo_scenes",
        group: Group::Scene,
        description: "every polygon of the built-in scenes (Listing 38.3)",
        polygons,
        tilings: vec![],
        sweep: None,
    }
}
