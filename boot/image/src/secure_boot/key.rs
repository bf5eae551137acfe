//! A Secure Boot key of the user's own, for `--enroll key` (the default,
//! `--enroll hash`, needs none): one enrollment that lasts across builds,
//! at the price of a secret kept on disk.
//!
//! Never a key shipped with the project: whoever holds the private half of
//! a key a PC trusts can boot anything on it. So the key is the user's,
//! made on the first build that asks for it and kept outside `target/` (so
//! that `cargo clean` does not force a new enrollment), and never stored
//! in the clear: the private key is encrypted under a passphrase (AES-256),
//! which `openssl` asks for on the terminal or [`PASSPHRASE_ENV`] gives;
//! signing decrypts it into memory only and hands it to `sbsign` through a
//! pipe. A key given with [`KEY_ENV`] (or `--key`) must be encrypted too.
//!
//! Its certificate is made for this one job: not a CA, key usage
//! digitalSignature, extended key usage codeSigning, a subject with a
//! random identifier (no user or host name), valid for [`VALIDITY_DAYS`].
//! shim ignores the validity (its verification sets OpenSSL's "no time
//! check" flag and accepts expired certificates), so the dates protect
//! nothing on a PC; the build refuses to sign with an expired certificate,
//! which makes the key one of a year and asks for a new one after.

use std::io::{Read, Write};
use std::os::unix::fs::{DirBuilderExt, OpenOptionsExt, PermissionsExt};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use anyhow::{bail, ensure, Context, Result};
use sha2::{Digest, Sha256};

use install::process::{command_line, find_in_path, output_of};

/// A private key (PEM, encrypted) to sign with instead of the generated one; needs [`CERT_ENV`].
pub const KEY_ENV: &str = "POLYLAB_SECURE_BOOT_KEY";
/// Its certificate (PEM or DER).
pub const CERT_ENV: &str = "POLYLAB_SECURE_BOOT_CERT";
/// The key's passphrase, when no one is at a terminal to type it.
pub const PASSPHRASE_ENV: &str = "POLYLAB_SECURE_BOOT_PASSPHRASE";

/// How long the generated certificate is valid, in days.
pub const VALIDITY_DAYS: u32 = 365;

/// The generated key's files in the key folder.
const KEY_FILE: &str = "polylab-loader-signing.key";
const CERT_FILE: &str = "polylab-loader-signing.crt";
/// The key earlier builds made: unencrypted, a CA, valid for a century.
const OLD_KEY_FILE: &str = "polylab-secure-boot.key";
const OLD_CERT_FILE: &str = "polylab-secure-boot.crt";

/// The certificate's profile, an `openssl req` configuration of its own
/// (the host's openssl.cnf would add its CA extensions); `{id}` is the
/// random identifier.
const CERTIFICATE_CONFIG: &str = "[req]
prompt = no
distinguished_name = subject
x509_extensions = loader_signing

[subject]
CN = polylab loader signing key {id}

[loader_signing]
basicConstraints = critical, CA:FALSE
keyUsage = critical, digitalSignature
extendedKeyUsage = codeSigning
subjectKeyIdentifier = hash
";

/// A key and its certificate, as the image build signs with them.
#[derive(Clone, PartialEq, Eq)]
pub struct SigningKey {
    /// The private key, PEM, encrypted.
    pub key: PathBuf,
    /// The certificate, PEM.
    pub cert: PathBuf,
    /// The passphrase, if not to be asked for on the terminal.
    passphrase: Option<String>,
}

impl std::fmt::Debug for SigningKey {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SigningKey").field("key", &self.key).field("cert", &self.cert).finish_non_exhaustive()
    }
}

impl SigningKey {
    /// The key named by [`KEY_ENV`] and [`CERT_ENV`] if set, else the
    /// user's generated key, made now if there is none; the passphrase
    /// from [`PASSPHRASE_ENV`] if set. A certificate given in DER is
    /// converted into `scratch`.
    pub fn users(scratch: &Path) -> Result<Self> {
        let passphrase = std::env::var(PASSPHRASE_ENV).ok();
        match (std::env::var_os(KEY_ENV), std::env::var_os(CERT_ENV)) {
            (Some(key), Some(cert)) => Self::own(Path::new(&key), Path::new(&cert), passphrase, scratch),
            (None, None) => Self::in_folder(&key_folder()?, passphrase),
            _ => bail!("{KEY_ENV} and {CERT_ENV} go together: the private key (PEM) and its certificate"),
        }
    }

