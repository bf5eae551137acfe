//! Interrupts nobody asked for, as a real PC sends them: an NMI (a
//! chipset's SERR# or IOCHK#, a BMC, a watchdog) while the show plays,
//! and an interrupt on a vector the kernel does not use, raised through
//! the local APIC as a device would raise it. Each must be counted and
//! logged, and the kernel must carry on.

use std::time::Duration;

use anyhow::{bail, ensure, Result};
use harness::checks::distinct_screens;
use harness::{Qemu, QemuOptions};
use protocol::{Command, EndedAt, FaultKind, InterruptCounts, LogEvent, Raised, StrayRaised};

/// How long the show is watched after the NMI, and how often its screen
/// is taken: a still page of the show stays 3 s, so 8 s see at least two
/// entries.
const WATCH: Duration = Duration::from_secs(8);
const WATCH_EVERY: Duration = Duration::from_millis(500);
/// How long after the event the watch starts.
const SETTLE: Duration = Duration::from_secs(1);

/// QMP's `inject-nmi` while the show plays: the show plays on (QEMU shows
/// at least two different screens over 8 s after it), a `LOG` frame
/// names the NMI and what port 0x61 said, and `PING` answers, counting
/// one NMI and no stray interrupt.
#[test]
fn an_nmi_during_the_show_is_counted_and_logged_and_the_show_plays_on() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    std::thread::sleep(Duration::from_secs(1));
    qemu.inject_nmi()?;
    // Whatever it does to the screen at once (the old kernel cleared it)
    // is over by then: the watch is of what follows.
    std::thread::sleep(SETTLE);
    let screens = distinct_screens(&mut qemu, WATCH, WATCH_EVERY)?;
    ensure!(screens >= 2, "after an NMI QEMU showed {screens} screen(s) in {} s: the show is over", WATCH.as_secs());
    let pong = qemu.console.pong()?;
    ensure!(
        pong.interrupts == Some(InterruptCounts { nmis: 1, stray: 0 }),
        "PING after one NMI counts {:?}",
        pong.interrupts
    );
    // QEMU's port 0x61 never sets bit 7 (SERR#) or bit 6 (IOCHK#): the
    // NMI came from QMP, and the kernel must say it found neither.
    let nmis: Vec<&LogEvent> = qemu.console.logs().iter().filter(|log| matches!(log, LogEvent::Nmi { .. })).collect();
    match nmis[..] {
        [LogEvent::Nmi { count: 1, reason, serr, iochk }] => ensure!(
            reason & 0xc0 == 0 && !serr && !iochk,
            "the NMI's LOG reads port 0x61 = {reason:#04x} as SERR# {serr}, IOCHK# {iochk}"
        ),
        _ => bail!("no LOG names the one NMI: {:?}", qemu.console.logs()),
    }
    ensure!(qemu.is_running()?, "QEMU ended after an NMI");
    Ok(())
}

/// `FAULT strayinterrupt` twice: each time the kernel sends vector 0x99
/// to itself through the local APIC, takes it, answers `OK` and logs it;
/// the second can only arrive if the first got its end of interrupt (the
/// local APIC holds back every vector of a class still in service).
/// `PING` then counts two stray interrupts.
#[test]
fn a_stray_interrupt_is_counted_ended_and_logged_not_fatal() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    for taken in 1..=2 {
        let text = qemu.console.ok(&Command::Fault(FaultKind::StrayInterrupt))?;
        let raised = StrayRaised::parse(&text)?;
        let expected = StrayRaised { vector: 0x99, raised: Raised::LocalApic, taken };
        ensure!(raised == expected, "FAULT strayinterrupt answered {raised:?}, expected {expected:?}");
    }
    let pong = qemu.console.pong()?;
    ensure!(
        pong.interrupts == Some(InterruptCounts { nmis: 0, stray: 2 }),
        "PING after two stray interrupts counts {:?}",
        pong.interrupts
    );
    for count in 1..=2 {
        let event = LogEvent::StrayInterrupt { vector: 0x99, count, ended: EndedAt::LocalApic };
        ensure!(qemu.console.logs().contains(&event), "no LOG {event:?}: {:?}", qemu.console.logs());
    }
    Ok(())
}
