//! QEMU's command line for a run: every flag, and why it is there.

use std::ffi::OsString;
use std::path::{Path, PathBuf};

use protocol::Firmware;

use super::board::{HPET_TABLE_FILE, MADT_FILE};
use super::options::{Cpu, Display, ExitDevice, Medium, QemuOptions, SerialLine, TimeBase};
use install::{ovmf_code, ovmf_secure_boot_code};

/// The slot `QemuOptions::display_ahead` puts the card in, and the QEMU
/// id screendumps name it by.
const CARD_BEHIND_SLOT: &str = "05.0";
pub(super) const CARD_BEHIND_ID: &str = "card";

/// Where a run keeps its QMP socket and, under UEFI, its copy of the
/// firmware's variable store.
pub(super) fn qmp_socket(run_dir: &Path) -> PathBuf {
    run_dir.join("qmp.sock")
}

pub(super) fn uefi_variables(run_dir: &Path) -> PathBuf {
    run_dir.join("OVMF_VARS_4M.fd")
}

/// QEMU's arguments for booting `image` with `options`, its QMP socket
/// (and the UEFI variable store) in `run_dir`.
pub(super) fn qemu_arguments(image: &Path, run_dir: &Path, options: QemuOptions) -> Vec<OsString> {
    let mut args: Vec<OsString> = Vec::new();
    if options.firmware == Firmware::Uefi && options.secure_boot {
        // Q35 with SMM: OVMF's Secure Boot build keeps its variables
        // behind SMM, where the guest's OS cannot write them directly...
        flag(&mut args, "-machine", "q35,smm=on");
        // ...its flash writable only from SMM...
        flag(&mut args, "-global", "driver=cfi.pflash01,property=secure,value=on");
        // ...and no S3 resume, which that build does not support.
        flag(&mut args, "-global", "ICH9-LPC.disable_s3=1");
        flag(
            &mut args,
            "-drive",
            with_path("if=pflash,format=raw,unit=0,readonly=on,file=", &ovmf_secure_boot_code(), ""),
        );
        flag(&mut args, "-drive", with_path("if=pflash,format=raw,unit=1,file=", &uefi_variables(run_dir), ""));
    } else {
        // The i440FX PC (or Q35). Its own firmware is SeaBIOS: a BIOS that
        // boots the image's BIOS side, like a PC's BIOS or CSM. `pit=off`
        // leaves the 8254 out, as on a legacy-free PC.
        flag(&mut args, "-machine", options.board.machine());
    }
    if options.hpet_table_at.is_some() {
        // One more ACPI table, which QEMU adds to the ones it builds for
        // the firmware: the HPET table, its body from the run's folder.
        let table = run_dir.join(HPET_TABLE_FILE);
        flag(&mut args, "-acpitable", with_path("sig=HPET,rev=1,oem_id=POLYLB,data=", &table, ""));
    }
    if options.io_apic_table_at.is_some() {
        // One more MADT beside the one QEMU builds: an I/O APIC of the
        // run's choosing, its body from the run's folder.
        let table = run_dir.join(MADT_FILE);
        flag(&mut args, "-acpitable", with_path("sig=APIC,rev=4,oem_id=POLYLB,data=", &table, ""));
    }
    if options.firmware == Firmware::Uefi && !options.secure_boot {
        // OVMF instead, as a UEFI PC's flash: its code read-only, and its
        // variable store (boot entries it writes as it boots) a copy of
        // the package's empty one, private to this run.
        flag(&mut args, "-drive", with_path("if=pflash,format=raw,unit=0,readonly=on,file=", &ovmf_code(), ""));
        flag(&mut args, "-drive", with_path("if=pflash,format=raw,unit=1,file=", &uefi_variables(run_dir), ""));
    }
    // Always emulate: KVM here is nested and pathologically slow, and TCG
    // exists everywhere QEMU does.
    flag(&mut args, "-accel", "tcg");
    // Plenty for the bootloader and the kernel's heap; small enough to start fast.
    flag(&mut args, "-m", "128M");
    if options.clock == TimeBase::InstructionCount {
        // `shift=0`: each instruction advances the virtual clock by 2^0 ns,
        // which rdtsc then reads; `sleep=off`: when the guest halts, the
        // clock jumps to the next timer instead of waiting for the host.
        flag(&mut args, "-icount", "shift=0,sleep=off");
    }
    // The display card (`Adapter`). Under SeaBIOS the VGA-compatible ones'
    // VGA BIOS puts them in text mode; under OVMF its graphics driver sets
    // their native mode, which the kernel undoes on the cards it knows.
    let [card_flag, card] = options.adapter.qemu_flags();
    match options.adapter.pci_device().zip(options.display_ahead) {
        Some((device, ahead)) => {
            // A display controller without VGA first in bus order, the
            // card behind it: the kernel must find the VGA by the legacy
            // VGA decoding, not by bus order, and under UEFI the head the
            // firmware used.
            flag(&mut args, "-vga", "none");
            flag(&mut args, "-device", ahead.device());
            flag(&mut args, "-device", format!("{device},addr={CARD_BEHIND_SLOT},id={CARD_BEHIND_ID}"));
        }
        None => {
            flag(&mut args, card_flag, card);
            if card_flag == "-device" {
                // No built-in VGA beside the card given as a device.
                flag(&mut args, "-vga", "none");
            }
        }
    }
    if options.cpu == Cpu::WithoutHypervisorBit {
        // QEMU's default CPU model, its hypervisor bit cleared.
        flag(&mut args, "-cpu", "qemu64,-hypervisor");
    }
    // No network card: nothing boots from the network, and no option ROM
    // of one slows the firmware down.
    flag(&mut args, "-nic", "none");
    match options.display {
        // No window; QMP screendumps still render the card's output.
        Display::Headless => flag(&mut args, "-display", "none"),
        // No `-display`: QEMU picks its best backend for a window (GTK, SDL).
        Display::Window => {}
    }
    // No human monitor: QMP is the control channel and stdio is COM1.
    flag(&mut args, "-monitor", "none");
    match options.serial {
        // COM1 on QEMU's stdin and stdout, both pipes to us: the protocol line.
        SerialLine::Stdio => flag(&mut args, "-serial", "stdio"),
        // COM1 on a pseudo-terminal, found through QMP (`Qemu::pty`).
        SerialLine::Pty => flag(&mut args, "-serial", "pty"),
        SerialLine::Telnet { port } => {
            // COM1 on a telnet server; `wait=on`: the guest starts once
            // the harness has connected, so no frame is lost.
            let server = format!("socket,id=com1,host=127.0.0.1,port={port},server=on,wait=on,telnet=on");
            flag(&mut args, "-chardev", server);
            flag(&mut args, "-serial", "chardev:com1");
        }
    }
    if let Some(irq) = options.com1_irq {
        flag(&mut args, "-global", format!("isa-serial.irq={irq}"));
    }
    // Screendump and quit; `wait=off` lets the guest run with no client yet.
    flag(&mut args, "-qmp", with_path("unix:", &qmp_socket(run_dir), ",server=on,wait=off"));
    if options.exit_device == ExitDevice::Present {
        // `EXIT n` and fault reports leave QEMU with exit status (n << 1) | 1.
        flag(&mut args, "-device", "isa-debug-exit,iobase=0xf4,iosize=0x04");
    }
    if !options.allow_reboot {
        // A triple fault exits QEMU instead of rebooting the guest forever.
        args.push("-no-reboot".into());
    }
    // `snapshot=on` sends writes to a temporary overlay: the image file stays
    // untouched and parallel runs can share it without QEMU's write lock.
    match options.medium {
        Medium::Disk => {
            flag(&mut args, "-drive", with_path("if=ide,index=0,format=raw,snapshot=on,file=", image, ""));
        }
        Medium::UsbStick => {
            // The stick's drive has no bus of its own; usb-storage carries it.
            flag(&mut args, "-drive", with_path("if=none,id=stick,format=raw,snapshot=on,file=", image, ""));
            // A USB 3 controller, as on the PCs the stick is meant for.
            flag(&mut args, "-device", "qemu-xhci,id=xhci");
            // The stick itself; SeaBIOS and OVMF boot from it as from a disk.
            flag(&mut args, "-device", "usb-storage,bus=xhci.0,drive=stick");
        }
    }
    args
}

