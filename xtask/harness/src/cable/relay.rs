//! A bad cable on purpose: a relay between the kernel's tty (QEMU's
//! `-serial pty`) and a pseudo-terminal of its own, whose other end the
//! host opens as it would a real port. Both ways it drops bytes, flips a
//! bit, inserts a random byte and holds the line still for a second, each
//! at its own rate, from a seeded generator; it counts what it did.

use std::io::{ErrorKind, Read, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::Duration;

use anyhow::{Context, Result};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64Mcg;
use serialport::{SerialPort, TTYPort};

use super::tty::{open_port, READ_POLL};
use crate::client::gather_after;

/// How long the relay holds the line still when it pauses.
pub const PAUSE: Duration = Duration::from_secs(1);

/// The chance, per byte carried, of each fault.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaultRates {
    /// The byte is lost.
    pub drop: f64,
    /// One of its bits, at random, is inverted.
    pub flip: f64,
    /// A random byte goes out before it.
    pub insert: f64,
    /// The line stays still for [`PAUSE`] before it.
    pub pause: f64,
}

impl FaultRates {
    /// A clean line.
    pub const NONE: FaultRates = FaultRates { drop: 0.0, flip: 0.0, insert: 0.0, pause: 0.0 };

    /// Drops, flips and inserts each once in `bytes` bytes on average, and
    /// pauses once in `pause_bytes`.
    pub fn one_in(bytes: f64, pause_bytes: f64) -> Self {
        FaultRates { drop: 1.0 / bytes, flip: 1.0 / bytes, insert: 1.0 / bytes, pause: 1.0 / pause_bytes }
    }
}

/// What the relay did to one direction.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FaultCounts {
    pub carried: u64,
    pub dropped: u64,
    pub flipped: u64,
    pub inserted: u64,
    pub paused: u64,
}

impl FaultCounts {
    /// Faults of any kind.
    pub fn faults(&self) -> u64 {
        self.dropped + self.flipped + self.inserted + self.paused
    }
}

#[derive(Default)]
struct Counters {
    carried: AtomicU64,
    dropped: AtomicU64,
    flipped: AtomicU64,
    inserted: AtomicU64,
    paused: AtomicU64,
}

impl Counters {
    fn read(&self) -> FaultCounts {
        let load = |counter: &AtomicU64| counter.load(Ordering::Relaxed);
        FaultCounts {
            carried: load(&self.carried),
            dropped: load(&self.dropped),
            flipped: load(&self.flipped),
            inserted: load(&self.inserted),
            paused: load(&self.paused),
        }
    }
}

/// A running relay; dropping it stops both directions and closes both
/// ttys.
pub struct Relay {
    device: PathBuf,
    stop: Arc<AtomicBool>,
    threads: Vec<JoinHandle<()>>,
    to_host: Arc<Counters>,
    to_kernel: Arc<Counters>,
    /// The host's end stays open here too, so that the pseudo-terminal
    /// lives (and buffers) while the host has not opened it yet.
    _host_end: TTYPort,
}

impl Relay {
    /// Opens `kernel_device` and starts relaying between it and a new
    /// pseudo-terminal ([`Relay::device`]): kernel to host with
    /// `to_host`'s fault rates, host to kernel with `to_kernel`'s, faults
    /// drawn from `seed`.
    pub fn start(kernel_device: &Path, to_host: FaultRates, to_kernel: FaultRates, seed: u64) -> Result<Relay> {
        let kernel = open_port(kernel_device)?;
        let (mut host, host_end) = TTYPort::pair().context("cannot make a pseudo-terminal for the relay")?;
        host.set_timeout(READ_POLL)?;
        let device = PathBuf::from(host_end.name().context("the relay's pseudo-terminal has no name")?);
        let stop = Arc::new(AtomicBool::new(false));
        let counters = (Arc::new(Counters::default()), Arc::new(Counters::default()));
        let directions = [
            (kernel.try_clone_native()?, host.try_clone_native()?, to_host, Arc::clone(&counters.0), seed),
            (host, kernel, to_kernel, Arc::clone(&counters.1), seed ^ 0x9e37_79b9_7f4a_7c15),
        ];
        let threads = directions
            .into_iter()
            .map(|(from, to, rates, counters, seed)| {
                let stop = Arc::clone(&stop);
                std::thread::spawn(move || carry(from, to, rates, &counters, Pcg64Mcg::seed_from_u64(seed), &stop))
            })
            .collect();
        Ok(Relay { device, stop, threads, to_host: counters.0, to_kernel: counters.1, _host_end: host_end })
    }

    /// The tty the host opens.
    pub fn device(&self) -> &Path {
        &self.device
    }

    /// What the relay did so far: kernel to host, and host to kernel.
    pub fn counts(&self) -> (FaultCounts, FaultCounts) {
        (self.to_host.read(), self.to_kernel.read())
    }
}

impl Drop for Relay {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        for thread in self.threads.drain(..) {
            let _ = thread.join();
        }
    }
}

