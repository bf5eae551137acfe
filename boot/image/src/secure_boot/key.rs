//! A Secure Boot key of the user's own, for `--enroll key` (the default,
//! `--enroll hash`, needs none): one enrollment that lasts across builds,
//! at the price of a secret kept on disk.
//!
//! Never a key shipped with the project: whoever holds the private half of
//! a key a PC trusts can boot anything on it. So the key is the user's,
//! made on the first build that asks for it and kept outside `target/` (so
//! that `cargo clean` does not force a new enrollment), and never stored
//! in the clear: the private key is encrypted under a passphrase (AES-256),
//! which the build asks for once on the terminal (a new key's twice, to
//! catch a typing slip), or reads from a file only its owner can read
//! ([`passphrase_from_file`], `--passphrase-file`), or [`PASSPHRASE_ENV`]
//! gives; every `openssl` that needs it reads it from a pipe on its
//! standard input. The variable is taken out of the environment before
//! any child starts ([`take_passphrase`]), so no child (cargo, apt-get,
//! dpkg-deb, sbsign) inherits it; but the process's own first environment
//! block (`/proc/PID/environ`) and that of every process above it (the
//! shell, `cargo run`) still hold it: the file and the terminal never put
//! it in an environment. Signing decrypts the key into memory only and
//! hands it to `sbsign` through a pipe. A key given with [`KEY_ENV`] (or
//! `--key`) must be encrypted too.
//!
//! Its certificate is made for this one job: not a CA, key usage
//! digitalSignature, extended key usage codeSigning, a subject with a
//! random identifier (no user or host name), valid for [`VALIDITY_DAYS`].
//! shim ignores the validity (its verification sets OpenSSL's "no time
//! check" flag and accepts expired certificates), so the dates protect
//! nothing on a PC; the build refuses to sign with an expired certificate,
//! which makes the key one of a year and asks for a new one after.

use std::io::{Read, Write};
use std::os::unix::fs::{DirBuilderExt, MetadataExt, OpenOptionsExt, PermissionsExt};
use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{bail, ensure, Context, Result};
use sha2::{Digest, Sha256};

use install::{command_line, find_in_path, output_of, output_with_input};

/// A private key (PEM, encrypted) to sign with instead of the generated one; needs [`CERT_ENV`].
pub const KEY_ENV: &str = "POLYLAB_SECURE_BOOT_KEY";
/// Its certificate (PEM or DER).
pub const CERT_ENV: &str = "POLYLAB_SECURE_BOOT_CERT";
/// The key's passphrase, when no one is at a terminal to type it (a file,
/// [`passphrase_from_file`], keeps it out of every environment).
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
    /// The key's passphrase, given or asked for once.
    passphrase: String,
}

impl std::fmt::Debug for SigningKey {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SigningKey").field("key", &self.key).field("cert", &self.cert).finish_non_exhaustive()
    }
}

impl SigningKey {
    /// The key named by [`KEY_ENV`] and [`CERT_ENV`] if set, else the
    /// user's generated key, made now if there is none; the passphrase
    /// given, else asked for on the terminal. A certificate given in DER
    /// is converted into `scratch`.
    pub fn users(scratch: &Path, passphrase: Option<String>) -> Result<Self> {
        match (std::env::var_os(KEY_ENV), std::env::var_os(CERT_ENV)) {
            (Some(key), Some(cert)) => Self::own(Path::new(&key), Path::new(&cert), passphrase, scratch),
            (None, None) => Self::in_folder(&key_folder()?, passphrase),
            _ => bail!("{KEY_ENV} and {CERT_ENV} go together: the private key (PEM) and its certificate"),
        }
    }

