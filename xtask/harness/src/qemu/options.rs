//! What a QEMU run is asked for: the firmware, the medium, the display
//! card and whether a person watches, the clock, where COM1 goes, the CPU
//! and the exit device ([`QemuOptions`]); `arguments.rs` turns them into
//! QEMU's command line.

use anyhow::{Context, Result};
use install::Step;
use install::{ensure_ovmf, ensure_qemu, ensure_qemu_qxl, ensure_qemu_window, ensure_secure_boot_ovmf};
use protocol::{Firmware, PciId};

use super::board::{Board, DisplayAhead};

/// How the image is attached.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Medium {
    /// The first IDE disk, as a PC's hard disk.
    #[default]
    Disk,
    /// A USB stick (usb-storage on an xHCI controller): the rehearsal for
    /// `dd`-ing the image onto a real stick.
    UsbStick,
}

/// Whether a person watches.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Display {
    #[default]
    Headless,
    /// A window on the user's desktop (QEMU's default display backend).
    Window,
}

/// The display card QEMU emulates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Adapter {
    /// QEMU's standard VGA, with the Bochs "dispi" VBE extension.
    #[default]
    Std,
    /// A Cirrus Logic GD5446: a real card's design, whose extended
    /// registers keep a VBE mode the standard ones cannot undo.
    Cirrus,
    /// The VMware SVGA II adapter.
    Vmware,
    /// QXL (SPICE's card) with its VGA core and the Bochs VBE interface.
    QxlVga,
    /// virtio-gpu with a VGA core and the Bochs VBE interface.
    VirtioVga,
    /// An ATI Rage 128 Pro, a real card's VGA core (no UEFI driver in OVMF).
    AtiVga,
    /// The Bochs display interface without a VGA core (PCI class 03/80,
    /// the std VGA's PCI IDs): only a framebuffer.
    BochsDisplay,
    /// A framebuffer in guest RAM the firmware sets up: no PCI device, no
    /// VGA.
    Ramfb,
    /// virtio-gpu without a VGA core (class 03/80): OVMF's driver for it
    /// offers only a BltOnly mode, no framebuffer the kernel can draw in.
    VirtioGpu,
    /// No display card at all.
    None,
}

impl Adapter {
    /// Every card, in the order `--vga` lists them.
    pub const ALL: [Adapter; 10] = [
        Adapter::Std,
        Adapter::Cirrus,
        Adapter::Vmware,
        Adapter::QxlVga,
        Adapter::VirtioVga,
        Adapter::AtiVga,
        Adapter::BochsDisplay,
        Adapter::Ramfb,
        Adapter::VirtioGpu,
        Adapter::None,
    ];

    /// Whether the adapter matrix proves the picture (or, with `None` and
    /// `VirtioGpu`, the boot) on this card under `firmware`: SeaBIOS's VGA
    /// BIOSes put the VGA-compatible cards in text mode; OVMF has a
    /// graphics driver for the first five and for bochs-display and ramfb
    /// (none for ati-vga), a BltOnly one for virtio-gpu, and with no card
    /// it shows nothing.
    pub fn proven_under(self, firmware: Firmware) -> bool {
        match self {
            Adapter::Std | Adapter::Cirrus | Adapter::Vmware | Adapter::QxlVga | Adapter::VirtioVga => true,
            Adapter::AtiVga | Adapter::None => firmware == Firmware::Bios,
            // virtio-gpu: the boot with no framebuffer (a BltOnly mode).
            Adapter::BochsDisplay | Adapter::Ramfb | Adapter::VirtioGpu => firmware == Firmware::Uefi,
        }
    }

