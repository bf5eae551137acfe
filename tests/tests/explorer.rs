//! The explorer page in a real browser: headless Chromium, driven through
//! WebDriver, judged against the host's own render of the same raster code.

use std::path::PathBuf;
use std::sync::OnceLock;
use std::time::Duration;

use anyhow::{ensure, Context, Result};
use explorer_site::{write_page, PageServer};
use harness::browser::webdriver::Session;
use harness::browser::Browser;
use harness::compare_images;
use harness::picture::Image;
use harness::render::render;
use harness::sources::builtin_scene;
use harness::workspace;
use raster::{CoverageSink, MethodId, Point, SCREEN};
use serde_json::json;

/// The page, built once for all the tests of this binary.
fn page_dir() -> Result<PathBuf> {
    static PAGE: OnceLock<Result<PathBuf, String>> = OnceLock::new();
    PAGE.get_or_init(|| {
        let dir = workspace::target_dir().join("explorer-test");
        write_page(&dir, None, None).map(|()| dir).map_err(|error| format!("{error:#}"))
    })
    .clone()
    .map_err(anyhow::Error::msg)
}

/// A server for the page and a browser on it, at `fragment`, rendered.
struct Explorer {
    browser: Browser,
    server: PageServer,
}

impl Explorer {
    fn open(fragment: &str) -> Result<Self> {
        let server = PageServer::start(&page_dir()?)?;
        let browser = Browser::start()?;
        let explorer = Self { browser, server };
        explorer.go(fragment)?;
        Ok(explorer)
    }

    fn go(&self, fragment: &str) -> Result<()> {
        self.session().navigate(&format!("{}{fragment}", self.server.url()))?;
        self.browser.wait_for(
            "the page is ready",
            "return document.body.dataset.ready === '1';",
            Duration::from_secs(30),
        )
    }

    fn session(&self) -> &Session {
        self.browser.session()
    }

    fn text(&self, selector: &str) -> Result<String> {
        let value = self.session().execute(
            "const e = document.querySelector(arguments[0]); return e ? (e.value ?? e.textContent) : null;",
            vec![json!(selector)],
        )?;
        value.as_str().map(str::to_string).with_context(|| format!("no element `{selector}`"))
    }

    fn number(&self, selector: &str) -> Result<usize> {
        let text = self.text(selector)?;
        text.trim().parse().with_context(|| format!("`{selector}` holds `{text}`, not a count"))
    }

    /// Picks `value` in the select `#id` with a real click on its option
    /// (unless it is picked already: that click changes nothing).
    fn choose(&self, id: &str, value: &str) -> Result<()> {
        if self.text(&format!("#{id}"))? == value {
            return Ok(());
        }
        let renders = self.renders()?;
        self.session().click(&self.session().find(&format!("#{id} option[value=\"{value}\"]"))?)?;
        self.wait_for_render_after(renders)
    }

    fn renders(&self) -> Result<u64> {
        let value = self.session().execute("return Number(document.body.dataset.renders || 0);", vec![])?;
        value.as_u64().context("no render count")
    }

    fn wait_for_render_after(&self, renders: u64) -> Result<()> {
        let script = format!("return Number(document.body.dataset.renders || 0) > {renders};");
        self.browser.wait_for("a new render", &script, Duration::from_secs(20))
    }

    /// Pane `pane`'s canvas read back from the browser, as an RGB image.
    fn canvas(&self, pane: &str) -> Result<Image> {
        let value = self.session().execute(
            "const c = document.querySelector(`#pane-${arguments[0]} .picture`);
             return Array.from(c.getContext('2d').getImageData(0, 0, c.width, c.height).data);",
            vec![json!(pane)],
        )?;
        let bytes: Vec<u8> =
            value.as_array().context("no pixels")?.iter().map(|v| v.as_u64().unwrap_or(256) as u8).collect();
        ensure!(bytes.len() == 320 * 200 * 4, "the canvas has {} bytes, not 320x200 RGBA", bytes.len());
        let rgba = bytes.as_chunks::<4>().0;
        ensure!(rgba.iter().all(|&[_, _, _, alpha]| alpha == 255), "the canvas has transparent pixels");
        Image::rgb(320, 200, rgba.iter().map(|&[r, g, b, _]| [r, g, b]).collect())
    }

