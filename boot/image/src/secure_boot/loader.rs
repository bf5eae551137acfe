//! The UEFI loader as it goes onto the stick: the patched loader
//! (boot/image/loader/verify.rs) checked for its refusals, the kernel's
//! and `boot.json`'s SHA-256 written into its placeholder, then either
//! left as it is, for its own SHA-256 (the Authenticode digest shim and
//! MokManager compute) to be enrolled, or signed with the user's key by
//! `sbsign`; the digest and the signature both cover the kernel's digests.

use std::path::Path;
use std::process::Command;

use anyhow::{ensure, Context, Result};
use object::pe::{ImageDataDirectory, ImageFileHeader, ImageOptionalHeader64, IMAGE_DIRECTORY_ENTRY_SECURITY};
use object::read::pe::PeFile64;
use object::{LittleEndian as LE, Object, ObjectSection};
use sha2::{Digest, Sha256};

use super::key::SigningKey;
use install::output_with_input;

/// The bytes that start the digest placeholder in the loader (its
/// `MARKER`); the kernel's SHA-256 follows, then `boot.json`'s.
pub const DIGESTS_MARKER: &[u8; 16] = b"polylab-digests:";

/// The first line of every `.sbat` section (shim's SBAT.md).
pub const SBAT_HEADER: &str = "sbat,1,SBAT Version,sbat,1,https://github.com/rhboot/shim/blob/main/SBAT.md\n";

/// Fails unless `loader` is a PE32+ image whose `.sbat` section starts
/// with [`SBAT_HEADER`] and has our component's line: shim 16 refuses an
/// image without one, and one whose section lies at address 0.
pub fn check_sbat(loader: &[u8]) -> Result<()> {
    let pe = PeFile64::parse(loader).context("the UEFI loader is not a PE32+ image")?;
    let section = pe.section_by_name(".sbat").context("the UEFI loader has no .sbat section")?;
    let data = section.data().context("the UEFI loader's .sbat section cannot be read")?;
    let text = String::from_utf8_lossy(data);
    ensure!(section.address() != pe.relative_address_base(), "the UEFI loader's .sbat section lies at address 0");
    ensure!(
        text.starts_with(SBAT_HEADER) && text.contains("\npolylab-loader,"),
        "the UEFI loader's .sbat section does not hold shim's header and our line: {text:?}"
    );
    Ok(())
}

/// The words of each of the loader's refusals, as boot/image/loader/verify.rs
/// says them, by the check that says them: each is in the built loader
/// only if its check is called (a unit test holds them to verify.rs).
pub const REFUSALS: [(&str, &str); 4] = [
    ("check_kernel", " is not the kernel this loader was signed for"),
    ("check_config", " is not the boot.json this loader was signed for"),
    ("check_not_empty", " is an empty file, which this loader never boots"),
    ("check_no_ramdisk", "a ramdisk is on the volume, and this loader loads none"),
];

/// Fails unless the built `loader` holds the words of every refusal in
/// [`REFUSALS`]: a loader built without a call to one of its checks (a
/// hand-edited copy, a stale build) would be signed and boot anything.
pub fn check_refusals(loader: &[u8]) -> Result<()> {
    let missing: Vec<&str> = REFUSALS
        .iter()
        .filter(|(_, words)| !loader.windows(words.len()).any(|window| window == words.as_bytes()))
        .map(|(check, _)| *check)
        .collect();
    ensure!(
        missing.is_empty(),
        "refusing to sign the UEFI loader: it never calls {} (the words it would refuse with are not in it). \
         It was not built from the patched bootloader's checked copy; remove target/nightly/patched-bootloader \
         and build again",
        missing.join(", ")
    );
    Ok(())
}