    /// The card's name for `--vga` (QEMU's device name where it has one).
    pub fn name(self) -> &'static str {
        match self {
            Adapter::Std => "std",
            Adapter::Cirrus => "cirrus",
            Adapter::Vmware => "vmware",
            Adapter::QxlVga => "qxl-vga",
            Adapter::VirtioVga => "virtio-vga",
            Adapter::AtiVga => "ati-vga",
            Adapter::BochsDisplay => "bochs-display",
            Adapter::Ramfb => "ramfb",
            Adapter::VirtioGpu => "virtio-gpu",
            Adapter::None => "none",
        }
    }

    /// The card called `name`; otherwise an error listing them.
    pub fn named(name: &str) -> Result<Adapter> {
        Adapter::ALL.into_iter().find(|adapter| adapter.name() == name).with_context(|| {
            let valid: Vec<&str> = Adapter::ALL.iter().map(|adapter| adapter.name()).collect();
            format!("unknown display adapter `{name}`; the adapters are {}", valid.join(", "))
        })
    }

    /// QEMU's flags for the card: `-vga` for the cards it knows by that
    /// flag; otherwise no built-in card and the card as a `-device`.
    pub(super) fn qemu_flags(self) -> [&'static str; 2] {
        match self {
            Adapter::Std => ["-vga", "std"],
            Adapter::Cirrus => ["-vga", "cirrus"],
            Adapter::Vmware => ["-vga", "vmware"],
            Adapter::QxlVga => ["-vga", "qxl"],
            Adapter::VirtioVga => ["-vga", "virtio"],
            Adapter::AtiVga => ["-device", "ati-vga"],
            Adapter::BochsDisplay => ["-device", "bochs-display"],
            Adapter::Ramfb => ["-device", "ramfb"],
            Adapter::VirtioGpu => ["-device", "virtio-gpu-pci"],
            Adapter::None => ["-vga", "none"],
        }
    }

    /// QEMU's device for the card on the PCI bus, which `-device` can put
    /// at a slot of one's choosing; `None` for ramfb and no card.
    pub(super) fn pci_device(self) -> Option<&'static str> {
        match self {
            Adapter::Std => Some("VGA"),
            Adapter::Cirrus => Some("cirrus-vga"),
            Adapter::Vmware => Some("vmware-svga"),
            Adapter::QxlVga => Some("qxl-vga"),
            Adapter::VirtioVga => Some("virtio-vga"),
            Adapter::AtiVga => Some("ati-vga"),
            Adapter::BochsDisplay => Some("bochs-display"),
            Adapter::VirtioGpu => Some("virtio-gpu-pci"),
            Adapter::Ramfb | Adapter::None => None,
        }
    }

    /// The PCI IDs QEMU gives the card (as `lspci -n` shows them in a
    /// guest), which the kernel reports in READY; `None` for no card and
    /// for ramfb, which is not on the PCI bus.
    pub fn pci_id(self) -> Option<PciId> {
        let (vendor, device) = match self {
            Adapter::Std | Adapter::BochsDisplay => (0x1234, 0x1111),
            Adapter::Cirrus => (0x1013, 0x00b8),
            Adapter::Vmware => (0x15ad, 0x0405),
            Adapter::QxlVga => (0x1b36, 0x0100),
            Adapter::VirtioVga | Adapter::VirtioGpu => (0x1af4, 0x1050),
            Adapter::AtiVga => (0x1002, 0x5046),
            Adapter::Ramfb | Adapter::None => return None,
        };
        Some(PciId { vendor, device })
    }
}

/// What the guest's clocks (the PIT, rdtsc) follow.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum TimeBase {
    /// The host's time: the demo plays at its real pace, and rdtsc counts
    /// host time spent emulating, which moves with the host's load.
    #[default]
    RealTime,
    /// Executed instructions: the virtual clock, and with it rdtsc, steps
    /// one nanosecond (one tick) per emulated instruction, whatever the
    /// host does, so the kernel's figures repeat exactly from run to run.
    /// For measuring; the demo's pacing then follows instructions too.
    InstructionCount,
}

/// Where COM1, the protocol line, reaches the harness.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SerialLine {
    /// QEMU's standard input and output, pipes to the harness: [`Qemu::console`].
    #[default]
    Stdio,
    /// A pseudo-terminal QEMU makes ([`Qemu::pty`]): a tty device that a
    /// program opens as it would a real serial port. [`Qemu::console`]
    /// then hears nothing.
    Pty,
    /// A telnet server on TCP port `port` of 127.0.0.1 (0: [`Qemu::spawn`]
    /// picks a free one): the one QEMU backend that carries a break (IAC
    /// BRK, bytes 255 243, which QEMU turns into a break on the UART's
    /// receiving end). A data byte 255 must be sent twice.
    Telnet { port: u16 },
}

