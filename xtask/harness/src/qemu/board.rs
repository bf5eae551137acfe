//! The machine around the card: the board and its timers, and a display
//! device ahead of the card in bus order (`QemuOptions`).

/// The QEMU id screendumps name the device ahead by.
pub(super) const AHEAD_ID: &str = "ahead";

/// A display controller ahead of the card (`QemuOptions::display_ahead`):
/// class 03/80, the std VGA's PCI IDs, no legacy VGA ranges; OVMF shows
/// its own screen on it, and hands its framebuffer over.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DisplayAhead {
    /// bochs-display in slot 2: only a framebuffer.
    BochsDisplay,
    /// secondary-vga in slot 4: the std VGA without the legacy ranges.
    SecondaryVga,
}

impl DisplayAhead {
    /// Its `-device` value.
    pub(super) fn device(self) -> String {
        match self {
            DisplayAhead::BochsDisplay => format!("bochs-display,addr=02.0,id={AHEAD_ID}"),
            DisplayAhead::SecondaryVga => format!("secondary-vga,addr=04.0,id={AHEAD_ID}"),
        }
    }
}

/// The PC QEMU emulates, and its timers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Board {
    /// The i440FX PC with its 8254 PIT (and HPET, and PIIX4's ACPI PM
    /// timer).
    #[default]
    Pc,
    /// The same without a PIT (`pit=off`), as a "legacy-free" PC: the
    /// HPET and the ACPI PM timer remain.
    PcWithoutPit,
    /// The Q35 (ICH9) PC without a PIT: the ICH9's ACPI PM timer and the
    /// HPET.
    Q35WithoutPit,
    /// The i440FX PC without its HPET (`hpet=off`): no HPET table either.
    PcWithoutHpet,
    /// The i440FX PC without a PIT or an HPET: the ACPI PM timer alone.
    PcWithPmTimerAlone,
}

impl Board {
    /// Its `-machine` value (without a firmware's needs: Secure Boot's
    /// board is its own).
    pub(super) fn machine(self) -> &'static str {
        match self {
            Board::Pc => "pc",
            Board::PcWithoutPit => "pc,pit=off",
            Board::Q35WithoutPit => "q35,pit=off",
            Board::PcWithoutHpet => "pc,hpet=off",
            Board::PcWithPmTimerAlone => "pc,pit=off,hpet=off",
        }
    }
}

/// The body of an ACPI HPET table (what follows the 36-byte header QEMU's
/// `-acpitable` writes), placing an HPET's registers at `address`: the
/// event timer block ID (QEMU's: Intel's vendor ID, 3 comparators, 64-bit
/// counter, legacy replacement capable, revision 1), the base address as a
/// generic address in system memory, HPET number 0, a minimum tick of 128,
/// no page protection (the IA-PC HPET specification, "ACPI table").
pub(super) fn hpet_table_body(address: u64) -> Vec<u8> {
    let mut body = 0x8086_A201u32.to_le_bytes().to_vec();
    body.extend([0, 64, 0, 0]);
    body.extend(address.to_le_bytes());
    body.push(0);
    body.extend(128u16.to_le_bytes());
    body.push(0);
    body
}

/// The file [`hpet_table_body`] is written to for a run.
pub(super) const HPET_TABLE_FILE: &str = "hpet-table.bin";

/// The body of an ACPI MADT (what follows the 36-byte header QEMU's
/// `-acpitable` writes) that lists one I/O APIC with its registers at
/// `address`: the local APIC's address (QEMU's, 0xFEE00000) and no flags,
/// then one I/O APIC entry (type 1, 12 bytes: I/O APIC ID 9, a reserved
/// byte, the address, global system interrupt base 24, past the 24 that
/// QEMU's own I/O APIC takes) (the ACPI specification, "Multiple APIC
/// Description Table").
pub(super) fn madt_body(address: u32) -> Vec<u8> {
    let mut body = 0xFEE0_0000u32.to_le_bytes().to_vec();
    body.extend(0u32.to_le_bytes());
    body.extend([1, 12, 9, 0]);
    body.extend(address.to_le_bytes());
    body.extend(24u32.to_le_bytes());
    body
}

/// The file [`madt_body`] is written to for a run.
pub(super) const MADT_FILE: &str = "madt.bin";