    /// A key of one's own: `key` (PEM, encrypted) and `cert` (PEM or DER).
    pub fn own(key: &Path, cert: &Path, passphrase: Option<String>, scratch: &Path) -> Result<Self> {
        ensure_private(key)?;
        ensure_encrypted(key)?;
        let bytes =
            std::fs::read(cert).with_context(|| format!("failed to read the certificate {}", cert.display()))?;
        if bytes.starts_with(b"-----BEGIN") {
            return Ok(Self { key: key.to_path_buf(), cert: cert.to_path_buf(), passphrase });
        }
        std::fs::create_dir_all(scratch).with_context(|| format!("failed to create {}", scratch.display()))?;
        let pem = scratch.join("certificate.pem");
        let mut convert = openssl();
        convert.args(["x509", "-inform", "DER", "-in"]).arg(cert).arg("-out").arg(&pem);
        output_of(&mut convert)
            .with_context(|| format!("{} is a certificate in neither PEM nor DER", cert.display()))?;
        Ok(Self { key: key.to_path_buf(), cert: pem, passphrase })
    }

    /// The key in `folder`, generated there first if it has none.
    pub fn in_folder(folder: &Path, passphrase: Option<String>) -> Result<Self> {
        let key = Self { key: folder.join(KEY_FILE), cert: folder.join(CERT_FILE), passphrase };
        if !key.key.exists() {
            key.generate(folder)?;
        }
        ensure_private(&key.key)?;
        ensure_encrypted(&key.key)?;
        ensure!(key.cert.is_file(), "{} has no certificate {}", folder.display(), key.cert.display());
        Ok(key)
    }

