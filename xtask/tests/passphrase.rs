//! The Secure Boot key's passphrase, given in its variable, leaves the
//! xtask's environment before its first child starts: the decision of
//! xtask/src/main.rs, tested through the xtask binary.

use std::os::unix::fs::PermissionsExt;
use std::process::Command;

use boot_image::secure_boot::key::PASSPHRASE_ENV;

#[test]
fn the_first_child_of_the_xtask_never_inherits_the_passphrase() {
    let dir = tempfile::tempdir().unwrap();
    // `cargo xtask lint` starts `rustup` first: this one, first on the
    // PATH, writes the environment it inherited beside itself and fails.
    let rustup = dir.path().join("rustup");
    std::fs::write(&rustup, "#!/bin/sh\nenv > \"$(dirname \"$0\")/environment\"\nexit 1\n").unwrap();
    std::fs::set_permissions(&rustup, std::fs::Permissions::from_mode(0o755)).unwrap();
    let path = format!("{}:{}", dir.path().display(), std::env::var("PATH").unwrap());
    let lint = Command::new(env!("CARGO_BIN_EXE_xtask"))
        .arg("lint")
        .env("PATH", path)
        .env(PASSPHRASE_ENV, "a secret of the test")
        .output()
        .unwrap();
    assert!(!lint.status.success(), "the xtask went on after its rustup failed");
    let environment = std::fs::read_to_string(dir.path().join("environment")).expect("the xtask never ran rustup");
    assert!(environment.contains("PATH="), "{environment}");
    assert!(!environment.contains("a secret of the test"), "the xtask's child inherited {PASSPHRASE_ENV}");
}
