//! Interrupts nobody asked for, as a real PC sends them: an NMI (a
//! chipset's SERR# or IOCHK#, a BMC, a watchdog) while the show plays;
//! interrupts on vectors the kernel does not use, across the range,
//! raised through the local APIC as a device would raise them; a device's
//! IRQ through the 8259s; the kernel's own vectors arriving through the
//! local APIC; and a level-triggered source that storms. Each must be
//! counted, ended where it is in service, and logged, and the kernel must
//! carry on.

use std::time::Duration;

use anyhow::{bail, ensure, Context, Result};
use harness::checks::distinct_screens;
use harness::{Qemu, QemuOptions};
use protocol::{Command, EndedAt, FaultKind, InterruptCounts, LogEvent, MaskedAt, Raised, StrayRaised};

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

/// Sends `FAULT kind` and expects it answered `expected`.
fn raise(qemu: &mut Qemu, kind: FaultKind, expected: StrayRaised) -> Result<()> {
    let command = Command::Fault(kind);
    let raised = StrayRaised::parse(&qemu.console.ok(&command)?)?;
    ensure!(raised == expected, "`{command}` answered {raised:?}, expected {expected:?}");
    Ok(())
}

/// Vectors across the range the IDT's stray handler covers: its bottom,
/// 0x21 (0x20 is the PIT's, 0x24 COM1's), and its top, 0xff (most
/// firmware's spurious vector), the 8259s' last (0x2f), and either side
/// of the local APIC's priority classes in between.
const SPREAD: [u8; 9] = [0x21, 0x2f, 0x30, 0x5f, 0x80, 0x99, 0xbf, 0xfe, 0xff];

/// `FAULT strayinterrupt VECTOR` twice for each vector of [`SPREAD`]:
/// each time the kernel sends it to itself through the local APIC, takes
/// it, answers `OK` and logs it; the second can only arrive if the first
/// got its end of interrupt (the local APIC holds back every vector of a
/// class still in service). `PING` then counts them all.
#[test]
fn stray_interrupts_across_the_vectors_are_counted_ended_and_logged_not_fatal() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    for vector in SPREAD {
        for taken in 1..=2 {
            raise(
                &mut qemu,
                FaultKind::StrayInterrupt(vector),
                StrayRaised { vector, raised: Raised::LocalApic, taken },
            )?;
        }
    }
    let pong = qemu.console.pong()?;
    let stray = 2 * SPREAD.len() as u32;
    ensure!(
        pong.interrupts == Some(InterruptCounts { nmis: 0, stray }),
        "PING after {stray} stray interrupts counts {:?}",
        pong.interrupts
    );
    for vector in SPREAD {
        let event = LogEvent::StrayInterrupt { vector, count: 2, ended: EndedAt::LocalApic };
        ensure!(qemu.console.logs().contains(&event), "no LOG {event:?}: {:?}", qemu.console.logs());
    }
    Ok(())
}

/// `FAULT strayirq` twice: the RTC's IRQ 8 let through the two 8259s
/// (vector 0x28, the slave's first) arrives, is ended at the 8259s and
/// logged so; the second can only arrive if the first got its end of
/// interrupt at both (an 8259 holds back every IRQ of its priority or
/// lower while one is in service).
#[test]
fn an_irq_through_the_8259s_is_counted_and_ended_there() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    for taken in 1..=2 {
        raise(&mut qemu, FaultKind::StrayIrq, StrayRaised { vector: 0x28, raised: Raised::Pic, taken })?;
    }
    qemu.console.ping()?;
    let event = LogEvent::StrayInterrupt { vector: 0x28, count: 2, ended: EndedAt::Pic };
    ensure!(qemu.console.logs().contains(&event), "no LOG {event:?}: {:?}", qemu.console.logs());
    Ok(())
}

/// The PIT's and COM1's own vectors (0x20, 0x24) sent through the local
/// APIC, as an I/O APIC entry the firmware left live would send them: their
/// handlers must end them there too, not only at the 8259, or they stay in
/// service and hold back their whole priority class (0x20 to 0x2f) for
/// good. A vector of that class sent after each arrives only if so.
#[test]
fn the_pits_and_com1s_vectors_sent_through_the_local_apic_are_ended_there() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    for (own, after) in [(0x24, 0x21), (0x20, 0x2f)] {
        // Their own handlers count no stray interrupt: 0 taken.
        raise(
            &mut qemu,
            FaultKind::StrayInterrupt(own),
            StrayRaised { vector: own, raised: Raised::LocalApic, taken: 0 },
        )?;
        let expected = StrayRaised { vector: after, raised: Raised::LocalApic, taken: 1 };
        raise(&mut qemu, FaultKind::StrayInterrupt(after), expected)
            .with_context(|| format!("after vector {own:#04x} came through the local APIC"))?;
    }
    Ok(())
}