    /// Opens the scene file `text` through the page's text box and button.
    fn open_text(&self, text: &str) -> Result<()> {
        self.session().execute("document.getElementById('scene-text').value = arguments[0];", vec![json!(text)])?;
        let renders = self.renders()?;
        self.session().click(&self.session().find("#open-text")?)?;
        self.wait_for_render_after(renders)
    }
}

#[test]
fn abrash38_3_with_abrash_int_on_the_canvas_is_the_host_render() -> Result<()> {
    let explorer = Explorer::open("#scene=abrash40-2&a=exact")?;
    explorer.choose("scene", "abrash38-3")?;
    explorer.choose("method-a", "abrash_int")?;
    explorer.choose("view", "picture")?;
    let scene = builtin_scene("abrash38-3")?;
    compare_images("explorer-abrash38-3-abrash_int", &render(&scene, MethodId::AbrashInt), &explorer.canvas("a")?)?;
    // Side by side: the second pane is its own method's picture.
    explorer.choose("method-b", "pendleton")?;
    compare_images("explorer-abrash38-3-pendleton", &render(&scene, MethodId::Pendleton), &explorer.canvas("b")?)
}

/// The pixels `method` adds to and misses of `exact` on `polygon`, on the host.
fn host_counts(polygon: &raster::Polygon, method: MethodId) -> (usize, usize) {
    let mut drawn = CoverageSink::new(SCREEN);
    let _ = method.method().fill(polygon, &mut drawn);
    let mut wanted = CoverageSink::new(SCREEN);
    let _ = MethodId::Exact.method().fill(polygon, &mut wanted);
    let report = drawn.report(&wanted);
    (report.extras, report.gaps)
}

#[test]
fn dragging_a_vertex_gives_the_hosts_difference_counts_for_the_moved_polygon() -> Result<()> {
    // The last hexagon of Listing 38.3, vertex 0 at (205, 80); zoomed 4x
    // with (75, 50) at the viewport's corner, so a CSS pixel is 64 subpixels.
    let explorer = Explorer::open("#scene=abrash38-3&a=abrash_int&view=diff&poly=237&zoom=4&x=-300&y=-200")?;
    let before = explorer.text("#line")?;
    ensure!(before == "poly color=15 rule=evenodd 205,80 160,55 115,80 115,120 160,145 205,120", "{before}");
    let at = explorer.session().execute("return explorer.vertexOnScreen('a', 0);", vec![])?;
    let (x, y) = (at["x"].as_f64().context("x")?.round() as i64, at["y"].as_f64().context("y")?.round() as i64);
    let renders = explorer.renders()?;
    let (dx, dy) = (13, 7);
    explorer.session().perform_actions(json!([{
        "type": "pointer",
        "id": "mouse",
        "parameters": { "pointerType": "mouse" },
        "actions": [
            { "type": "pointerMove", "x": x, "y": y, "origin": "viewport" },
            { "type": "pointerDown", "button": 0 },
            { "type": "pointerMove", "x": x + 5, "y": y + 2, "origin": "viewport", "duration": 100 },
            { "type": "pointerMove", "x": x + dx, "y": y + dy, "origin": "viewport", "duration": 100 },
            { "type": "pointerUp", "button": 0 },
        ],
    }]))?;
    explorer.wait_for_render_after(renders)?;

    let line = explorer.text("#line")?;
    let moved = scenes::file::parse_poly(line.strip_prefix("poly").context("not a poly line")?)
        .map_err(|error| anyhow::anyhow!("{line}: {error}"))?;
    let expected_vertex = Point::new(205 * 256 + dx as i32 * 64, 80 * 256 + dy as i32 * 64);
    ensure!(moved.contours[0][0] == expected_vertex, "vertex 0 is at {:?}: {line}", moved.contours[0][0]);

    let (added, missed) = host_counts(&moved, MethodId::AbrashInt);
    ensure!(added + missed > 0, "the moved hexagon should show abrash_int's half-pixel offset");
    let page = (
        explorer.number("#pane-a [data-field=selected_added]")?,
        explorer.number("#pane-a [data-field=selected_missed]")?,
    );
    ensure!(page == (added, missed), "the page counts (added, missed) = {page:?}, the host {:?}", (added, missed));

    // The difference view paints exactly the counted pixels.
    let Some(colors) = (match explorer.canvas("a")?.pixels() {
        harness::picture::Pixels::Rgb(colors) => Some(colors.clone()),
        _ => None,
    }) else {
        anyhow::bail!("the canvas is not RGB")
    };
    let painted = |rgb: [u8; 3]| colors.iter().filter(|&&c| c == rgb).count();
    ensure!(painted(explorer::view::ADDED) == added, "{} pixels painted as added", painted(explorer::view::ADDED));
    ensure!(painted(explorer::view::MISSED) == missed, "{} pixels painted as missed", painted(explorer::view::MISSED));

    // The address carries the edit: loading it again shows the moved polygon.
    let address = explorer.session().execute("return location.href;", vec![])?;
    explorer.session().navigate("about:blank")?;
    explorer.session().navigate(address.as_str().context("no address")?)?;
    explorer.browser.wait_for(
        "the page is ready",
        "return document.body.dataset.ready === '1';",
        Duration::from_secs(30),
    )?;
    let reloaded = explorer.text("#line")?;
    ensure!(reloaded == line, "after reloading {address}: {reloaded}");
    Ok(())
}

