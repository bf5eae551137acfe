//! Builds the C shim of the Allegro and GD peers (`src/peers/shim.c`)
//! against the system's Allegro 4 and GD, found by pkg-config, and links
//! the lab with both. (The SDL2_gfx peer links through the `sdl2` crate,
//! the Cairo peer through `cairo-rs`.) `cargo xtask lab`, `test` and
//! `lint` install the libraries when missing.

const SHIM: &str = "src/peers/shim.c";
/// The pkg-config names of the libraries the shim includes.
const LIBRARIES: [&str; 2] = ["allegro", "gdlib"];

fn main() {
    println!("cargo:rerun-if-changed={SHIM}");
    let found: Vec<pkg_config::Library> = LIBRARIES
        .iter()
        .map(|name| {
            // Linked below, after the shim, which needs them.
            pkg_config::Config::new().cargo_metadata(false).probe(name).unwrap_or_else(|error| {
                panic!(
                    "the lab's C peers need {name} (pkg-config): {error}\n`cargo xtask lab` installs it; by hand: \
                     sudo apt-get install --no-install-recommends liballegro4-dev libgd-dev libsdl2-gfx-dev pkg-config"
                )
            })
        })
        .collect();
    let mut shim = cc::Build::new();
    shim.file(SHIM).warnings(true);
    for library in &found {
        shim.includes(&library.include_paths);
        for (name, value) in &library.defines {
            shim.define(name, value.as_deref());
        }
    }
    shim.compile("lab_peers_shim");
    for library in &found {
        for path in &library.link_paths {
            println!("cargo:rustc-link-search=native={}", path.display());
        }
        for lib in &library.libs {
            println!("cargo:rustc-link-lib={lib}");
        }
    }
}
