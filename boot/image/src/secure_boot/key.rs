//! The user's own Secure Boot key, which signs the loader.
//!
//! Never a key shipped with the project: whoever holds the private half of
//! a key a PC trusts can boot anything on it, so every user has one of
//! their own. It is made on the first image build (RSA 2048, a self-signed
//! certificate, with `openssl`) and kept in the user's configuration
//! folder, outside `target/`, so that `cargo clean` does not force a new
//! enrollment; the private key is readable by its owner only and goes
//! neither into the repository nor onto the image (only the certificate
//! does). [`KEY_ENV`] and [`CERT_ENV`] (or `cargo xtask image --key
//! --cert`) take a key of one's own instead.

use std::io::Write;
use std::os::unix::fs::{DirBuilderExt, OpenOptionsExt, PermissionsExt};
use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{bail, ensure, Context, Result};
use sha2::{Digest, Sha256};

use crate::process::{find_in_path, output_of};

/// A private key (PEM) to sign with instead of the generated one; needs [`CERT_ENV`].
pub const KEY_ENV: &str = "POLYLAB_SECURE_BOOT_KEY";
/// Its certificate (PEM or DER).
pub const CERT_ENV: &str = "POLYLAB_SECURE_BOOT_CERT";

/// The generated key's files in the key folder.
const KEY_FILE: &str = "polylab-secure-boot.key";
const CERT_FILE: &str = "polylab-secure-boot.crt";

/// A key and its certificate, as `sbsign` takes them.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SigningKey {
    /// The private key, PEM.
    pub key: PathBuf,
    /// The certificate, PEM.
    pub cert: PathBuf,
}

impl SigningKey {
    /// The key named by [`KEY_ENV`] and [`CERT_ENV`] if set, else the
    /// user's generated key, made now if there is none. A certificate
    /// given in DER is converted into `scratch`.
    pub fn users(scratch: &Path) -> Result<Self> {
        match (std::env::var_os(KEY_ENV), std::env::var_os(CERT_ENV)) {
            (Some(key), Some(cert)) => Self::own(Path::new(&key), Path::new(&cert), scratch),
            (None, None) => Self::in_folder(&key_folder()?),
            _ => bail!("{KEY_ENV} and {CERT_ENV} go together: the private key (PEM) and its certificate"),
        }
    }

    /// A key of one's own: `key` (PEM) and `cert` (PEM or DER).
    pub fn own(key: &Path, cert: &Path, scratch: &Path) -> Result<Self> {
        ensure_private(key)?;
        let bytes =
            std::fs::read(cert).with_context(|| format!("failed to read the certificate {}", cert.display()))?;
        if bytes.starts_with(b"-----BEGIN") {
            return Ok(Self { key: key.to_path_buf(), cert: cert.to_path_buf() });
        }
        std::fs::create_dir_all(scratch).with_context(|| format!("failed to create {}", scratch.display()))?;
        let pem = scratch.join("certificate.pem");
        let mut convert = openssl();
        convert.args(["x509", "-inform", "DER", "-in"]).arg(cert).arg("-out").arg(&pem);
        output_of(&mut convert)
            .with_context(|| format!("{} is a certificate in neither PEM nor DER", cert.display()))?;
        Ok(Self { key: key.to_path_buf(), cert: pem })
    }

    /// The key in `folder`, generated there first if it has none.
    pub fn in_folder(folder: &Path) -> Result<Self> {
        let key = Self { key: folder.join(KEY_FILE), cert: folder.join(CERT_FILE) };
        if !key.key.exists() {
            key.generate(folder)?;
        }
        ensure_private(&key.key)?;
        ensure!(key.cert.is_file(), "{} has no certificate {}", folder.display(), key.cert.display());
        Ok(key)
    }

    /// A new RSA 2048 key and its self-signed certificate (SHA-256), the
    /// folder made readable by its owner only, the key written with mode
    /// 0600 before a byte of it is.
    fn generate(&self, folder: &Path) -> Result<()> {
        std::fs::DirBuilder::new()
            .recursive(true)
            .mode(0o700)
            .create(folder)
            .with_context(|| format!("failed to create {}", folder.display()))?;
        ensure!(
            find_in_path("openssl").is_some(),
            "making your Secure Boot key needs `openssl`, which is not on the PATH: install it (Debian and Ubuntu: \
             `sudo apt-get install openssl`), or give a key of your own with --key and --cert"
        );
        eprintln!("image: making your own Secure Boot key in {} (openssl, RSA 2048)", folder.display());
        let scratch_key = folder.join(format!("{KEY_FILE}.partial"));
        let scratch_cert = folder.join(format!("{CERT_FILE}.partial"));
        let _ = std::fs::remove_file(&scratch_key);
        std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .mode(0o600)
            .open(&scratch_key)
            .and_then(|mut file| file.flush())
            .with_context(|| format!("failed to create {}", scratch_key.display()))?;
        let mut generate = openssl();
        generate
            .args(["req", "-x509", "-newkey", "rsa:2048", "-sha256", "-nodes", "-days", "36500", "-subj"])
            .arg(format!("/CN=polylab Secure Boot key of {}", owner()))
            .arg("-keyout")
            .arg(&scratch_key)
            .arg("-out")
            .arg(&scratch_cert);
        // Quiet: openssl's progress dots say nothing.
        output_of(&mut generate).context("failed to make the Secure Boot key")?;
        ensure_private(&scratch_key)?;
        std::fs::rename(&scratch_cert, &self.cert)
            .with_context(|| format!("failed to write {}", self.cert.display()))?;
        std::fs::rename(&scratch_key, &self.key).with_context(|| format!("failed to write {}", self.key.display()))
    }