    /// A key of one's own: `key` (PEM, encrypted) and `cert` (PEM or DER);
    /// the passphrase asked for on the terminal unless given.
    pub fn own(key: &Path, cert: &Path, passphrase: Option<String>, scratch: &Path) -> Result<Self> {
        ensure_private(key)?;
        ensure_encrypted(key)?;
        let passphrase = match passphrase {
            Some(passphrase) => passphrase,
            None => ask_at_terminal(&format!("Passphrase of the Secure Boot key {}: ", key.display()))?,
        };
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

    /// The key in `folder`, generated there first if it has none; the
    /// passphrase asked for on the terminal unless given.
    pub fn in_folder(folder: &Path, passphrase: Option<String>) -> Result<Self> {
        Self::in_folder_asking(folder, passphrase, &mut ask_at_terminal)
    }

    /// [`Self::in_folder`], asking with `ask` (a prompt in, the answer
    /// out): once for a key that is there, twice (the same question and
    /// its confirmation) for a new one.
    fn in_folder_asking(
        folder: &Path,
        passphrase: Option<String>,
        ask: &mut dyn FnMut(&str) -> Result<String>,
    ) -> Result<Self> {
        let (key, cert) = (folder.join(KEY_FILE), folder.join(CERT_FILE));
        let new = !key.exists();
        let passphrase = match passphrase {
            Some(passphrase) => passphrase,
            None if new => {
                let first = ask(&format!("A passphrase for your new Secure Boot key in {}: ", folder.display()))?;
                let again = ask("The same passphrase again: ")?;
                ensure!(first == again, "the two passphrases differ; nothing was made");
                first
            }
            None => ask(&format!("Passphrase of your Secure Boot key {}: ", key.display()))?,
        };
        ensure!(!passphrase.is_empty(), "the Secure Boot key's passphrase is empty");
        let signing = Self { key, cert, passphrase };
        if new {
            signing.generate(folder)?;
        }
        ensure_private(&signing.key)?;
        ensure_encrypted(&signing.key)?;
        ensure!(signing.cert.is_file(), "{} has no certificate {}", folder.display(), signing.cert.display());
        Ok(signing)
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
            "image: making your own Secure Boot key in {} (openssl, RSA 2048, encrypted under your passphrase)",
            folder.display()
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
        generate.arg(&scratch_key).args(["-pass", "stdin"]);
        self.run_with_passphrase(&mut generate).context("failed to make the Secure Boot key")?;
        let config = tempfile::NamedTempFile::new().context("failed to create a temporary file")?;
        std::fs::write(config.path(), CERTIFICATE_CONFIG.replace("{id}", &random_id()?))
            .context("failed to write the certificate's profile")?;
        let mut certify = openssl();
        certify.args(["req", "-new", "-x509", "-sha256", "-days", &VALIDITY_DAYS.to_string(), "-config"]);
        certify.arg(config.path()).arg("-key").arg(&scratch_key).arg("-out").arg(&scratch_cert);
        certify.args(["-passin", "stdin"]);
        self.run_with_passphrase(&mut certify).context("failed to make the Secure Boot key's certificate")?;
        ensure_private(&scratch_key)?;
        std::fs::rename(&scratch_cert, &self.cert)
            .with_context(|| format!("failed to write {}", self.cert.display()))?;
        std::fs::rename(&scratch_key, &self.key).with_context(|| format!("failed to write {}", self.key.display()))
    }

    /// Runs `command` (an openssl command reading the passphrase with
    /// `stdin`) with the passphrase written to its standard input, and
    /// returns its standard output; fails unless it succeeds.
    fn run_with_passphrase(&self, command: &mut Command) -> Result<Vec<u8>> {
        output_with_input(command, format!("{}\n", self.passphrase).as_bytes())
    }

    /// The private key decrypted (PEM), in memory only.
    pub fn decrypted(&self) -> Result<Vec<u8>> {
        let mut decrypt = openssl();
        decrypt.arg("pkey").arg("-in").arg(&self.key).args(["-passin", "stdin"]);
        self.run_with_passphrase(&mut decrypt).with_context(|| {
            format!(
                "could not decrypt the Secure Boot key {} (a wrong passphrase?): type it again, or give it with \
                 --passphrase-file (or {PASSPHRASE_ENV})",
                self.key.display()
            )
        })
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

/// The passphrase in [`PASSPHRASE_ENV`], taken out of this process's
/// environment the first time (so that no child started after inherits
/// it), and kept for every later call. `cargo xtask` calls it first thing,
/// before any thread or child starts.
pub fn take_passphrase() -> Option<String> {
    static TAKEN: std::sync::OnceLock<Option<String>> = std::sync::OnceLock::new();
    TAKEN
        .get_or_init(|| {
            let passphrase = std::env::var(PASSPHRASE_ENV).ok();
            std::env::remove_var(PASSPHRASE_ENV);
            passphrase
        })
        .clone()
}

/// The passphrase in the file `path`, its one line (a final newline is
/// not part of it): the file must be a regular file, not a symlink
/// (`O_NOFOLLOW`), owned by the user running the build and readable and
/// writable by that user only (mode 0600 or 0400); anything else is
/// refused with the fix.
pub fn passphrase_from_file(path: &Path) -> Result<String> {
    let mut file = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NOFOLLOW)
        .open(path)
        .with_context(|| format!("failed to open the passphrase file {} (a symlink is refused)", path.display()))?;
    let metadata = file.metadata().with_context(|| format!("failed to read {}", path.display()))?;
    ensure!(metadata.is_file(), "the passphrase file {} is not a file", path.display());
    let owner = install::user_id();
    ensure!(
        Some(metadata.uid()) == owner,
        "the passphrase file {} belongs to user {}, not to the user running the build: refusing a passphrase \
         another user could have written",
        path.display(),
        metadata.uid()
    );
    let mode = metadata.permissions().mode() & 0o777;
    ensure!(
        mode & 0o077 == 0,
        "the passphrase file {} can be read or written by others (mode {mode:o}); make it its owner's only: chmod \
         600 {}",
        path.display(),
        path.display()
    );
    let mut passphrase = String::new();
    file.read_to_string(&mut passphrase).with_context(|| format!("failed to read {}", path.display()))?;
    let passphrase = passphrase.strip_suffix('\n').unwrap_or(&passphrase).to_string();
    ensure!(!passphrase.is_empty(), "the passphrase file {} is empty", path.display());
    Ok(passphrase)
}

/// Asks for a passphrase on the terminal, not echoing it.
fn ask_at_terminal(prompt: &str) -> Result<String> {
    rpassword::prompt_password(prompt).with_context(|| {
        format!(
            "no terminal to ask for the Secure Boot key's passphrase at: give it with --passphrase-file (or \
                 {PASSPHRASE_ENV})"
        )
    })
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
        let wrong = SigningKey { passphrase: "another".into(), ..key.clone() };
        assert!(wrong.decrypted().unwrap_err().to_string().contains("could not decrypt"));
        let der = key.certificate_der().unwrap();
        assert_eq!(der[0], 0x30, "a DER SEQUENCE");
        let again = test_key(&folder);
        assert_eq!(again.certificate_der().unwrap(), der, "the second build keeps the key");
        let given = Some("a passphrase for the tests".to_string());
        let own = SigningKey::own(&key.key, &key.cert, given.clone(), dir.path()).unwrap();
        assert_eq!(own.cert, key.cert, "a PEM certificate is taken as it is");
        let der_file = dir.path().join("cert.der");
        std::fs::write(&der_file, &der).unwrap();
        let converted = SigningKey::own(&key.key, &der_file, given, &dir.path().join("scratch")).unwrap();
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
        let error = SigningKey::own(&key, &key, Some("p".into()), dir.path()).unwrap_err().to_string();
        assert!(error.contains("can be read by others (mode 644)"), "{error}");
        assert!(error.ends_with(&format!("chmod 600 {}", key.display())), "{error}");
        std::fs::set_permissions(&key, std::fs::Permissions::from_mode(0o600)).unwrap();
        let error = SigningKey::own(&key, &key, Some("p".into()), dir.path()).unwrap_err().to_string();
        assert!(error.contains("is not encrypted"), "{error}");
        assert!(error.contains("-aes-256-cbc"), "{error}");
    }

    #[test]
    fn a_passphrase_file_is_read_only_if_it_is_the_users_alone() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("passphrase");
        std::fs::write(&file, "a secret\n").unwrap();
        std::fs::set_permissions(&file, std::fs::Permissions::from_mode(0o600)).unwrap();
        assert_eq!(passphrase_from_file(&file).unwrap(), "a secret", "one line, its newline left out");
        std::fs::set_permissions(&file, std::fs::Permissions::from_mode(0o640)).unwrap();
        let error = passphrase_from_file(&file).unwrap_err().to_string();
        assert!(error.contains("by others (mode 640)") && error.ends_with(&format!("chmod 600 {}", file.display())));
        std::fs::set_permissions(&file, std::fs::Permissions::from_mode(0o600)).unwrap();
        let link = dir.path().join("link");
        std::os::unix::fs::symlink(&file, &link).unwrap();
        let error = format!("{:#}", passphrase_from_file(&link).unwrap_err());
        assert!(error.contains("a symlink is refused"), "{error}");
        if install::is_root() {
            std::os::unix::fs::chown(&file, Some(65534), None).unwrap();
            let error = passphrase_from_file(&file).unwrap_err().to_string();
            assert!(error.contains("belongs to user 65534, not to the user running the build"), "{error}");
            std::os::unix::fs::chown(&file, Some(0), None).unwrap();
        }
        std::fs::write(&file, "\n").unwrap();
        let error = passphrase_from_file(&file).unwrap_err().to_string();
        assert!(error.contains("is empty"), "{error}");
    }