/// Checks that the page still renders with `method`: picked through the
/// controls, a click on "fit" draws again, and the pane reports counts.
fn still_answers(explorer: &Explorer, method: &str) -> Result<()> {
    explorer.choose("method-a", method)?;
    let renders = explorer.renders()?;
    explorer.session().click(&explorer.session().find("#zoom-fit")?)?;
    explorer.wait_for_render_after(renders)?;
    explorer.number("#pane-a [data-field=scene_added]").map(drop)
}

#[test]
fn hostile_scene_files_get_a_message_and_the_page_keeps_answering() -> Result<()> {
    let explorer = Explorer::open("#scene=abrash38-3&a=exact")?;

    explorer.open_text("clear 1\npoly color=2 0,0 NaN,3 4,4\n")?;
    let message = explorer.text("#message")?;
    ensure!(message.contains("line 2: bad vertex `NaN`"), "{message}");
    ensure!(explorer.text("#poly-count")? == "238", "a refused file replaced the scene");
    still_answers(&explorer, "abrash_float")?;

    let limits = "poly color=4 -8388608,-8388608 8388607.99609375,-8388608 0,8388607.99609375\n\
                  poly color=9 rule=nonzero 8388607,100 -8388608,120 160,-8388608\n";
    explorer.open_text(limits)?;
    ensure!(explorer.text("#message")? == "Scene file opened.", "{}", explorer.text("#message")?);
    for method in MethodId::ALL {
        still_answers(&explorer, method.name())?;
    }

    let many: Vec<String> = (0..5000).map(|i| format!("{},{}", i % 320, (i * 7) % 200)).collect();
    explorer.open_text(&format!("poly color=3 {}\n", many.join(" ")))?;
    let message = explorer.text("#message")?;
    ensure!(message.contains("line 1: a polygon of 5000 vertices; the explorer takes at most 4096"), "{message}");
    still_answers(&explorer, "lamothe")
}

#[test]
fn a_hostile_address_gets_a_message_and_a_usable_page() -> Result<()> {
    let explorer = Explorer::open("#text=poly%20color%3D1%20nan%2C0%201%2C1%202%2C0&a=bogus&zoom=1e308&poly=-4")?;
    let message = explorer.text("#message")?;
    ensure!(message.contains("the scene in the address: line 1: bad vertex `nan`"), "{message}");
    ensure!(message.contains("unknown method `bogus`; the methods are abrash_float, "), "{message}");
    ensure!(explorer.text("#scene")? == "abrash38-3", "the default scene is not open");
    still_answers(&explorer, "wgt")
}

