//! The boot stages the image is built with: the registry's `bootloader`
//! with its BIOS stage 2 and its UEFI loader patched.
//!
//! Why stage 2: it would leave the card in a VBE mode the kernel cannot
//! undo on every card; docs/boot.md#why-stage-2-is-patched tells it, with
//! what was measured.
//!
//! Why the UEFI loader: under Secure Boot shim starts it only if it carries
//! an `.sbat` section, and once started it would boot any kernel beside it
//! on the stick; the patched loader has the section and checks the
//! SHA-256 of the kernel and of `boot.json` against digests the image
//! build writes into it before signing it ([`crate::secure_boot`],
//! boot/image/loader/verify.rs).
//!
//! How: nothing of the bootloader lives in this repository. At build time
//! [`crate::patched_copy`] has cargo fetch `bootloader`,
//! `bootloader-x86_64-bios-stage-2` and `bootloader-x86_64-uefi` of
//! [`VERSION`] from the registry, checks their archives against the
//! SHA-256 pinned in [`crate::sources`], unpacks `bootloader` into a folder
//! under the nightly target directory with the stage-2 crate at
//! `bios/stage-2` and the loader at `uefi` inside it (where `bootloader`'s
//! build script builds them from when those folders exist; the other
//! stages still come from the registry), and applies [`STAGE_2_EDITS`] and
//! [`LOADER_EDITS`], each of which must match exactly once or the build
//! stops saying which ([`apply_edits`]). The image writer (`boot`) is then
//! built against that copy.

use anyhow::{ensure, Result};

use crate::sources::{PinnedCrate, BOOTLOADER, STAGE_2, UEFI_LOADER};

pub use crate::sources::VERSION;

/// One change to a file of a patched crate: `find` must occur exactly
/// once and becomes `replace`.
pub struct Edit {
    /// The file, relative to the crate.
    pub file: &'static str,
    /// What the edit does and why, for the error when `find` is missing.
    pub purpose: &'static str,
    pub find: &'static str,
    pub replace: &'static str,
}

/// Everything the image's stage 2 changes from the registry's, and why.
pub const STAGE_2_EDITS: &[Edit] = &[
    Edit {
        file: "Cargo.toml",
        purpose: "make the copy a workspace of its own: cargo would otherwise take it for a member of ours, \
                  since it lies inside our workspace's folder",
        find: "\n[profile.stage-2]\n",
        replace: "\n[workspace]\n\n[profile.stage-2]\n",
    },
    Edit {
        file: "src/main.rs",
        purpose: "drop the VBE query and mode set (`vesa_mode.enable().unwrap();`): the card stays in the \
                  BIOS's text mode, and a machine without VBE boots too",
        find: "    // TODO: load these from the kernel's config instead of hardcoding
    let max_width = 1280;
    let max_height = 720;

    let mut vesa_info = vesa::VesaInfo::query(disk_buffer).unwrap();
    let vesa_mode = vesa_info
        .get_best_mode(max_width, max_height)
        .unwrap()
        .expect(\"no suitable VESA mode found\");
    writeln!(
        screen::Writer,
        \"VESA MODE: {}x{}\",
        vesa_mode.width,
        vesa_mode.height
    )
    .unwrap();
    vesa_mode.enable().unwrap();
",
        replace: "",
    },
    Edit {
        file: "src/main.rs",
        purpose: "describe the mode-13h window instead of the VBE mode's framebuffer: the later stages log \
                  there (one byte a pixel, a format their logger takes), which text mode does not show, and \
                  the kernel finds it in its boot info",
        find: "        framebuffer: BiosFramebufferInfo {
            region: Region {
                start: vesa_mode.framebuffer_start.into(),
                len: u64::from(vesa_mode.height) * u64::from(vesa_mode.bytes_per_scanline),
            },
            width: vesa_mode.width,
            height: vesa_mode.height,
            bytes_per_pixel: vesa_mode.bytes_per_pixel,
            stride: vesa_mode.bytes_per_scanline / u16::from(vesa_mode.bytes_per_pixel),
            pixel_format: vesa_mode.pixel_format,
        },
",
        replace: "        framebuffer: BiosFramebufferInfo {
            region: Region { start: 0xA0000, len: 320 * 200 },
            width: 320,
            height: 200,
            bytes_per_pixel: 1,
            stride: 320,
            pixel_format: bootloader_x86_64_bios_common::PixelFormat::Rgb,
        },
",
    },
];

