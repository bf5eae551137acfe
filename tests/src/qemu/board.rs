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
}

impl Board {
    /// Its `-machine` value (without a firmware's needs: Secure Boot's
    /// board is its own).
    pub(super) fn machine(self) -> &'static str {
        match self {
            Board::Pc => "pc",
            Board::PcWithoutPit => "pc,pit=off",
            Board::Q35WithoutPit => "q35,pit=off",
        }
    }
}
