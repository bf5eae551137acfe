//! What the image needs to boot under UEFI Secure Boot: shim signed by
//! Microsoft, MokManager, and the UEFI loader, either to be enrolled by
//! its own SHA-256 or signed with the user's key, each put on the FAT
//! partition where shim looks.
//!
//! The chain (docs/secure-boot.md tells it in full): the firmware trusts
//! Microsoft's third-party UEFI CA (in its `db`), which signed Debian's
//! shim; shim trusts the hashes and keys in the MOK list, which the user
//! enrolls with MokManager; the loader's hash (or signature) covers the
//! SHA-256 of the kernel and of `boot.json` it refuses to boot anything
//! but.

pub mod debian;
pub mod key;
pub mod loader;
pub mod shim;

use key::SigningKey;

/// How the user tells shim to trust the loader.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Enrollment {
    /// The loader's own SHA-256 goes into the MOK list ("Enroll hash from
    /// disk"): no key exists, and every build is enrolled anew.
    Hash,
    /// The loader is signed with the user's key, whose certificate goes
    /// into the MOK list once.
    Key(SigningKey),
}

/// Where a UEFI firmware starts removable media: shim (FAT names ignore case).
pub const SHIM_PATH: &str = "efi/boot/bootx64.efi";
/// The second stage shim starts from its own folder: our signed loader
/// (shim's name for it is GRUB's, the loader it was made for).
pub const LOADER_PATH: &str = "efi/boot/grubx64.efi";
/// MokManager, which shim starts when the loader's signature is not
/// trusted yet and where the user enrolls the key.
pub const MOK_MANAGER_PATH: &str = "efi/boot/mmx64.efi";
/// The user's certificate (DER), at the root, where MokManager's "Enroll
/// key from disk" shows it first (its name sorts before the others'), on
/// an image signed with a key.
pub const CERTIFICATE_PATH: &str = "ENROLL-THIS-polylab-key.cer";
/// A copy of the loader at the root, where MokManager's "Enroll hash from
/// disk" shows it first, on an image whose loader is enrolled by its hash.
pub const HASH_ENROLL_PATH: &str = "ENROLL-THIS-polylab-loader.efi";
