//! What the build needs to know of the shim it puts on the stick: its
//! version, and whether it lets a loader signed with the user's key boot.
//!
//! shim before 16 (15.8, for one) hooks ExitBootServices and lets it
//! through only if the second stage "took part" in verification: it
//! called the SHIM_LOCK protocol's Verify (or started an image through
//! the firmware's LoadImage and StartImage), or shim itself had verified
//! it by a hash in db or the MOK list; otherwise it prints "Bootloader has
//! not verified loaded image." and halts. Our loader boots an ELF kernel,
//! which Verify (a PE checker) cannot verify; the loader checks it by the
//! SHA-256 its signature covers, and calling Verify only to be counted as
//! taking part would be a lie. So with shim 15 the loader boots when its
//! own hash is enrolled (`--enroll hash`, the default) and not when it is
//! verified by the user's certificate, which the build refuses. shim 16
//! dropped the hook (its loader protocol replaced it).

use anyhow::{ensure, Context, Result};
use object::read::pe::PeFile64;
use object::{Object, ObjectSection};

/// The first shim release without the ExitBootServices hook.
pub const FIRST_WITHOUT_EXIT_HOOK: u32 = 16;

/// shim's version, from the `$Version: X.Y $` line of its `.data.ident`
/// section: (major, minor).
pub fn version(shim: &[u8]) -> Result<(u32, u32)> {
    let pe = PeFile64::parse(shim).context("shim is not a PE32+ image")?;
    let ident = pe.section_by_name(".data.ident").context("shim has no .data.ident section")?;
    let text = String::from_utf8_lossy(ident.data().context("shim's .data.ident cannot be read")?).into_owned();
    parse_version(&text).with_context(|| format!("shim's .data.ident names no version: {text:?}"))
}

fn parse_version(ident: &str) -> Option<(u32, u32)> {
    let version = ident.split("$Version: ").nth(1)?.split(' ').next()?;
    let mut parts = version.split('.');
    let major = parts.next()?.parse().ok()?;
    let minor = parts.next().map_or(Some(0), |minor| minor.parse().ok())?;
    Some((major, minor))
}

/// Fails, saying why and what to do, unless `shim` boots a loader it
/// verified by the user's certificate.
pub fn ensure_boots_key_signed_loader(shim: &[u8], source: &str) -> Result<()> {
    let (major, minor) = version(shim)?;
    ensure!(
        major >= FIRST_WITHOUT_EXIT_HOOK,
        "refusing to build an image signed with your key around shim {major}.{minor} ({source}): shim before \
         {FIRST_WITHOUT_EXIT_HOOK} halts at ExitBootServices (\"Bootloader has not verified loaded image. System is \
         compromised. halting.\") unless the loader had shim verify what it boots, and shim can verify PE images \
         only, not this loader's ELF kernel (the loader checks it by the SHA-256 its signature covers). Build \
         with the default --enroll hash instead (shim {major}.{minor} boots a loader enrolled by its hash), or \
         with shim {FIRST_WITHOUT_EXIT_HOOK} or newer"
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_version_is_read_from_shims_ident_text() {
        assert_eq!(parse_version("UEFI SHIM\n$Version: 15.8 $\n$BuildMachine: Linux x86_64 $\n"), Some((15, 8)));
        assert_eq!(parse_version("UEFI SHIM\n$Version: 16.1 $\n"), Some((16, 1)));
        assert_eq!(parse_version("UEFI SHIM\n$Version: 16 $\n"), Some((16, 0)));
        assert_eq!(parse_version("UEFI SHIM\n"), None);
        assert_eq!(parse_version("$Version: x.1 $"), None);
    }
}