/// What QEMU's CPU tells the guest about itself.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Cpu {
    /// QEMU's default CPU, which says a hypervisor runs it (CPUID leaf 1,
    /// ECX bit 31) and names it (`TCGTCGTCGTCG`).
    #[default]
    Default,
    /// The same CPU with CPUID's hypervisor bit clear: from the CPU, a
    /// guest cannot tell it runs under QEMU.
    WithoutHypervisorBit,
}

/// Whether QEMU has its exit device (`isa-debug-exit`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ExitDevice {
    #[default]
    Present,
    /// None: a kernel's write to its port goes nowhere, as on a PC.
    Absent,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct QemuOptions {
    pub firmware: Firmware,
    pub medium: Medium,
    pub display: Display,
    pub adapter: Adapter,
    pub clock: TimeBase,
    pub serial: SerialLine,
    /// With `Firmware::Uefi`: OVMF's Secure Boot build on the q35 machine
    /// (it needs SMM), its variable store Microsoft's keys with Secure Boot
    /// on unless the run is given another ([`Qemu::spawn_with_variables`]).
    pub secure_boot: bool,
    /// A guest reboot restarts the machine (MokManager reboots after
    /// enrolling a key) instead of ending QEMU.
    pub allow_reboot: bool,
    /// COM1's IRQ line if not its standard 4: the UART then interrupts on
    /// a line the kernel does not listen to.
    pub com1_irq: Option<u8>,
    pub cpu: Cpu,
    pub exit_device: ExitDevice,
    /// A display controller with no legacy VGA ranges ahead of the card
    /// in bus order, and the card (a PCI one) in slot 5, where
    /// screendumps are taken of it ([`Qemu::screendump_ahead`] takes the
    /// one ahead).
    pub display_ahead: Option<DisplayAhead>,
    pub board: Board,
    /// An ACPI HPET table of the run's own, placing the HPET's registers
    /// at this physical address (on a board without QEMU's HPET, whose own
    /// table it would stand beside): how a firmware's wrong table is
    /// played.
    pub hpet_table_at: Option<u64>,
    /// An ACPI MADT of the run's own, one more beside QEMU's, listing one
    /// I/O APIC with its registers at this physical address: how a
    /// firmware's wrong or hostile table is played.
    pub io_apic_table_at: Option<u32>,
}

impl QemuOptions {
    /// What a run with these options needs installed, in order, for
    /// `install::ensure_all` (a user who is not root is told
    /// every missing package at once): QEMU; its window; its QXL card; OVMF
    /// under UEFI; OVMF's Secure Boot build.
    pub fn needs(&self) -> Vec<Step> {
        let mut needs: Vec<Step> = vec![ensure_qemu];
        if self.display == Display::Window {
            needs.push(ensure_qemu_window);
        }
        if self.adapter == Adapter::QxlVga {
            needs.push(ensure_qemu_qxl);
        }
        if self.firmware == Firmware::Uefi {
            needs.push(ensure_ovmf);
        }
        if self.secure_boot {
            needs.push(ensure_secure_boot_ovmf);
        }
        needs
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cards_are_found_by_name_and_others_refused_with_the_list() {
        for adapter in Adapter::ALL {
            assert_eq!(Adapter::named(adapter.name()).unwrap(), adapter);
        }
        for name in ["qxl", "virtio", ""] {
            let error = Adapter::named(name).unwrap_err().to_string();
            assert_eq!(
                error,
                format!(
                    "unknown display adapter `{name}`; the adapters are std, cirrus, vmware, qxl-vga, virtio-vga, \
                     ati-vga, bochs-display, ramfb, virtio-gpu, none"
                )
            );
        }
    }

    #[test]
    fn the_matrix_covers_every_card_under_one_firmware_or_the_other() {
        for adapter in Adapter::ALL {
            let proven = Firmware::ALL.into_iter().any(|firmware| adapter.proven_under(firmware));
            assert!(proven, "{adapter:?} is proven under no firmware");
        }
    }
}
