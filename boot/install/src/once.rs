//! Work done once per process (installing, building) whose outcome, success
//! or failure, every later caller shares.

use std::sync::OnceLock;

use anyhow::{anyhow, Result};

/// Runs `work` the first time, and hands every caller its result. Callers
/// arriving while it runs wait for it, so parallel tests never start two
/// builds. A failure is kept as its full message (`{:#}`).
pub fn once_per_process<T: Clone>(cell: &OnceLock<Result<T, String>>, work: impl FnOnce() -> Result<T>) -> Result<T> {
    cell.get_or_init(|| work().map_err(|error| format!("{error:#}"))).clone().map_err(|message| anyhow!(message))
}