    /// A new RSA 2048 key, encrypted, and its self-signed certificate
    /// (SHA-256, [`CERTIFICATE_CONFIG`]), the folder made readable by its
    /// owner only, the key written with mode 0600 before a byte of it is.
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
        eprintln!(
            "image: making your own Secure Boot key in {} (openssl, RSA 2048, encrypted under a passphrase{})",
            folder.display(),
            if self.passphrase.is_some() {
                format!(" from {PASSPHRASE_ENV}")
            } else {
                ", which openssl asks for".into()
            }
        );
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
        generate.args(["genpkey", "-algorithm", "RSA", "-pkeyopt", "rsa_keygen_bits:2048", "-aes-256-cbc", "-out"]);
        generate.arg(&scratch_key);
        self.pass_passphrase(&mut generate, "-pass");
        run_at_terminal(&mut generate).context("failed to make the Secure Boot key")?;
        let config = tempfile::NamedTempFile::new().context("failed to create a temporary file")?;
        std::fs::write(config.path(), CERTIFICATE_CONFIG.replace("{id}", &random_id()?))
            .context("failed to write the certificate's profile")?;
        let mut certify = openssl();
        certify.args(["req", "-new", "-x509", "-sha256", "-days", &VALIDITY_DAYS.to_string(), "-config"]);
        certify.arg(config.path()).arg("-key").arg(&scratch_key).arg("-out").arg(&scratch_cert);
        self.pass_passphrase(&mut certify, "-passin");
        run_at_terminal(&mut certify).context("failed to make the Secure Boot key's certificate")?;
        ensure_private(&scratch_key)?;
        std::fs::rename(&scratch_cert, &self.cert)
            .with_context(|| format!("failed to write {}", self.cert.display()))?;
        std::fs::rename(&scratch_key, &self.key).with_context(|| format!("failed to write {}", self.key.display()))
    }

    /// Gives `command` (an openssl command, its arguments written) the
    /// passphrase by `option` (`-pass`, `-passin`) from its own
    /// environment, if there is one; else openssl asks.
    fn pass_passphrase(&self, command: &mut Command, option: &str) {
        if let Some(passphrase) = &self.passphrase {
            command.env(PASSPHRASE_ENV, passphrase).arg(option).arg(format!("env:{PASSPHRASE_ENV}"));
        }
    }

    /// The private key decrypted (PEM), in memory only.
    pub fn decrypted(&self) -> Result<Vec<u8>> {
        let mut decrypt = openssl();
        decrypt.arg("pkey").arg("-in").arg(&self.key);
        self.pass_passphrase(&mut decrypt, "-passin");
        let line = command_line(&decrypt);
        let output = decrypt
            .stdin(Stdio::inherit())
            .stderr(Stdio::inherit())
            .output()
            .with_context(|| format!("failed to start `{line}`"))?;
        ensure!(
            output.status.success(),
            "`{line}` could not decrypt the Secure Boot key {} ({}): type its passphrase at a terminal, or set \
             {PASSPHRASE_ENV}",
            self.key.display(),
            output.status
        );
        Ok(output.stdout)
    }

    /// Fails if the certificate has expired: shim would not mind, but the
    /// build signs with a key of a year only ([`VALIDITY_DAYS`]).
    pub fn ensure_current(&self) -> Result<()> {
        let mut check = openssl();
        check.args(["x509", "-noout", "-checkend", "0", "-in"]).arg(&self.cert);
        let line = command_line(&check);
        let status = check.output().with_context(|| format!("failed to start `{line}`"))?.status;
        ensure!(
            status.success(),
            "the certificate {} has expired, and the build signs with current keys only. Make a new key (remove \
             {} and {}; the next build makes one), enroll its certificate, and remove the old one from the MOK \
             list: every loader it signed boots until then (`sudo mokutil --delete {}`)",
            self.cert.display(),
            self.key.display(),
            self.cert.display(),
            self.cert.display()
        );
        Ok(())
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

/// Runs `command` with the terminal at hand (openssl asks for a
/// passphrase there), failing unless it succeeds.
fn run_at_terminal(command: &mut Command) -> Result<()> {
    let line = command_line(command);
    let output = command.stdin(Stdio::inherit()).output().with_context(|| format!("failed to start `{line}`"))?;
    ensure!(
        output.status.success(),
        "`{line}` failed with {}: {} (with no terminal to type a passphrase at, set {PASSPHRASE_ENV})",
        output.status,
        String::from_utf8_lossy(&output.stderr).trim()
    );
    Ok(())
}

/// 16 random hex digits, the certificate's identifier.
fn random_id() -> Result<String> {
    let mut bytes = [0u8; 8];
    std::fs::File::open("/dev/urandom")
        .and_then(|mut random| random.read_exact(&mut bytes))
        .context("failed to read /dev/urandom")?;
    Ok(bytes.iter().map(|byte| format!("{byte:02x}")).collect())
}

/// Says so if the key folder still holds the key earlier builds made
/// (whatever the build enrolls: that key is on disk all the same).
pub fn warn_of_old_key() {
    let Ok(folder) = key_folder() else { return };
    if folder.join(OLD_KEY_FILE).exists() {
        eprintln!(
            "image: {} is the key earlier builds made: a CA valid for 100 years, not encrypted. Nothing uses it \
             now; remove it (rm {0} {}) and its certificate from the MOK list of every PC that enrolled it \
             (`sudo mokutil --delete {1}`): until then every loader it signed boots there",
            folder.join(OLD_KEY_FILE).display(),
            folder.join(OLD_CERT_FILE).display()
        );
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

/// Fails unless `key` is a PEM private key encrypted under a passphrase
/// (PKCS #8's `ENCRYPTED PRIVATE KEY`, or the older `Proc-Type: 4,ENCRYPTED`).
fn ensure_encrypted(key: &Path) -> Result<()> {
    let text = std::fs::read_to_string(key).with_context(|| format!("failed to read {}", key.display()))?;
    ensure!(
        text.contains("-----BEGIN ENCRYPTED PRIVATE KEY-----") || text.contains("Proc-Type: 4,ENCRYPTED"),
        "the private key {} is not encrypted: anything that runs as you could read it and sign loaders your PCs \
         boot. Encrypt it under a passphrase (`openssl pkey -in {0} -aes-256-cbc -out {0}.encrypted`, then use \
         that file and remove this one), or use the default `--enroll hash`, which needs no key",
        key.display()
    );
    Ok(())
}

fn openssl() -> Command {
    Command::new("openssl")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn test_key(folder: &Path) -> SigningKey {
        SigningKey::in_folder(folder, Some("a passphrase for the tests".into())).unwrap()
    }

    #[test]
    fn a_new_key_is_encrypted_private_and_kept_and_its_certificate_reads_as_der() {
        let dir = tempfile::tempdir().unwrap();
        let folder = dir.path().join("polylab/secure-boot");
        let key = test_key(&folder);
        assert_eq!(std::fs::metadata(&key.key).unwrap().permissions().mode() & 0o777, 0o600);
        assert_eq!(std::fs::metadata(&folder).unwrap().permissions().mode() & 0o777, 0o700);
        assert!(std::fs::read_to_string(&key.key).unwrap().starts_with("-----BEGIN ENCRYPTED PRIVATE KEY-----"));
        assert!(String::from_utf8(key.decrypted().unwrap()).unwrap().starts_with("-----BEGIN PRIVATE KEY-----"));
        let wrong = SigningKey { passphrase: Some("another".into()), ..key.clone() };
        assert!(wrong.decrypted().unwrap_err().to_string().contains("could not decrypt"));
        let der = key.certificate_der().unwrap();
        assert_eq!(der[0], 0x30, "a DER SEQUENCE");
        let again = test_key(&folder);
        assert_eq!(again.certificate_der().unwrap(), der, "the second build keeps the key");
        let own = SigningKey::own(&key.key, &key.cert, None, dir.path()).unwrap();
        assert_eq!(own.cert, key.cert, "a PEM certificate is taken as it is");
        let der_file = dir.path().join("cert.der");
        std::fs::write(&der_file, &der).unwrap();
        let converted = SigningKey::own(&key.key, &der_file, None, &dir.path().join("scratch")).unwrap();
        assert_eq!(converted.certificate_der().unwrap(), der, "a DER certificate is converted");
    }

    #[test]
    fn the_certificate_is_for_signing_code_only_names_no_one_and_is_valid_for_a_year() {
        let dir = tempfile::tempdir().unwrap();
        let key = test_key(dir.path());
        let text = output_of(openssl().args(["x509", "-noout", "-text", "-in"]).arg(&key.cert)).unwrap();
        assert!(text.contains("X509v3 Basic Constraints: critical\n                CA:FALSE"), "{text}");
        assert!(text.contains("X509v3 Key Usage: critical\n                Digital Signature\n"), "{text}");
        assert!(text.contains("X509v3 Extended Key Usage: \n                Code Signing\n"), "{text}");
        let subject = text.lines().find(|line| line.trim_start().starts_with("Subject:")).unwrap();
        let id = subject.trim().strip_prefix("Subject: CN = polylab loader signing key ").unwrap();
        assert!(id.len() == 16 && id.chars().all(|c| c.is_ascii_hexdigit()), "{subject}");
        let user = std::env::var("USER").unwrap_or_else(|_| "root".into());
        assert!(!text.contains(&format!("of {user}")), "{subject}");
        let other = test_key(&dir.path().join("other"));
        let other_text = output_of(openssl().args(["x509", "-noout", "-subject", "-in"]).arg(&other.cert)).unwrap();
        assert!(!other_text.contains(id), "two keys, one identifier");
        let in_a_year = output_of(openssl().args(["x509", "-noout", "-checkend", "31449600", "-in"]).arg(&key.cert));
        let after_a_year = openssl().args(["x509", "-noout", "-checkend", "31622400", "-in"]).arg(&key.cert).output();
        assert!(in_a_year.is_ok() && !after_a_year.unwrap().status.success(), "valid for 364 days, not 366");
        key.ensure_current().unwrap();
    }

    #[test]
    fn a_key_others_can_read_or_in_the_clear_is_refused_with_the_fix() {
        let dir = tempfile::tempdir().unwrap();
        let key = dir.path().join("k.pem");
        std::fs::write(&key, "-----BEGIN PRIVATE KEY-----\n").unwrap();
        std::fs::set_permissions(&key, std::fs::Permissions::from_mode(0o644)).unwrap();
        let error = SigningKey::own(&key, &key, None, dir.path()).unwrap_err().to_string();
        assert!(error.contains("can be read by others (mode 644)"), "{error}");
        assert!(error.ends_with(&format!("chmod 600 {}", key.display())), "{error}");
        std::fs::set_permissions(&key, std::fs::Permissions::from_mode(0o600)).unwrap();
        let error = SigningKey::own(&key, &key, None, dir.path()).unwrap_err().to_string();
        assert!(error.contains("is not encrypted"), "{error}");
        assert!(error.contains("-aes-256-cbc"), "{error}");
    }

    #[test]
    fn fingerprints_are_colon_separated_upper_hex() {
        assert_eq!(
            fingerprint(b"abc"),
            "BA:78:16:BF:8F:01:CF:EA:41:41:40:DE:5D:AE:22:23:B0:03:61:A3:96:17:7A:9C:B4:10:FF:61:F2:00:15:AD"
        );
    }
}
