//! `lab --scene FILE`, the binary as `cargo xtask lab` runs it: a small
//! scene's report names every contender and the families it was split
//! into, and its summary.json is the report's table of the closest peers; a bad scene is refused, naming its line, and nothing is written.

use std::path::Path;
use std::process::{Command, Output};

use lab::Bound;
use lab::Contender;

fn lab(args: &[&str], scene: &Path, out: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lab"))
        .args(args)
        .arg("--scene")
        .arg(scene)
        .arg("--out")
        .arg(out)
        .output()
        .expect("the lab binary runs")
}

#[test]
fn a_small_scene_is_measured_by_every_contender() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("mine.scene");
    std::fs::write(
        &scene,
        "clear 0\npoly color=2 10,10 60,15 30,70\npoly color=3 rule=nonzero 100,20 200,20 200,120 100,120 | 120,40 \
         120,100 180,100 180,40\npoly color=4 20,150 90,140 70,190\n",
    )
    .unwrap();
    let out = dir.path().join("out");
    let run = lab(&["--quick", "--scene-from", "mine.scene, by hand"], &scene, &out);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let report = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(report.contains("the polygons of your scene `mine` (mine.scene, by hand)"), "{report}");
    assert!(report.contains("| scene_triangles | your scene | 2 |"), "{report}");
    assert!(report.contains("| scene_complex | your scene | 1 |"), "{report}");
    assert!(!report.contains("| demo_scenes |"), "{report}");
    let mut lines = report.lines().skip_while(|line| !line.starts_with("## Speed: ns per polygon"));
    let columns = lines.nth(2).expect("the speed table's header");
    for name in Contender::all().iter().map(Contender::name).chain(Bound::ALL.map(Bound::name)) {
        assert!(columns.contains(&format!("| {name} |")), "{name} missing from {columns}");
    }
    let results: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap()).unwrap();
    assert_eq!(results["scene"]["name"], "mine");
    let summary: lab::Summary =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(
        summary.families.iter().map(|f| f.family.as_str()).collect::<Vec<_>>(),
        ["scene_triangles", "scene_complex"]
    );
    assert!(summary.families.iter().all(|f| f.closest_peer.is_some()), "{summary:?}");
    // summary.json's closest peers are the run's: on each family, the peer
    // whose time over `exact`'s is least in results.json.
    for family in &summary.families {
        let peers = results["rows"].as_array().unwrap().iter().filter(|row| {
            row["kind"] == "peer" && row["family"] == family.family.as_str() && row["vs_exact"].is_object()
        });
        let ratio = |row: &&serde_json::Value| row["vs_exact"]["ratio"].as_f64().unwrap();
        let closest = peers.min_by(|a, b| ratio(a).total_cmp(&ratio(b)));
        assert_eq!(
            closest.map(|row| row["name"].as_str().unwrap()),
            family.closest_peer.as_deref(),
            "{}",
            family.family
        );
        assert_eq!(closest.map(|row| ratio(&row)), family.vs_exact.map(|r| r.ratio), "{}", family.family);
    }
    // Nothing to sweep and no stress family: those charts are not drawn.
    assert!(out.join("versus_exact.png").is_file() && out.join("speed_vs_accuracy.svg").is_file());
    assert!(!out.join("rotation.png").exists() && !out.join("stability.png").exists());
}

#[test]
fn a_bad_scene_is_refused_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let bad = dir.path().join("bad.scene");
    std::fs::write(&bad, "clear 0\npoly color=2 10,10 60,x 30,70\n").unwrap();
    let empty = dir.path().join("empty.scene");
    std::fs::write(&empty, "clear 0\n").unwrap();
    let missing = dir.path().join("missing.scene");
    for (scene, message) in [
        (&bad, "bad.scene: bad scene file: line 2: bad vertex"),
        (&empty, "scene `empty` has no polygon to measure"),
        (&missing, "failed to read scene file"),
    ] {
        let run = lab(&["--quick"], scene, &out);
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(!run.status.success() && stderr.contains(message), "{}: {stderr}", scene.display());
        assert!(!out.exists(), "{} wrote {}", scene.display(), out.display());
    }
}