/// `FAULT interruptstorm`: the RTC's IRQ 8 routed level-triggered through
/// the I/O APIC, its line left high, comes again after every end of
/// interrupt; the kernel must count it, mask it at the I/O APIC (1,000
/// arrivals within 100 ms, `kernel/src/interrupts/storm.rs`) long before the command
/// gives up and stops the RTC, say so in a `LOG` frame, and serve on, the
/// vector silent from then on.
#[test]
fn a_storming_vector_is_masked_at_its_source_and_the_kernel_serves_on() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    let command = Command::Fault(FaultKind::InterruptStorm);
    let raised = StrayRaised::parse(&qemu.console.ok(&command)?)?;
    ensure!(raised.vector == 0x9a && raised.raised == Raised::IoApicLevel, "`{command}` answered {raised:?}");
    // The guard's 1,000, and a few more before the mask took: not the
    // hundreds of thousands the storm brings before the command gives up
    // after 2 s and stops the RTC itself.
    ensure!((1000..2000).contains(&raised.taken), "{} interrupts came in the storm: it was not stopped", raised.taken);
    let before = qemu.console.pong()?.interrupts;
    std::thread::sleep(Duration::from_secs(1));
    let after = qemu.console.pong()?.interrupts;
    ensure!(before == after, "the storm goes on: PING counted {before:?}, then {after:?}");
    let stopped = qemu.console.logs().iter().any(|log| {
        matches!(log, LogEvent::InterruptStorm { vector: 0x9a, masked: MaskedAt::IoApic { interrupt: 8 }, .. })
    });
    ensure!(stopped, "no LOG says the storm was masked at the I/O APIC: {:?}", qemu.console.logs());
    Ok(())
}

/// Which refusal an I/O APIC's address must meet.
type RefusedAs = fn(&protocol::IoApicRefusal) -> bool;

/// A firmware's MADT naming an I/O APIC where none can be, played by one
/// more MADT of the test's own beside QEMU's: in RAM (16 MiB, which the
/// memory map gives the kernel or its loader), off the 16-byte boundary
/// its registers start on (QEMU's I/O APIC plus 4), and where nothing
/// answers (QEMU reads 0 there, a version of 0). The kernel must refuse
/// the first two before it maps or writes anything there, the third before
/// it uses it, say why in a `LOG` frame each, and carry on: it draws, and
/// the storm of interrupts is still masked at QEMU's own I/O APIC. The
/// control, QEMU's own I/O APIC's address in the extra table, is taken
/// and logs nothing.
#[test]
fn an_io_apic_a_madt_places_in_ram_off_its_boundary_or_where_nothing_answers_is_refused() -> Result<()> {
    use harness::checks::dump_matches_host_render;
    use protocol::IoApicRefusal;
    let not_an_io_apic = |why: &IoApicRefusal| matches!(why, IoApicRefusal::NotAnIoApic { version: 0 });
    let cases: [(u32, Option<RefusedAs>); 4] = [
        (0x100_0000, Some(|why| *why == IoApicRefusal::InRam)),
        (0xfec0_0004, Some(|why| *why == IoApicRefusal::Misaligned)),
        (0xfeb0_0000, Some(not_an_io_apic)),
        (0xfec0_0000, None),
    ];
    for (address, expected) in cases {
        let on = format!("a MADT with an I/O APIC at {address:#x}");
        let mut qemu = Qemu::boot(QemuOptions { io_apic_table_at: Some(address), ..QemuOptions::default() })?;
        let refusals: Vec<&IoApicRefusal> = qemu
            .console
            .logs()
            .iter()
            .filter_map(|log| match log {
                LogEvent::IoApicRefused { address: at, why } if *at == u64::from(address) => Some(why),
                _ => None,
            })
            .collect();
        match expected {
            Some(expected) => ensure!(
                refusals.len() == 1 && expected(refusals[0]),
                "{on}: the LOG frames do not refuse it as expected: {:?}",
                qemu.console.logs()
            ),
            None => ensure!(refusals.is_empty(), "{on}: QEMU's own I/O APIC was refused: {refusals:?}"),
        }
        dump_matches_host_render(&mut qemu.console, "abrash38-1", raster::MethodId::Exact)
            .with_context(|| format!("{on}: the kernel does not draw"))?;
        let raised = StrayRaised::parse(&qemu.console.ok(&Command::Fault(FaultKind::InterruptStorm))?)?;
        ensure!(raised.raised == Raised::IoApicLevel, "{on}: the storm was raised {raised:?}");
        ensure!((1000..2000).contains(&raised.taken), "{on}: {} interrupts came in the storm", raised.taken);
    }
    Ok(())
}
