//! Running child processes the way the installs, the builds, the harness
//! and the xtask want them: the exact command line printed first, failure
//! turned into an error that says which command failed.

use std::ffi::OsStr;
use std::io::Write;
use std::process::{Command, Stdio};

use anyhow::{bail, Context, Result};

/// The command as a person would type it: program, then arguments, each
/// quoted when the shell would need it. Environment changes are not shown.
pub fn command_line(command: &Command) -> String {
    std::iter::once(command.get_program()).chain(command.get_args()).map(shell_word).collect::<Vec<_>>().join(" ")
}

fn shell_word(word: &OsStr) -> String {
    let word = word.to_string_lossy();
    let plain = !word.is_empty() && word.chars().all(|c| c.is_ascii_alphanumeric() || "-_./=:,+@%".contains(c));
    if plain {
        word.into_owned()
    } else {
        format!("'{}'", word.replace('\'', r"'\''"))
    }
}

/// Prints `command`, runs it with inherited standard streams (so its output
/// streams to the user) and fails unless it exits successfully.
pub fn run_streaming(command: &mut Command) -> Result<()> {
    let line = command_line(command);
    eprintln!("running {line}");
    let status = command.status().with_context(|| format!("failed to start `{line}`"))?;
    if !status.success() {
        bail!("`{line}` failed with {status}");
    }
    Ok(())
}

/// Runs `command` quietly and returns its standard output, failing (with
/// its standard error) unless it exits successfully. For look-ups, not for
/// work the user should watch.
pub fn output_of(command: &mut Command) -> Result<String> {
    let line = command_line(command);
    let output = command.output().with_context(|| format!("failed to start `{line}`"))?;
    if !output.status.success() {
        bail!("`{line}` failed with {}: {}", output.status, String::from_utf8_lossy(&output.stderr).trim());
    }
    String::from_utf8(output.stdout).with_context(|| format!("`{line}` printed something that is not UTF-8"))
}

/// Runs `command` quietly with `input` written to its standard input (a
/// secret that must not reach its arguments or environment) and returns
/// its standard output, failing (with its standard error) unless it exits
/// successfully having read all of `input`.
pub fn output_with_input(command: &mut Command, input: &[u8]) -> Result<Vec<u8>> {
    let line = command_line(command);
    let mut child = command
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .with_context(|| format!("failed to start `{line}`"))?;
    let mut stdin = child.stdin.take().with_context(|| format!("the standard input of `{line}`"))?;
    let written = stdin.write_all(input);
    drop(stdin);
    let output = child.wait_with_output().with_context(|| format!("failed to wait for `{line}`"))?;
    if !output.status.success() || written.is_err() {
        bail!("`{line}` failed with {}: {}", output.status, String::from_utf8_lossy(&output.stderr).trim());
    }
    Ok(output.stdout)
}

/// Whether this process runs as root (`id -u` says 0).
pub fn is_root() -> bool {
    user_id() == Some(0)
}

/// The user this process runs as (`id -u`).
pub fn user_id() -> Option<u32> {
    output_of(Command::new("id").arg("-u")).ok()?.trim().parse().ok()
}

/// The first `program` on the `PATH`.
pub fn find_in_path(program: &str) -> Option<std::path::PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path).map(|dir| dir.join(program)).find(|candidate| candidate.is_file())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn command_lines_quote_only_what_the_shell_needs() {
        let mut command = Command::new("qemu-system-x86_64");
        command.args(["-drive", "format=raw,file=/tmp/a b.img", "-m", "128M", "it's", ""]);
        assert_eq!(
            command_line(&command),
            r"qemu-system-x86_64 -drive 'format=raw,file=/tmp/a b.img' -m 128M 'it'\''s' ''"
        );
    }
}
