//! `cargo xtask render`: a scene drawn on the host.

use anyhow::Result;
use harness::render::render as render_scene;

use crate::opt::RenderOpt;

pub fn render(opt: &RenderOpt) -> Result<()> {
    let scene = opt.drawing.source()?.scene();
    let method = scene.method_or(opt.method);
    render_scene(&scene, method).write_png(&opt.out)?;
    println!("{}", opt.out.display());
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::opt::{parse_command, Action};
    use crate::source::svg_fixture;
    use scenes::palette::c6_to_8;

    /// `cargo xtask render --svg SVG ARGS --out OUT`.
    fn render_svg(svg: &str, args: &[&str], out: &Path) -> Result<()> {
        let svg = svg_fixture(svg);
        let head = ["--svg", svg.to_str().unwrap(), "--out", out.to_str().unwrap()];
        match parse_command("render", &[&head[..], args].concat())? {
            Action::Render(opt) => render(&opt),
            other => panic!("parsed as {other:?}"),
        }
    }

    /// A pixel, x and y, and its colour at 6 bits a channel.
    type Pixel = (u32, u32, [u8; 3]);

    /// Pixels of each drawing, worked out from its SVG (the import's
    /// tests tell how): the PNG holds each colour at 8 bits.
    const PIXELS: [(&str, &[Pixel]); 5] = [
        ("transforms.svg", &[(35, 20, [63, 0, 0]), (101, 21, [0; 3]), (120, 14, [0, 63, 0]), (255, 58, [0, 0, 63])]),
        ("holes.svg", &[(100, 30, [55, 40, 8]), (100, 70, [0; 3]), (215, 60, [8, 24, 47]), (240, 60, [0; 3])]),
        ("rules.svg", &[(80, 100, [0; 3]), (240, 100, [63, 63, 0]), (80, 40, [63, 63, 63])]),
        ("icon.svg", &[(150, 83, [13, 13, 13]), (150, 95, [59, 59, 59]), (185, 96, [47, 12, 12])]),
        ("strokes.svg", &[(36, 86, [0, 0, 63]), (65, 120, [0; 3]), (80, 144, [63, 63, 0]), (240, 144, [0; 3])]),
    ];

    #[test]
    fn svgs_are_rendered_to_pngs_in_their_own_colours() -> Result<()> {
        let dir = tempfile::tempdir()?;
        for (svg, pixels) in PIXELS {
            let out = dir.path().join(svg.replace(".svg", ".png"));
            render_svg(svg, &[], &out)?;
            let image = harness::Image::read_png(&out)?;
            for &(x, y, levels) in pixels {
                let colour = image.color((y * image.width() + x) as usize);
                assert_eq!(colour, levels.map(c6_to_8), "{svg}: pixel ({x}, {y})");
            }
        }
        Ok(())
    }

    #[test]
    fn a_bad_svg_is_refused_and_no_png_is_written() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out.png");
        for (svg, args, expected) in [
            ("bad/malformed.svg", &[][..], "not imported: malformed XML: expected 'rect' tag, not 'g' at 5:3"),
            ("bad/nan.svg", &[], "not imported: <path id=\"broken\"> at line 3: bad path data: "),
            ("bad/image.svg", &[], "not imported: <image id=\"photo\"> at line 4 cannot be imported"),
            ("bad/empty.svg", &[], "not imported: nothing to draw"),
            ("holes.svg", &["--view-box", "0,0,1e-9,1e-9"], "shape #ring reaches 4.000e11 pixels once fitted"),
        ] {
            let error = format!("{:#}", render_svg(svg, args, &out).unwrap_err());
            assert!(error.contains(expected), "{svg}: {error}");
            assert!(!out.exists(), "{svg}: {} was written", out.display());
        }
    }

    #[test]
    fn scene_and_svg_exclude_each_other_and_render_needs_one() {
        let both = parse_command("render", &["--scene", "abrash38-1", "--svg", "a.svg", "--out", "a.png"]);
        let error = both.unwrap_err().to_string();
        assert!(error.contains("the argument '--scene <NAME|FILE>' cannot be used with '--svg <FILE>'"), "{error}");
        let neither = parse_command("render", &["--out", "a.png"]).unwrap_err().to_string();
        assert!(neither.contains("the following required arguments were not provided"), "{neither}");
    }
}