    #[test]
    fn fingerprints_are_colon_separated_upper_hex() {
        assert_eq!(
            fingerprint(b"abc"),
            "BA:78:16:BF:8F:01:CF:EA:41:41:40:DE:5D:AE:22:23:B0:03:61:A3:96:17:7A:9C:B4:10:FF:61:F2:00:15:AD"
        );
    }

    #[test]
    fn a_first_key_build_asks_for_the_passphrase_once_and_confirms_it_and_a_later_one_once() {
        let dir = tempfile::tempdir().unwrap();
        let asked = std::cell::RefCell::new(Vec::new());
        let mut ask = |prompt: &str| {
            asked.borrow_mut().push(prompt.to_string());
            Ok("typed once".to_string())
        };
        let key = SigningKey::in_folder_asking(dir.path(), None, &mut ask).unwrap();
        let signing = key.decrypted().unwrap();
        assert!(String::from_utf8(signing).unwrap().starts_with("-----BEGIN PRIVATE KEY-----"));
        let first: Vec<String> = asked.take();
        assert_eq!(first.len(), 2, "{first:?}");
        assert!(first[0].starts_with("A passphrase for your new") && first[1].starts_with("The same"), "{first:?}");
        let again = SigningKey::in_folder_asking(dir.path(), None, &mut ask).unwrap();
        again.decrypted().unwrap();
        again.certificate_der().unwrap();
        assert_eq!(asked.take().len(), 1, "a later build asks once");
        let mut slip = |prompt: &str| Ok(if prompt.starts_with("The same") { "typo" } else { "typed" }.to_string());
        let error = SigningKey::in_folder_asking(&dir.path().join("other"), None, &mut slip).unwrap_err();
        assert!(error.to_string().contains("differ"), "{error}");
    }

    /// Set in the copy of this test binary the test below starts.
    const CHILD: &str = "PASSPHRASE_TEST_CHILD";

    #[test]
    fn the_passphrase_leaves_the_environment_before_any_child_starts() {
        if std::env::var_os(CHILD).is_some() {
            assert_eq!(take_passphrase().as_deref(), Some("a secret"));
            let env = output_of(&mut Command::new("env")).unwrap();
            assert!(!env.contains(PASSPHRASE_ENV), "a child inherits {PASSPHRASE_ENV}");
            assert_eq!(take_passphrase().as_deref(), Some("a secret"), "kept for later calls");
            return;
        }
        let name = "secure_boot::key::tests::the_passphrase_leaves_the_environment_before_any_child_starts";
        let child = Command::new(std::env::current_exe().unwrap())
            .args(["--exact", name, "--test-threads=1"])
            .env(CHILD, "1")
            .env(PASSPHRASE_ENV, "a secret")
            .output()
            .unwrap();
        let printed = String::from_utf8_lossy(&child.stdout);
        assert!(child.status.success() && printed.contains("1 passed"), "{printed}");
    }
}