/// Carries bytes from `from` to `to` until `stop`, damaging them at
/// `rates`. A side with nobody on it yet (a pseudo-terminal not opened)
/// reads as an error: it is tried again.
fn carry(
    mut from: TTYPort,
    mut to: TTYPort,
    rates: FaultRates,
    counters: &Counters,
    mut rng: Pcg64Mcg,
    stop: &AtomicBool,
) {
    let mut chunk = vec![0; 4096];
    let mut out = Vec::with_capacity(chunk.len() * 2);
    while !stop.load(Ordering::Relaxed) {
        let n = match from.read(&mut chunk) {
            Ok(n) => n,
            Err(error) if matches!(error.kind(), ErrorKind::TimedOut | ErrorKind::Interrupted) => continue,
            Err(_) => {
                std::thread::sleep(READ_POLL);
                continue;
            }
        };
        out.clear();
        for &byte in &chunk[..n] {
            if rng.random_bool(rates.pause) {
                send(&mut to, &out, stop);
                out.clear();
                std::thread::sleep(PAUSE);
                counters.paused.fetch_add(1, Ordering::Relaxed);
            }
            if rng.random_bool(rates.insert) {
                out.push(rng.random());
                counters.inserted.fetch_add(1, Ordering::Relaxed);
            }
            if rng.random_bool(rates.drop) {
                counters.dropped.fetch_add(1, Ordering::Relaxed);
            } else if rng.random_bool(rates.flip) {
                out.push(byte ^ (1 << rng.random_range(0..8)));
                counters.flipped.fetch_add(1, Ordering::Relaxed);
            } else {
                out.push(byte);
            }
        }
        counters.carried.fetch_add(n as u64, Ordering::Relaxed);
        send(&mut to, &out, stop);
        gather_after(n);
    }
}

/// Writes all of `bytes` to `to`, waiting while it is full (a reader that
/// is slow, or not there yet), until `stop`.
fn send(to: &mut TTYPort, mut bytes: &[u8], stop: &AtomicBool) {
    while !bytes.is_empty() && !stop.load(Ordering::Relaxed) {
        match to.write(bytes) {
            Ok(n) => bytes = &bytes[n..],
            Err(error) if matches!(error.kind(), ErrorKind::TimedOut | ErrorKind::Interrupted) => {}
            Err(_) => std::thread::sleep(READ_POLL),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Instant;

    /// How long a read may wait for bytes that must come: only a relay
    /// that lost them, or hangs, takes this long.
    const PATIENCE: Duration = Duration::from_secs(30);

    /// Reads from `port` until `enough` says the bytes read are all that
    /// should come, or [`PATIENCE`] passed.
    fn read_until(port: &mut TTYPort, mut enough: impl FnMut(&[u8]) -> bool) -> Vec<u8> {
        let (mut bytes, give_up) = (Vec::new(), Instant::now() + PATIENCE);
        let mut chunk = [0; 4096];
        while !enough(&bytes) && Instant::now() < give_up {
            if let Ok(n) = port.read(&mut chunk) {
                bytes.extend_from_slice(&chunk[..n]);
            }
        }
        bytes
    }

    /// Reads from `port` until `len` bytes came, or [`PATIENCE`] passed.
    fn read_some(port: &mut TTYPort, len: usize) -> Vec<u8> {
        read_until(port, |bytes| bytes.len() >= len)
    }

    /// A relay between two pseudo-terminals of the test's: the kernel's
    /// side is one the test holds the other end of.
    fn relay(to_host: FaultRates, to_kernel: FaultRates) -> (Relay, TTYPort, TTYPort) {
        let (kernel_master, kernel_slave) = TTYPort::pair().unwrap();
        let kernel_path = kernel_slave.name().unwrap();
        drop(kernel_slave);
        let relay = Relay::start(Path::new(&kernel_path), to_host, to_kernel, 7).unwrap();
        let host = open_port(relay.device()).unwrap();
        (relay, kernel_master, host)
    }

    #[test]
    fn a_clean_relay_carries_every_byte_both_ways() {
        let (relay, mut kernel, mut host) = relay(FaultRates::NONE, FaultRates::NONE);
        let bytes: Vec<u8> = (0..=255).cycle().take(10_000).collect();
        kernel.write_all(&bytes).unwrap();
        assert_eq!(read_some(&mut host, bytes.len()), bytes);
        host.write_all(b"PING\n").unwrap();
        assert_eq!(read_some(&mut kernel, 5), b"PING\n");
        let (to_host, to_kernel) = relay.counts();
        assert_eq!((to_host.carried, to_host.faults(), to_kernel.carried), (10_000, 0, 5));
    }

    #[test]
    fn a_faulty_relay_damages_each_way_as_often_as_asked_and_counts_it() {
        let (relay, mut kernel, mut host) = relay(FaultRates::one_in(100.0, 1e12), FaultRates::NONE);
        let bytes: Vec<u8> = (0..=255).cycle().take(20_000).collect();
        kernel.write_all(&bytes).unwrap();
        // Once the relay has carried every byte, its counts say how many
        // it sends on: read until that many came.
        let received = read_until(&mut host, |received| {
            let to_host = relay.counts().0;
            to_host.carried == 20_000 && received.len() as u64 >= 20_000 - to_host.dropped + to_host.inserted
        });
        let (to_host, to_kernel) = relay.counts();
        assert_eq!(to_host.carried, 20_000);
        // 20,000 bytes at 1 in 100: about 200 of each, and certainly not 0.
        for (what, count) in
            [("dropped", to_host.dropped), ("flipped", to_host.flipped), ("inserted", to_host.inserted)]
        {
            assert!((100..=300).contains(&count), "{what}: {count}");
        }
        assert_eq!(received.len() as u64, 20_000 - to_host.dropped + to_host.inserted);
        assert_ne!(received, bytes);
        assert_eq!(to_kernel.faults(), 0);
    }

    #[test]
    fn a_pause_holds_the_line_for_a_second() {
        let (relay, mut kernel, mut host) = relay(FaultRates { pause: 1.0, ..FaultRates::NONE }, FaultRates::NONE);
        let started = Instant::now();
        kernel.write_all(b"x").unwrap();
        assert_eq!(read_some(&mut host, 1), b"x");
        assert!(started.elapsed() >= PAUSE);
        assert_eq!(relay.counts().0.paused, 1);
    }
}