/// Everything the image's copy of `bootloader` itself changes: its build
/// script, which builds the BIOS stages with `cargo install` (the
/// registry's stages 3 and 4, the boot sector, and the patched stage 2),
/// passes them cargo's path trimming (a nightly feature), as the kernel's
/// build and the loader's profile do; and `--force`, since `cargo install`
/// skips a version it installed before into the same folder whatever its
/// flags (a stage built without the trimming would stay).
pub const BOOTLOADER_EDITS: &[Edit] = &[
    Edit {
        file: "build.rs",
        purpose:
            "build the BIOS boot sector with no path of the build machine in it, as the loader and the kernel are \
                  built: cargo remaps the sources of the toolchain and of every crate to names without the \
                  builder's home folder",
        find: "    cmd.arg(\"--profile\").arg(\"stage-1\");\n",
        replace: "    cmd.arg(\"--profile\").arg(\"stage-1\");\n    \
                  cmd.args([\"--force\", \"-Ztrim-paths\", \"--config\", \"profile.stage-1.trim-paths=\\\"all\\\"\"]);\n",
    },
    Edit {
        file: "build.rs",
        purpose: "build the BIOS stage 2 with no path of the build machine in it, as the loader and the kernel are \
                  built: cargo remaps the sources of the toolchain and of every crate to names without the \
                  builder's home folder",
        find: "    cmd.arg(\"--profile\").arg(\"stage-2\");\n",
        replace: "    cmd.arg(\"--profile\").arg(\"stage-2\");\n    \
                  cmd.args([\"--force\", \"-Ztrim-paths\", \"--config\", \"profile.stage-2.trim-paths=\\\"all\\\"\"]);\n",
    },
    Edit {
        file: "build.rs",
        purpose: "build the BIOS stage 3 with no path of the build machine in it, as the loader and the kernel are \
                  built: cargo remaps the sources of the toolchain and of every crate to names without the \
                  builder's home folder",
        find: "    cmd.arg(\"--profile\").arg(\"stage-3\");\n",
        replace: "    cmd.arg(\"--profile\").arg(\"stage-3\");\n    \
                  cmd.args([\"--force\", \"-Ztrim-paths\", \"--config\", \"profile.stage-3.trim-paths=\\\"all\\\"\"]);\n",
    },
    Edit {
        file: "build.rs",
        purpose: "build the BIOS stage 4 with no path of the build machine in it, as the loader and the kernel are \
                  built: cargo remaps the sources of the toolchain and of every crate to names without the \
                  builder's home folder",
        find: "    cmd.arg(\"--profile\").arg(\"stage-4\");\n",
        replace: "    cmd.arg(\"--profile\").arg(\"stage-4\");\n    \
                  cmd.args([\"--force\", \"-Ztrim-paths\", \"--config\", \"profile.stage-4.trim-paths=\\\"all\\\"\"]);\n",
    },
];