/// The loader's Authenticode SHA-256, the digest shim looks up in the MOK
/// list and MokManager's "Enroll hash from disk" enrolls: the image's
/// bytes without its checksum, its certificate table's directory entry
/// and the certificate table itself (so signing does not change it), the
/// headers first, then each section's raw data in file order, then what
/// follows the last section.
pub fn authenticode_sha256(image: &[u8]) -> Result<[u8; 32]> {
    let pe = PeFile64::parse(image).context("the UEFI loader is not a PE32+ image")?;
    let optional = pe.dos_header().nt_headers_offset() as usize + 4 + size_of::<ImageFileHeader>();
    let checksum = optional + std::mem::offset_of!(ImageOptionalHeader64, check_sum);
    let security_entry = optional
        + size_of::<ImageOptionalHeader64>()
        + IMAGE_DIRECTORY_ENTRY_SECURITY * size_of::<ImageDataDirectory>();
    let header = &pe.nt_headers().optional_header;
    let headers = header.size_of_headers.get(LE) as usize;
    let (table_start, table_len) = match pe.data_directory(IMAGE_DIRECTORY_ENTRY_SECURITY) {
        Some(entry) => (entry.virtual_address.get(LE) as usize, entry.size.get(LE) as usize),
        None => (image.len(), 0),
    };
    ensure!(
        header.number_of_rva_and_sizes.get(LE) as usize > IMAGE_DIRECTORY_ENTRY_SECURITY
            && security_entry + 8 <= headers
            && headers <= table_start
            && table_start.checked_add(table_len) == Some(image.len()),
        "the UEFI loader's headers or certificate table are not where a PE32+ image has them"
    );
    let mut digest = Sha256::new();
    digest.update(&image[..checksum]);
    digest.update(&image[checksum + 4..security_entry]);
    digest.update(&image[security_entry + 8..headers]);
    let mut sections: Vec<(usize, usize)> = pe
        .section_table()
        .iter()
        .map(|section| (section.pointer_to_raw_data.get(LE) as usize, section.size_of_raw_data.get(LE) as usize))
        .filter(|&(_, len)| len > 0)
        .collect();
    sections.sort_unstable();
    // What follows the sections starts where as many bytes as were hashed
    // so far end (the specification's count, not the last section's end).
    let mut hashed = headers;
    for (start, len) in sections {
        let section = start.checked_add(len).filter(|&end| end <= table_start).map(|end| &image[start..end]);
        digest.update(section.context("a section of the UEFI loader lies outside it")?);
        hashed += len;
    }
    digest.update(image.get(hashed..table_start).unwrap_or_default());
    Ok(digest.finalize().into())
}

/// Writes the SHA-256 of `kernel` and of `boot_json` after the marker,
/// which must occur exactly once in `loader`.
pub fn write_digests(loader: &mut [u8], kernel: &[u8], boot_json: &[u8]) -> Result<()> {
    let found: Vec<usize> = loader
        .windows(DIGESTS_MARKER.len())
        .enumerate()
        .filter(|(_, window)| window == DIGESTS_MARKER)
        .map(|(at, _)| at)
        .collect();
    let [at] = found[..] else {
        anyhow::bail!(
            "the UEFI loader holds the digest placeholder's marker {} times, not once: it was not built \
             from boot/image/loader/verify.rs",
            found.len()
        );
    };
    let start = at + DIGESTS_MARKER.len();
    ensure!(loader.len() >= start + 64, "the UEFI loader ends inside its digest placeholder");
    ensure!(loader[start..start + 64] == [0; 64], "the UEFI loader's digest placeholder is written already");
    loader[start..start + 32].copy_from_slice(&Sha256::digest(kernel));
    loader[start + 32..start + 64].copy_from_slice(&Sha256::digest(boot_json));
    Ok(())
}

