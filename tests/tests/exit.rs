//! Leaving QEMU: on request with the requested code, and on every fault
//! with a FATAL report and the failure code.

use std::time::Duration;

use anyhow::{ensure, Result};
use harness::{Qemu, QemuOptions, Reply};
use protocol::{qemu_status, Command, FaultKind, EXIT_FAILURE as FAILED, EXIT_SUCCESS as SUCCESS};

/// Longest wait for QEMU to exit once the kernel has asked it to.
const EXIT_TIMEOUT: Duration = Duration::from_secs(30);

#[test]
fn exit_16_leaves_qemu_with_status_33() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    qemu.console.send(&Command::Exit(SUCCESS))?;
    let status = qemu.wait_exit(EXIT_TIMEOUT)?;
    ensure!(status.code() == Some(qemu_status(SUCCESS)), "QEMU exited with {status}, expected 33");
    Ok(())
}

/// Provokes `kind`, expects a FATAL frame whose text starts with `named`
/// (so the right handler caught it), then QEMU's exit with the failure
/// status (35).
fn fault_is_reported_and_fails(kind: FaultKind, named: &str) -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    match qemu.console.request(&Command::Fault(kind))? {
        Reply::Fatal(text) => {
            ensure!(text.starts_with(named), "FAULT {} reported \"{text}\", expected \"{named}...\"", kind.name())
        }
        other => anyhow::bail!("FAULT {} answered {other:?}, expected FATAL", kind.name()),
    }
    let status = qemu.wait_exit(EXIT_TIMEOUT)?;
    ensure!(
        status.code() == Some(qemu_status(FAILED)),
        "QEMU exited with {status} after FAULT {}, expected 35",
        kind.name()
    );
    Ok(())
}

#[test]
fn breakpoint_is_reported_and_exits_with_status_35() -> Result<()> {
    fault_is_reported_and_fails(FaultKind::Breakpoint, "breakpoint")
}

#[test]
fn page_fault_is_reported_and_exits_with_status_35() -> Result<()> {
    fault_is_reported_and_fails(FaultKind::PageFault, "page fault")
}

#[test]
fn double_fault_is_reported_and_exits_with_status_35() -> Result<()> {
    fault_is_reported_and_fails(FaultKind::DoubleFault, "double fault")
}

#[test]
fn panic_is_reported_and_exits_with_status_35() -> Result<()> {
    fault_is_reported_and_fails(FaultKind::Panic, "panic")
}