/// Everything the image's UEFI loader changes from the registry's, and
/// why; the code it calls is [`LOADER_FILES`].
pub const LOADER_EDITS: &[Edit] = &[
    Edit {
        file: "Cargo.toml",
        purpose: "make the copy a workspace of its own, as stage 2's",
        find: "\n[[bin]]\n",
        replace: "\n[workspace]\n\n[[bin]]\n",
    },
    Edit {
        file: "src/main.rs",
        purpose: "add the modules that check the kernel and boot.json and carry the .sbat section",
        find: "\nmod memory_descriptor;\n",
        replace: "\nmod memory_descriptor;\nmod polylab_sha256;\nmod polylab_verify;\n",
    },
    Edit {
        file: "src/main.rs",
        purpose: "check the kernel's SHA-256 before anything reads it, whether it came from the disk or over TFTP",
        find: "    let kernel_slice = load_file_from_boot_method(&KERNEL_FILE, boot_mode)?;\n",
        replace: "    let kernel_slice = load_file_from_boot_method(&KERNEL_FILE, boot_mode)?;\n    \
                  polylab_verify::check_kernel(kernel_slice);\n",
    },
    Edit {
        file: "src/main.rs",
        purpose: "check boot.json's SHA-256 before it is parsed (a missing one is refused too)",
        find: "fn load_config_file(boot_mode: BootMode) -> Option<&'static mut [u8]> {
    load_file_from_boot_method(&CONFIG_FILE, boot_mode)
}
",
        replace: "fn load_config_file(boot_mode: BootMode) -> Option<&'static mut [u8]> {
    let config = load_file_from_boot_method(&CONFIG_FILE, boot_mode);
    polylab_verify::check_config(config.as_deref());
    config
}
",
    },
    Edit {
        file: "src/main.rs",
        purpose: "refuse a ramdisk on the volume: nothing checks it, and the loader would map it for the kernel",
        find: "fn load_ramdisk(boot_mode: BootMode) -> Option<&'static mut [u8]> {
    load_file_from_boot_method(&RAMDISK_FILE, boot_mode)
}
",
        replace: "fn load_ramdisk(boot_mode: BootMode) -> Option<&'static mut [u8]> {
    let ramdisk = load_file_from_boot_method(&RAMDISK_FILE, boot_mode);
    polylab_verify::check_no_ramdisk(ramdisk.is_some());
    ramdisk
}
",
    },
    Edit {
        file: "src/main.rs",
        purpose: "refuse an empty file on the disk before the loader asks for a zero-byte allocation, which panics",
        find: "    let file_size = usize::try_from(file_info.file_size()).unwrap();\n",
        replace: "    let file_size = usize::try_from(file_info.file_size()).unwrap();\n    \
                  polylab_verify::check_not_empty(&name, file_size);\n",
    },
    Edit {
        file: "src/main.rs",
        purpose: "refuse an empty file over TFTP as on the disk",
        find: "    let kernel_size = usize::try_from(file_size).expect(\"The file size should fit into usize\");\n",
        replace:
            "    let kernel_size = usize::try_from(file_size).expect(\"The file size should fit into usize\");\n    \
                  polylab_verify::check_not_empty(&name, kernel_size);\n",
    },
    Edit {
        file: "Cargo.toml",
        purpose: "let the loader's profile trim paths (a nightly cargo feature)",
        find: "\n[package]\n",
        replace: "\ncargo-features = [\"trim-paths\"]\n\n[package]\n",
    },
    Edit {
        file: "Cargo.toml",
        purpose: "write no path of the build machine into the loader: cargo remaps the sources of the toolchain \
                  and of every crate to names without the builder's home folder",
        find: "\n[[bin]]\n",
        replace: "\n[profile.release]\ntrim-paths = \"all\"\n\n[[bin]]\n",
    },
    Edit {
        file: "src/main.rs",
        purpose: "hand over no framebuffer where the firmware's graphics mode has none the kernel can draw in \
                  (PixelBitmask or BltOnly), before the uefi crate's `frame_buffer()` panics on a BltOnly mode, \
                  instead of a panic that hangs the PC before the kernel (which says so on COM1)",
        find: "    let mode_info = gop.current_mode_info();
    let mut framebuffer = gop.frame_buffer();
",
        replace: "    let mode_info = gop.current_mode_info();
    if matches!(mode_info.pixel_format(), PixelFormat::Bitmask | PixelFormat::BltOnly) {
        return None;
    }
    let mut framebuffer = gop.frame_buffer();
",
    },
    Edit {
        file: "src/main.rs",
        purpose: "the same formats in the match below it: no panic left there either",
        find: "            PixelFormat::Bitmask | PixelFormat::BltOnly => {
                panic!(\"Bitmask and BltOnly framebuffers are not supported\")
            }
",
        replace: "            PixelFormat::Bitmask | PixelFormat::BltOnly => return None,
",
    },
    Edit {
        file: "src/main.rs",
        purpose: "take the smallest mode of at least the configured size (640x400, boot.json) with a framebuffer \
                  the kernel can draw in, not the largest: the kernel's 320x200 frame, scaled by a whole number, \
                  then costs 640x400 pixels a frame instead of the native mode's (1600x1000 at 1080p)",
        find: "                .filter(|m| {
                    let res = m.info().resolution();
                    res.1 >= height && res.0 >= width
                })
                .last(),
",
        replace: "                .filter(|m| {
                    let res = m.info().resolution();
                    res.1 >= height
                        && res.0 >= width
                        && matches!(m.info().pixel_format(), PixelFormat::Rgb | PixelFormat::Bgr)
                })
                .min_by_key(|m| {
                    let res = m.info().resolution();
                    res.0 * res.1
                }),
",
    },
    Edit {
        file: "src/main.rs",
        purpose: "keep the firmware's mode where it refuses the one chosen, instead of a panic (a hang, as above)",
        find: "        gop.set_mode(&mode)
            .expect(\"Failed to apply the desired display mode\");
",
        replace: "        // The firmware's own mode stays if it refuses this one.
        let _ = gop.set_mode(&mode);
",
    },
];

/// Files added to the UEFI loader's source: (path in the crate, text).
pub const LOADER_FILES: &[(&str, &str)] = &[
    ("src/polylab_sha256.rs", include_str!("../loader/sha256.rs")),
    ("src/polylab_verify.rs", include_str!("../loader/verify.rs")),
];

/// One crate put into the copy of `bootloader`, patched.
pub struct Patch {
    pub source: PinnedCrate,
    /// Where in the copy: the folder `bootloader`'s build script builds
    /// that stage from when it exists.
    pub folder: &'static str,
    pub edits: &'static [Edit],
    pub added_files: &'static [(&'static str, &'static str)],
}