/// Signs `unsigned` into `signed` with `key`, by `sbsign`, which reads
/// the key decrypted from a pipe: it is never on disk in the clear.
pub fn sign(sbsign: &Path, key: &SigningKey, unsigned: &Path, signed: &Path) -> Result<()> {
    key.ensure_current()?;
    let decrypted = key.decrypted()?;
    let mut command = Command::new(sbsign);
    command.args(["--key", "/dev/stdin", "--cert"]).arg(&key.cert).arg("--output").arg(signed).arg(unsigned);
    output_with_input(&mut command, &decrypted).context("failed to sign the UEFI loader")?;
    Ok(())
}

/// The loader's own SHA-256, tested here against `sha2`.
#[cfg(test)]
#[path = "../../loader/sha256.rs"]
mod loader_sha256;

#[cfg(test)]
mod tests {
    use super::loader_sha256;
    use super::*;

    fn hex(bytes: &[u8]) -> String {
        bytes.iter().map(|byte| format!("{byte:02x}")).collect()
    }

    #[test]
    fn the_loaders_sha256_is_sha2s_on_every_length_around_the_blocks() {
        let bytes: Vec<u8> = (0..300u32).map(|i| (i.wrapping_mul(2_654_435_761) >> 13) as u8).collect();
        for len in 0..bytes.len() {
            assert_eq!(loader_sha256::sha256(&bytes[..len]), Sha256::digest(&bytes[..len]).as_slice(), "{len} bytes");
        }
        assert_eq!(
            hex(&loader_sha256::sha256(&vec![b'a'; 1_000_000])),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0",
            "FIPS 180-2, appendix B.3"
        );
        assert_eq!(
            hex(&loader_sha256::sha256(b"abc")),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad",
            "FIPS 180-2, appendix B.1"
        );
    }

    #[test]
    fn every_refusal_required_of_the_built_loader_is_said_by_its_check() {
        let verify = include_str!("../../loader/verify.rs");
        for (check, words) in REFUSALS {
            assert!(verify.contains(&format!("pub fn {check}(")), "verify.rs has no {check}");
            assert!(verify.contains(&format!(": &str = \"{words}\";")), "verify.rs never says {words:?}");
        }
        let mut loader = b"MZ...".to_vec();
        for (_, words) in REFUSALS {
            loader.extend_from_slice(words.as_bytes());
        }
        check_refusals(&loader).unwrap();
        let without_kernel_check = String::from_utf8(loader).unwrap().replace(REFUSALS[0].1, "");
        let error = check_refusals(without_kernel_check.as_bytes()).unwrap_err().to_string();
        assert!(error.contains("it never calls check_kernel (the words"), "{error}");
    }

    #[test]
    fn the_marker_and_the_sbat_header_are_the_loaders() {
        let verify = include_str!("../../loader/verify.rs");
        let marker = std::str::from_utf8(DIGESTS_MARKER).unwrap();
        assert!(verify.contains(&format!("const MARKER: &[u8; 16] = b\"{marker}\";")));
        assert!(verify.contains(&format!("const SBAT_CSV: &str = \"{}", SBAT_HEADER.trim_end())));
    }

    #[test]
    fn digests_go_after_the_one_marker() {
        let mut loader = b"MZ....".to_vec();
        loader.extend_from_slice(DIGESTS_MARKER);
        loader.extend_from_slice(&[0; 64]);
        loader.extend_from_slice(b"rest");
        write_digests(&mut loader, b"kernel", b"{}").unwrap();
        let start = 6 + DIGESTS_MARKER.len();
        assert_eq!(&loader[start..start + 32], Sha256::digest(b"kernel").as_slice());
        assert_eq!(&loader[start + 32..start + 64], Sha256::digest(b"{}").as_slice());
        assert!(loader.ends_with(b"rest"));
        let error = write_digests(&mut loader, b"kernel", b"{}").unwrap_err().to_string();
        assert!(error.contains("written already"), "{error}");
        loader.extend_from_slice(DIGESTS_MARKER);
        let error = write_digests(&mut loader, b"kernel", b"{}").unwrap_err().to_string();
        assert!(error.contains("2 times, not once"), "{error}");
    }
}