    /// The certificate in DER, as it goes onto the image (MokManager
    /// enrolls DER).
    pub fn certificate_der(&self) -> Result<Vec<u8>> {
        let scratch = tempfile::NamedTempFile::new().context("failed to create a temporary file")?;
        let mut convert = openssl();
        convert.args(["x509", "-outform", "DER", "-in"]).arg(&self.cert).arg("-out").arg(scratch.path());
        output_of(&mut convert).with_context(|| format!("failed to read the certificate {}", self.cert.display()))?;
        std::fs::read(scratch.path()).context("failed to read the DER certificate")
    }
}

/// The folder of the user's generated key: `$XDG_CONFIG_HOME/polylab/secure-boot`,
/// else `~/.config/polylab/secure-boot`.
pub fn key_folder() -> Result<PathBuf> {
    let config = match (std::env::var_os("XDG_CONFIG_HOME"), std::env::var_os("HOME")) {
        (Some(config), _) if Path::new(&config).is_absolute() => PathBuf::from(config),
        (_, Some(home)) => Path::new(&home).join(".config"),
        _ => bail!("neither XDG_CONFIG_HOME nor HOME is set: no folder to keep the Secure Boot key in"),
    };
    Ok(config.join("polylab").join("secure-boot"))
}

/// The SHA-256 fingerprint of a DER certificate, as `openssl x509
/// -fingerprint -sha256` prints it (`AB:CD:...`).
pub fn fingerprint(der: &[u8]) -> String {
    Sha256::digest(der).iter().map(|byte| format!("{byte:02X}")).collect::<Vec<_>>().join(":")
}

/// Fails unless only its owner may read `key`.
fn ensure_private(key: &Path) -> Result<()> {
    let mode = std::fs::metadata(key)
        .with_context(|| format!("failed to read the private key {}", key.display()))?
        .permissions()
        .mode();
    ensure!(
        mode & 0o077 == 0,
        "the private key {} can be read by others (mode {:o}); make it its owner's only: chmod 600 {}",
        key.display(),
        mode & 0o777,
        key.display()
    );
    Ok(())
}

fn openssl() -> Command {
    Command::new("openssl")
}

/// Who the key is for, for its certificate's name: `user@host`.
fn owner() -> String {
    let user = std::env::var("USER").or_else(|_| std::env::var("LOGNAME")).unwrap_or_else(|_| "user".to_string());
    let host = std::fs::read_to_string("/etc/hostname").map(|host| host.trim().to_string()).unwrap_or_default();
    if host.is_empty() {
        user
    } else {
        format!("{user}@{host}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_new_key_is_private_and_kept_and_its_certificate_reads_as_der() {
        let dir = tempfile::tempdir().unwrap();
        let folder = dir.path().join("polylab/secure-boot");
        let key = SigningKey::in_folder(&folder).unwrap();
        assert_eq!(std::fs::metadata(&key.key).unwrap().permissions().mode() & 0o777, 0o600);
        assert_eq!(std::fs::metadata(&folder).unwrap().permissions().mode() & 0o777, 0o700);
        let der = key.certificate_der().unwrap();
        assert_eq!(der[0], 0x30, "a DER SEQUENCE");
        let again = SigningKey::in_folder(&folder).unwrap();
        assert_eq!(again.certificate_der().unwrap(), der, "the second build keeps the key");
        let own = SigningKey::own(&key.key, &key.cert, dir.path()).unwrap();
        assert_eq!(own.cert, key.cert, "a PEM certificate is taken as it is");
        let der_file = dir.path().join("cert.der");
        std::fs::write(&der_file, &der).unwrap();
        let converted = SigningKey::own(&key.key, &der_file, &dir.path().join("scratch")).unwrap();
        assert_eq!(converted.certificate_der().unwrap(), der, "a DER certificate is converted");
    }

    #[test]
    fn a_key_others_can_read_is_refused_with_the_fix() {
        let dir = tempfile::tempdir().unwrap();
        let key = dir.path().join("k.pem");
        std::fs::write(&key, "-----BEGIN PRIVATE KEY-----\n").unwrap();
        std::fs::set_permissions(&key, std::fs::Permissions::from_mode(0o644)).unwrap();
        let error = SigningKey::own(&key, &key, dir.path()).unwrap_err().to_string();
        assert!(error.contains("can be read by others (mode 644)"), "{error}");
        assert!(error.ends_with(&format!("chmod 600 {}", key.display())), "{error}");
    }

    #[test]
    fn fingerprints_are_colon_separated_upper_hex() {
        assert_eq!(
            fingerprint(b"abc"),
            "BA:78:16:BF:8F:01:CF:EA:41:41:40:DE:5D:AE:22:23:B0:03:61:A3:96:17:7A:9C:B4:10:FF:61:F2:00:15:AD"
        );
    }
}