fn flag(args: &mut Vec<OsString>, flag: &str, value: impl Into<OsString>) {
    args.push(flag.into());
    args.push(value.into());
}

/// `prefix`, `path` and `suffix` as one argument (paths need not be UTF-8).
fn with_path(prefix: &str, path: &Path, suffix: &str) -> OsString {
    let mut arg = OsString::from(prefix);
    arg.push(path);
    arg.push(suffix);
    arg
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::qemu::board::{Board, DisplayAhead};
    use crate::qemu::options::Adapter;

    fn arguments(options: QemuOptions) -> Vec<String> {
        qemu_arguments(Path::new("/img/polylab.img"), Path::new("/run"), options)
            .into_iter()
            .map(|a| a.into_string().unwrap())
            .collect()
    }

    fn has_pair(args: &[String], flag: &str, value: &str) -> bool {
        args.windows(2).any(|w| w[0] == flag && w[1] == value)
    }

    #[test]
    fn headless_disk_boot_has_every_required_flag() {
        let args = arguments(QemuOptions::default());
        for (flag, value) in [
            ("-accel", "tcg"),
            ("-display", "none"),
            ("-serial", "stdio"),
            ("-qmp", "unix:/run/qmp.sock,server=on,wait=off"),
            ("-device", "isa-debug-exit,iobase=0xf4,iosize=0x04"),
            ("-m", "128M"),
            ("-nic", "none"),
            ("-drive", "if=ide,index=0,format=raw,snapshot=on,file=/img/polylab.img"),
        ] {
            assert!(has_pair(&args, flag, value), "{flag} {value} missing from {args:?}");
        }
        assert!(args.contains(&"-no-reboot".to_string()));
        assert!(!args.iter().any(|a| a.contains("usb")));
        assert!(!args.iter().any(|a| a.contains("pflash")), "SeaBIOS is the default firmware: {args:?}");
    }

    #[test]
    fn uefi_boots_ovmf_from_read_only_code_and_a_private_variable_store() {
        let args = arguments(QemuOptions { firmware: Firmware::Uefi, ..QemuOptions::default() });
        let code = format!("if=pflash,format=raw,unit=0,readonly=on,file={}", ovmf_code().display());
        assert!(has_pair(&args, "-drive", &code), "{args:?}");
        assert!(has_pair(&args, "-drive", "if=pflash,format=raw,unit=1,file=/run/OVMF_VARS_4M.fd"), "{args:?}");
        assert!(has_pair(&args, "-drive", "if=ide,index=0,format=raw,snapshot=on,file=/img/polylab.img"));
    }

    #[test]
    fn secure_boot_is_ovmfs_secure_build_on_q35_with_smm_and_its_flash_secured() {
        let args = arguments(QemuOptions { firmware: Firmware::Uefi, secure_boot: true, ..QemuOptions::default() });
        let code = format!("if=pflash,format=raw,unit=0,readonly=on,file={}", ovmf_secure_boot_code().display());
        assert!(has_pair(&args, "-drive", &code), "{args:?}");
        assert!(has_pair(&args, "-drive", "if=pflash,format=raw,unit=1,file=/run/OVMF_VARS_4M.fd"), "{args:?}");
        assert!(has_pair(&args, "-machine", "q35,smm=on"), "{args:?}");
        assert!(has_pair(&args, "-global", "driver=cfi.pflash01,property=secure,value=on"), "{args:?}");
        assert!(has_pair(&args, "-global", "ICH9-LPC.disable_s3=1"), "{args:?}");
        assert_eq!(args.iter().filter(|a| *a == "-machine").count(), 1, "{args:?}");
        assert_eq!(args.iter().filter(|a| a.starts_with("if=pflash")).count(), 2, "{args:?}");
        assert!(args.contains(&"-no-reboot".to_string()));
    }

    #[test]
    fn a_reboot_restarts_the_machine_only_when_allowed() {
        let args = arguments(QemuOptions { allow_reboot: true, ..QemuOptions::default() });
        assert!(!args.contains(&"-no-reboot".to_string()), "{args:?}");
    }

    #[test]
    fn usb_stick_boot_puts_the_image_on_xhci_usb_storage() {
        let args = arguments(QemuOptions { medium: Medium::UsbStick, ..QemuOptions::default() });
        assert!(has_pair(&args, "-drive", "if=none,id=stick,format=raw,snapshot=on,file=/img/polylab.img"));
        assert!(has_pair(&args, "-device", "qemu-xhci,id=xhci"));
        assert!(has_pair(&args, "-device", "usb-storage,bus=xhci.0,drive=stick"));
        assert!(!args.iter().any(|a| a.starts_with("if=ide")));
    }

    #[test]
    fn each_card_is_one_vga_flag_or_a_device_with_no_built_in_vga() {
        assert!(has_pair(&arguments(QemuOptions::default()), "-vga", "std"));
        for (adapter, flag, value) in [
            (Adapter::Cirrus, "-vga", "cirrus"),
            (Adapter::Vmware, "-vga", "vmware"),
            (Adapter::QxlVga, "-vga", "qxl"),
            (Adapter::VirtioVga, "-vga", "virtio"),
            (Adapter::AtiVga, "-device", "ati-vga"),
            (Adapter::BochsDisplay, "-device", "bochs-display"),
            (Adapter::Ramfb, "-device", "ramfb"),
            (Adapter::VirtioGpu, "-device", "virtio-gpu-pci"),
            (Adapter::None, "-vga", "none"),
        ] {
            let args = arguments(QemuOptions { adapter, ..QemuOptions::default() });
            assert!(has_pair(&args, flag, value), "{adapter:?}: {args:?}");
            assert_eq!(args.iter().filter(|a| *a == "-vga").count(), 1, "{args:?}");
            if flag == "-device" {
                assert!(has_pair(&args, "-vga", "none"), "{args:?}");
            }
        }
    }

    #[test]
    fn com1_goes_to_stdio_or_to_a_pty() {
        assert!(has_pair(&arguments(QemuOptions::default()), "-serial", "stdio"));
        let args = arguments(QemuOptions { serial: SerialLine::Pty, ..QemuOptions::default() });
        assert!(has_pair(&args, "-serial", "pty"), "{args:?}");
        assert_eq!(args.iter().filter(|a| *a == "-serial").count(), 1, "{args:?}");
    }

    #[test]
    fn only_instruction_counting_adds_icount() {
        assert!(!arguments(QemuOptions::default()).iter().any(|a| a == "-icount"));
        let args = arguments(QemuOptions { clock: TimeBase::InstructionCount, ..QemuOptions::default() });
        assert!(has_pair(&args, "-icount", "shift=0,sleep=off"), "{args:?}");
    }

    #[test]
    fn a_telnet_com1_waits_for_the_harness_and_carries_breaks() {
        let args = arguments(QemuOptions { serial: SerialLine::Telnet { port: 4555 }, ..QemuOptions::default() });
        let server = "socket,id=com1,host=127.0.0.1,port=4555,server=on,wait=on,telnet=on";
        assert!(has_pair(&args, "-chardev", server), "{args:?}");
        assert!(has_pair(&args, "-serial", "chardev:com1"), "{args:?}");
        assert!(!has_pair(&args, "-serial", "stdio"), "{args:?}");
    }

    #[test]
    fn com1_irq_cpu_and_exit_device_options_change_only_their_flags() {
        let default = arguments(QemuOptions::default());
        assert!(!default.iter().any(|a| a == "-cpu" || a == "-global"), "{default:?}");
        let moved = arguments(QemuOptions { com1_irq: Some(3), ..QemuOptions::default() });
        assert!(has_pair(&moved, "-global", "isa-serial.irq=3"), "{moved:?}");
        let disguised = arguments(QemuOptions { cpu: Cpu::WithoutHypervisorBit, ..QemuOptions::default() });
        assert!(has_pair(&disguised, "-cpu", "qemu64,-hypervisor"), "{disguised:?}");
        let bare = arguments(QemuOptions { exit_device: ExitDevice::Absent, ..QemuOptions::default() });
        assert!(!bare.iter().any(|a| a.contains("isa-debug-exit")), "{bare:?}");
        // One flag and its value more, or less; nothing else moves.
        assert_eq!(
            [moved.len(), disguised.len(), bare.len()],
            [default.len() + 2, default.len() + 2, default.len() - 2]
        );
    }

    #[test]
    fn a_display_ahead_puts_bochs_display_in_slot_2_or_secondary_vga_in_slot_4_and_the_card_in_slot_5() {
        for (ahead, expected) in [
            (DisplayAhead::BochsDisplay, "bochs-display,addr=02.0,id=ahead"),
            (DisplayAhead::SecondaryVga, "secondary-vga,addr=04.0,id=ahead"),
        ] {
            let options =
                QemuOptions { adapter: Adapter::Cirrus, display_ahead: Some(ahead), ..QemuOptions::default() };
            let args = arguments(options);
            assert!(has_pair(&args, "-vga", "none"), "{args:?}");
            let devices: Vec<&String> = args.windows(2).filter(|w| w[0] == "-device").map(|w| &w[1]).collect();
            assert_eq!(devices[..2], [expected, "cirrus-vga,addr=05.0,id=card"], "{args:?}");
        }
        let options = QemuOptions {
            adapter: Adapter::Ramfb,
            display_ahead: Some(DisplayAhead::BochsDisplay),
            ..QemuOptions::default()
        };
        let ramfb = arguments(options);
        assert!(has_pair(&ramfb, "-device", "ramfb") && !ramfb.iter().any(|a| a.contains("bochs-display")));
    }

    #[test]
    fn a_madt_of_the_runs_own_is_one_more_acpi_table_from_its_folder() {
        let args = arguments(QemuOptions { io_apic_table_at: Some(0x100_0000), ..QemuOptions::default() });
        let at = args.iter().position(|a| a == "-acpitable").expect("an -acpitable flag");
        assert!(args[at + 1].starts_with("sig=APIC,rev=4,oem_id=POLYLB,data="), "{args:?}");
        assert!(args[at + 1].ends_with("madt.bin"), "{args:?}");
        let body = super::super::board::madt_body(0x1234_5678);
        assert_eq!(body.len(), 20, "the MADT's body after its header: 8 bytes, one 12-byte entry");
        assert_eq!((body[8], body[9]), (1, 12), "an I/O APIC entry");
        assert_eq!(u32::from_le_bytes(body[12..16].try_into().unwrap()), 0x1234_5678);
    }

    #[test]
    fn an_hpet_table_of_the_runs_own_is_one_more_acpi_table_from_its_folder() {
        assert!(!arguments(QemuOptions::default()).iter().any(|a| a == "-acpitable"));
        let options =
            QemuOptions { board: Board::PcWithoutHpet, hpet_table_at: Some(0x20_0000), ..QemuOptions::default() };
        let args = arguments(options);
        let at = args.iter().position(|a| a == "-acpitable").expect("an -acpitable flag");
        assert!(args[at + 1].starts_with("sig=HPET,rev=1,oem_id=POLYLB,data="), "{args:?}");
        assert!(args[at + 1].ends_with("hpet-table.bin"), "{args:?}");
        assert!(has_pair(&args, "-machine", "pc,hpet=off"), "{args:?}");
        let body = super::super::board::hpet_table_body(0x1234_5678_9abc);
        assert_eq!(body.len(), 20, "the HPET table's body after its header");
        assert_eq!(u64::from_le_bytes(body[8..16].try_into().unwrap()), 0x1234_5678_9abc);
    }

    #[test]
    fn a_board_without_a_pit_is_pc_or_q35_with_pit_off() {
        assert!(has_pair(&arguments(QemuOptions::default()), "-machine", "pc"));
        for (board, machine) in [(Board::PcWithoutPit, "pc,pit=off"), (Board::Q35WithoutPit, "q35,pit=off")] {
            for firmware in Firmware::ALL {
                let args = arguments(QemuOptions { board, firmware, ..QemuOptions::default() });
                assert!(has_pair(&args, "-machine", machine), "{args:?}");
                assert_eq!(args.iter().filter(|a| *a == "-machine").count(), 1, "{args:?}");
            }
        }
    }

    #[test]
    fn a_window_drops_only_the_display_flag() {
        let headless = arguments(QemuOptions::default());
        let window = arguments(QemuOptions { display: Display::Window, ..QemuOptions::default() });
        let mut expected = headless.clone();
        let display = headless.iter().position(|a| a == "-display").unwrap();
        expected.drain(display..display + 2);
        assert_eq!(window, expected);
    }
}
