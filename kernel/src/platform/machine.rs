//! Which machine the kernel runs on, found without writing a single port
//! it has not identified: two read-only signs, both of which QEMU gives.
//!
//! - The CPU: CPUID leaf 1 says in ECX bit 31 that a hypervisor is there,
//!   and leaf 0x4000_0000 then names it in EBX, ECX, EDX: QEMU's own CPU
//!   emulator (TCG) says `TCGTCGTCGTCG`, KVM (under QEMU or another
//!   monitor) `KVMKVMKVM\0\0\0`. A PC's CPU has bit 31 clear.
//! - The board: QEMU gives the PCI devices it emulates, its host bridge at
//!   00:00.0 among them, Red Hat's subsystem vendor 1af4 and its own
//!   subsystem 1100 ("QEMU virtual machine"). A PC's host bridge has its
//!   maker's, or none.
//!
//! Both must agree: the CPU alone cannot tell QEMU from another monitor
//! under KVM, the board alone could be any machine copying QEMU's IDs.
//! Only on QEMU does the kernel answer `EXIT` and `FAULT` and write QEMU's
//! exit port (`exit.rs`). Bochs 2.7 shows neither sign (no hypervisor bit
//! on its CPU models, no subsystem IDs on its host bridge), so there the
//! kernel is on an unknown machine, as on a PC.

use core::arch::x86_64::__cpuid;

use protocol::{Machine, MachineEvidence, PciAddress, PciId};
use spin::Once;

use crate::platform::pci;

/// CPUID leaf 1, ECX bit 31: a hypervisor is present.
const HYPERVISOR_PRESENT: u32 = 1 << 31;
/// The leaf that names the hypervisor.
const HYPERVISOR_LEAF: u32 = 0x4000_0000;
/// The names QEMU's CPUs give: its emulator's, and KVM's.
const QEMU_HYPERVISORS: [&[u8; 12]; 2] = [b"TCGTCGTCGTCG", b"KVMKVMKVM\0\0\0"];
const HOST_BRIDGE: PciAddress = PciAddress { bus: 0, device: 0, function: 0 };
/// QEMU's subsystem vendor (Red Hat) and subsystem ID.
const QEMU_SUBSYSTEM: PciId = PciId { vendor: 0x1af4, device: 0x1100 };

/// What [`identify`] found, and the signs it went by.
pub struct Identity {
    pub machine: Machine,
    /// The hypervisor's name from CPUID, if the CPU says there is one.
    hypervisor: Option<[u8; 12]>,
    /// The host bridge's subsystem IDs, if it has a device header.
    board: Option<PciId>,
}

static IDENTITY: Once<Machine> = Once::new();

/// Looks at the CPU and the host bridge, once; later calls return the
/// first answer.
pub fn identify() -> Identity {
    let hypervisor = hypervisor_name();
    let board = pci::subsystem(HOST_BRIDGE);
    let is_qemu = hypervisor.is_some_and(|name| QEMU_HYPERVISORS.contains(&&name)) && board == Some(QEMU_SUBSYSTEM);
    let machine = *IDENTITY.call_once(|| if is_qemu { Machine::Qemu } else { Machine::Unknown });
    Identity { machine, hypervisor, board }
}

/// The machine [`identify`] found; unknown before it ran.
pub fn current() -> Machine {
    IDENTITY.get().copied().unwrap_or(Machine::Unknown)
}

/// The hypervisor's 12-byte name, if CPUID says there is one.
fn hypervisor_name() -> Option<[u8; 12]> {
    if __cpuid(1).ecx & HYPERVISOR_PRESENT == 0 {
        return None;
    }
    let leaf = __cpuid(HYPERVISOR_LEAF);
    let mut name = [0; 12];
    for (chunk, register) in name.as_chunks_mut::<4>().0.iter_mut().zip([leaf.ebx, leaf.ecx, leaf.edx]) {
        *chunk = register.to_le_bytes();
    }
    Some(name)
}

impl Identity {
    /// What was seen, for the `LOG` frame at boot: `machine: qemu (CPUID
    /// hypervisor "TCGTCGTCGTCG", host bridge subsystem 1af4:1100)`.
    pub fn evidence(&self) -> MachineEvidence {
        MachineEvidence { machine: self.machine, hypervisor: self.hypervisor, board: self.board }
    }
}
