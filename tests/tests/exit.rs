//! Leaving QEMU: on request with the requested code, and on every fault
//! (each by its name) with a FATAL report and the failure code; an NMI
//! after the kernel stopped cleanly reports nothing (one while it runs is
//! counted and survived: `idt.rs`).
//! The kernel answers `EXIT` and `FAULT` only where it has identified
//! QEMU: with CPUID's hypervisor bit hidden it refuses both and touches
//! nothing.

use std::time::{Duration, Instant};

use anyhow::{bail, ensure, Result};
use harness::{Cpu, ExitDevice, Qemu, QemuOptions, Reply};
use protocol::{
    qemu_status, Command, ErrorReply, FatalReport, FaultKind, Machine, EXIT_FAILURE as FAILED, EXIT_SUCCESS as SUCCESS,
};

/// Longest wait for QEMU to exit once the kernel has asked it to.
const EXIT_TIMEOUT: Duration = Duration::from_secs(30);
/// How long a stopped kernel is watched for a frame it must not send.
const QUIET_WATCH: Duration = Duration::from_secs(5);

#[test]
fn exit_16_leaves_qemu_with_status_33() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    ensure!(qemu.ready.machine == Some(Machine::Qemu), "READY names the machine {:?}, not QEMU", qemu.ready.machine);
    qemu.console.send(&Command::Exit(SUCCESS))?;
    let status = qemu.wait_exit(EXIT_TIMEOUT)?;
    ensure!(status.code() == Some(qemu_status(SUCCESS)), "QEMU exited with {status}, expected 33");
    Ok(())
}

/// Provokes `kind`, expects a FATAL frame whose report is `reported`
/// (so the right handler caught it), then QEMU's exit with the failure
/// status (35).
fn fault_is_reported_and_fails(kind: FaultKind, reported: fn(&FatalReport) -> bool) -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    qemu.console.send(&Command::Fault(kind))?;
    let cause = format!("FAULT {}", kind.name());
    match qemu.console.reply()? {
        Reply::Fatal(text) => ensure!(reported(&FatalReport::parse(&text)?), "{cause} reported \"{text}\""),
        other => bail!("{cause} answered {other:?}, expected FATAL"),
    }
    let status = qemu.wait_exit(EXIT_TIMEOUT)?;
    ensure!(status.code() == Some(qemu_status(FAILED)), "QEMU exited with {status} after {cause}, expected 35");
    Ok(())
}

/// On a QEMU without the exit device, as on a PC, `EXIT` leaves the
/// kernel halted for good: an NMI then (a chipset's report after the run
/// ended cleanly) must not turn the clean stop into a FATAL report.
#[test]
fn an_nmi_after_a_clean_stop_reports_nothing() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions { exit_device: ExitDevice::Absent, ..QemuOptions::default() })?;
    qemu.console.send(&Command::Exit(SUCCESS))?;
    // The kernel answers nothing to EXIT: give it a moment to stop.
    std::thread::sleep(Duration::from_secs(1));
    qemu.inject_nmi()?;
    let watched = Instant::now();
    match qemu.console.reply_within(QUIET_WATCH) {
        Ok(reply) => bail!("after EXIT and an NMI the kernel sent {reply:?}"),
        Err(_) if watched.elapsed() >= QUIET_WATCH => {}
        Err(error) => return Err(error.context("the serial line failed while the stopped kernel was watched")),
    }
    ensure!(qemu.is_running()?, "QEMU ended after EXIT and an NMI, with no exit device to end it");
    Ok(())
}

/// With CPUID's hypervisor bit hidden, the kernel cannot tell QEMU from a
/// PC: `READY` says so, and `EXIT` and `FAULT` are refused with nothing
/// touched (QEMU's exit device is there, so a write to its port would end
/// QEMU, and a fault would be reported) and the kernel keeps serving.
#[test]
fn where_qemu_is_not_identified_exit_and_fault_are_refused_and_nothing_is_touched() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions { cpu: Cpu::WithoutHypervisorBit, ..QemuOptions::default() })?;
    ensure!(
        qemu.ready.machine == Some(Machine::Unknown),
        "with the hypervisor bit hidden READY names the machine {:?}",
        qemu.ready.machine
    );
    for command in [Command::Exit(SUCCESS), Command::Fault(FaultKind::Panic), Command::Fault(FaultKind::PageFault)] {
        match qemu.console.request(&command)? {
            Reply::Err(text) if ErrorReply::parse(&text)? == ErrorReply::NotQemu(command.name()) => {}
            other => bail!("`{command}` on an unidentified machine answered {other:?}, expected ERR"),
        }
    }
    let losses = qemu.console.ping()?;
    ensure!(losses.none(), "PING says the serial line lost bytes: {losses}");
    ensure!(qemu.is_running()?, "QEMU ended although EXIT was refused");
    Ok(())
}

#[test]
fn breakpoint_is_reported_and_exits_with_status_35() -> Result<()> {
    fault_is_reported_and_fails(FaultKind::Breakpoint, |report| {
        matches!(report, FatalReport::Exception { vector: 3, error: None, .. })
    })
}

#[test]
fn page_fault_is_reported_and_exits_with_status_35() -> Result<()> {
    fault_is_reported_and_fails(FaultKind::PageFault, |report| {
        // A read (no write, no user, no protection bits) of the kernel's
        // unmapped address, `kernel/src/interrupts/fault.rs`.
        matches!(report, FatalReport::PageFault { address: 0xdeadbeef000, code, .. } if code.bits() == 0)
    })
}

#[test]
fn double_fault_is_reported_and_exits_with_status_35() -> Result<()> {
    fault_is_reported_and_fails(FaultKind::DoubleFault, |report| matches!(report, FatalReport::DoubleFault { .. }))
}

#[test]
fn panic_is_reported_and_exits_with_status_35() -> Result<()> {
    fault_is_reported_and_fails(FaultKind::Panic, |report| matches!(report, FatalReport::Panic(_)))
}

#[test]
fn divide_error_is_reported_and_exits_with_status_35() -> Result<()> {
    fault_is_reported_and_fails(FaultKind::DivideError, |report| {
        matches!(report, FatalReport::Exception { vector: 0, error: None, .. })
    })
}

#[test]
fn invalid_opcode_is_reported_and_exits_with_status_35() -> Result<()> {
    fault_is_reported_and_fails(FaultKind::InvalidOpcode, |report| {
        matches!(report, FatalReport::Exception { vector: 6, error: None, .. })
    })
}