/// The patched crates: `bootloader` itself (at the copy's root), stage 2
/// and the UEFI loader.
pub const PATCHES: [Patch; 3] = [
    Patch { source: BOOTLOADER, folder: "", edits: BOOTLOADER_EDITS, added_files: &[] },
    Patch { source: STAGE_2, folder: "bios/stage-2", edits: STAGE_2_EDITS, added_files: &[] },
    Patch { source: UEFI_LOADER, folder: "uefi", edits: LOADER_EDITS, added_files: LOADER_FILES },
];

/// `text` with every edit of `edits` for `file` applied, in order; fails
/// naming the first edit whose `find` does not occur exactly once.
pub fn apply_edits(crate_name: &str, file: &str, text: &str, edits: &[Edit]) -> Result<String> {
    let mut text = text.to_string();
    for edit in edits.iter().filter(|edit| edit.file == file) {
        let found = text.matches(edit.find).count();
        ensure!(
            found == 1,
            "cannot patch {crate_name} {VERSION}'s {file}: the text to change occurs {found} times, not once \
             (the edit is to {}); its first line: `{}`",
            edit.purpose,
            edit.find.trim_start_matches('\n').lines().next().unwrap_or_default().trim()
        );
        text = text.replacen(edit.find, edit.replace, 1);
    }
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_image_builder_asks_for_exactly_the_patched_version() {
        let manifest = include_str!("../../Cargo.toml");
        assert!(
            manifest.contains(&format!("bootloader = {{ version = \"={VERSION}\"")),
            "boot/Cargo.toml must pin bootloader ={VERSION}, the version the edits are written for"
        );
    }

    #[test]
    fn every_edit_applies_once_and_a_missing_text_is_an_error_naming_it() {
        let source = "fn main() {\n    a();\n    vesa_mode.enable().unwrap();\n    b();\n}\n";
        let edits = [Edit {
            file: "src/main.rs",
            purpose: "drop the mode set",
            find: "    vesa_mode.enable().unwrap();\n",
            replace: "",
        }];
        assert_eq!(apply_edits("x", "src/main.rs", source, &edits).unwrap(), "fn main() {\n    a();\n    b();\n}\n");
        assert_eq!(apply_edits("x", "Cargo.toml", source, &edits).unwrap(), source, "edits of other files");
        let error = apply_edits("x", "src/main.rs", "fn main() {}\n", &edits).unwrap_err().to_string();
        assert_eq!(
            error,
            format!(
                "cannot patch x {VERSION}'s src/main.rs: the text to change occurs 0 times, not once \
                 (the edit is to drop the mode set); its first line: `vesa_mode.enable().unwrap();`"
            )
        );
        let twice = format!("{source}{source}");
        assert!(apply_edits("x", "src/main.rs", &twice, &edits).unwrap_err().to_string().contains("occurs 2 times"));
    }

    #[test]
    fn the_edits_remove_the_mode_set_and_every_use_of_the_vbe_mode() {
        let removed: String = STAGE_2_EDITS.iter().map(|edit| edit.find).collect();
        let added: String = STAGE_2_EDITS.iter().map(|edit| edit.replace).collect();
        assert!(removed.contains("vesa_mode.enable().unwrap();"));
        assert!(removed.contains("vesa::VesaInfo::query("));
        assert!(!added.contains("vesa"), "{added}");
    }

    #[test]
    fn the_loader_edits_leave_no_panic_on_the_framebuffer_path_and_take_the_smallest_mode() {
        let replacing = |text: &str| {
            let edit = LOADER_EDITS.iter().find(|edit| edit.find.contains(text)).expect("an edit replaces it");
            assert!(!edit.replace.contains("panic!") && !edit.replace.contains(".expect("), "{}", edit.replace);
            edit.replace
        };
        assert!(replacing("Bitmask and BltOnly framebuffers are not supported").contains("=> return None,"));
        replacing(".expect(\"Failed to apply the desired display mode\")");
        assert!(replacing(".last(),").contains(".min_by_key("));
        let early = replacing("    let mut framebuffer = gop.frame_buffer();\n");
        let check = early.find("PixelFormat::BltOnly) {\n        return None;").expect("the early return");
        assert!(check < early.find("gop.frame_buffer()").expect("the framebuffer's access"), "{early}");
    }

    #[test]
    fn the_loader_edits_call_both_checks_and_add_their_modules() {
        let added: String = LOADER_EDITS.iter().map(|edit| edit.replace).collect();
        assert!(added.contains("polylab_verify::check_kernel(kernel_slice);"), "{added}");
        assert!(added.contains("polylab_verify::check_config(config.as_deref());"), "{added}");
        for (file, _) in LOADER_FILES {
            let module = file.trim_start_matches("src/").trim_end_matches(".rs");
            assert!(added.contains(&format!("mod {module};")), "{file} is added but not declared");
        }
    }
}