#[test]
fn lab_results_show_the_methods_figures_for_the_nearest_family() -> Result<()> {
    // Polygon 2 of Listing 38.3 is a triangle 30x20 px: the lab's
    // small_triangles family. The file has the fields the page reads, in
    // the shape xtask/lab/src/results.rs writes.
    let explorer = Explorer::open("#scene=abrash38-3&a=abrash_int&poly=2")?;
    let results = json!({
        "seed": 1, "quick": true,
        "families": [{ "name": "small_triangles", "group": "random", "description": "random triangles 10-50 px across",
                       "polygons": 60, "tilings": 0, "pixels": 20000 }],
        "contenders": [],
        "rows": [{ "name": "abrash_int", "kind": "method", "family": "small_triangles", "group": "random",
                   "polygons": 60, "pixels": 20000, "timed_polygons": 60, "ns_per_polygon": 321.5,
                   "ns_min": 300.2, "ns_max": 350.0,
                   "vs_exact": { "ratio": 1.5, "low": 1.404, "high": 1.6, "pairs": 7 },
                   "time_vs_memset": 4.25, "wrong_pixels": 500, "wrong_pixels_own": 0, "overdraw": 0,
                   "faulty_polygons": 40, "refusals": 0, "failures": 0 }],
        "sweeps": [],
    });
    let path = std::env::temp_dir().join(format!("explorer-results-{}.json", std::process::id()));
    std::fs::write(&path, results.to_string())?;
    let renders = explorer.renders()?;
    explorer.session().send_keys(&explorer.session().find("#results-file")?, &path.display().to_string())?;
    explorer.wait_for_render_after(renders)?;
    std::fs::remove_file(&path)?;
    let lab = explorer.text("#pane-a [data-field=lab]")?;
    for expected in [
        "Nearest lab family: small_triangles",
        "322 ns a polygon (300–350 over the repeats)",
        "1.50x exact's (95% interval 1.40–1.60)",
        "4.25x",
        "500 under our convention (2.50% of 20000)",
    ] {
        ensure!(lab.contains(expected), "`{expected}` not in: {lab}");
    }
    Ok(())
}

#[test]
fn a_click_selects_the_topmost_polygon_under_the_pointer() -> Result<()> {
    let explorer = Explorer::open("#scene=abrash38-3&a=exact&poly=0&zoom=2&x=0&y=0")?;
    let rect = explorer.session().execute(
        "const r = document.querySelector('#pane-a .overlay').getBoundingClientRect(); return [r.left, r.top];",
        vec![],
    )?;
    let corner = (rect[0].as_f64().context("left")?, rect[1].as_f64().context("top")?);
    // Pixel (x, y) covers 2x2 CSS px at zoom 2; click its middle, away
    // from the selected polygon's vertices (a press there grabs one).
    for ((x, y), polygon) in [((160, 100), "237"), ((319, 199), "1"), ((314, 3), "0")] {
        let at = |v: i32, origin: f64| (origin + f64::from(v) * 2.0 + 1.0).round() as i64;
        let renders = explorer.renders()?;
        explorer.session().perform_actions(json!([{
            "type": "pointer",
            "id": "mouse",
            "parameters": { "pointerType": "mouse" },
            "actions": [
                { "type": "pointerMove", "x": at(x, corner.0), "y": at(y, corner.1), "origin": "viewport" },
                { "type": "pointerDown", "button": 0 },
                { "type": "pointerUp", "button": 0 },
            ],
        }]))?;
        explorer.wait_for_render_after(renders)?;
        ensure!(explorer.text("#poly")? == polygon, "a click on pixel ({x}, {y}) selected {}", explorer.text("#poly")?);
    }
    Ok(())
}

/// `cargo xtask explore --scene FILE` (or `--svg FILE`) puts the scene
/// beside the page, which opens it when its address names no scene: the
/// canvas is the host render, in the scene's own palette.
#[test]
fn a_scene_given_to_explore_opens_in_its_own_palette() -> Result<()> {
    let text = "clear 0\npalette 20 63,32,0 10,20,63\n\
                poly color=20 20,20 300,20 300,180 20,180 | 80,60 80,140 240,140 240,60\n\
                poly color=21 rule=nonzero 160,30 60,170 260,170\n";
    let dir = workspace::target_dir().join("explorer-test-scene");
    write_page(&dir, None, Some(text))?;
    let server = PageServer::start(&dir)?;
    let browser = Browser::start()?;
    let explorer = Explorer { browser, server };
    explorer.go("#a=exact&view=picture")?;
    let scene = scenes::file::parse("given", text).map_err(|error| anyhow::anyhow!("{error}"))?;
    compare_images("explorer-given-scene-exact", &render(&scene, MethodId::Exact), &explorer.canvas("a")?)?;
    // The address now carries the scene, so the link opens it again.
    let fragment = explorer.session().execute("return location.hash;", vec![])?;
    ensure!(fragment.as_str().is_some_and(|hash| hash.contains("text=")), "the address is {fragment}");
    Ok(())
}
