//! What the image needs to boot under UEFI Secure Boot: shim signed by
//! Microsoft, MokManager, the user's own key, and the UEFI loader signed
//! with it, each put on the FAT partition where shim looks.
//!
//! The chain (docs/boot.md tells it in full): the firmware trusts
//! Microsoft's third-party UEFI CA (in its `db`), which signed Debian's
//! shim; shim trusts the keys in the MOK list, which the user enrolls once
//! with MokManager (the certificate is on the stick); that key signed our
//! loader, whose signature covers the SHA-256 of the kernel and of
//! `boot.json` it refuses to boot anything but.

pub mod debian;
pub mod key;
pub mod loader;

/// Where a UEFI firmware starts removable media: shim (FAT names ignore case).
pub const SHIM_PATH: &str = "efi/boot/bootx64.efi";
/// The second stage shim starts from its own folder: our signed loader
/// (shim's name for it is GRUB's, the loader it was made for).
pub const LOADER_PATH: &str = "efi/boot/grubx64.efi";
/// MokManager, which shim starts when the loader's signature is not
/// trusted yet and where the user enrolls the key.
pub const MOK_MANAGER_PATH: &str = "efi/boot/mmx64.efi";
/// The user's certificate (DER), at the root, where MokManager's "Enroll
/// key from disk" shows it first (its name sorts before the others').
pub const CERTIFICATE_PATH: &str = "ENROLL-THIS-polylab-key.cer";
