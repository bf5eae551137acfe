//! The protocol server on COM1 (the `protocol` crate is the spec):
//! one command line in, one frame out. Whatever arrives, the server
//! answers and keeps serving: a bad line gets an `ERR` frame naming the
//! problem, an over-long one is thrown away up to its newline, a line
//! left unfinished for `PARTIAL_LINE_IDLE_SECONDS` is dropped and the
//! show plays again (`line.rs`: a stray byte on the line does not end
//! the show for good), and no byte sequence can make it panic or wait
//! forever. `EXIT` and `FAULT` are answered only on QEMU (`machine.rs`).

use alloc::borrow::Cow;
use alloc::string::{String, ToString};
use alloc::vec;
use alloc::vec::Vec;
use protocol::{
    Cleared, Command, CommandError, Damaged, DemoReply, DrawReply, ErrorReply, Firmware, FrameKind, Listing, LogEvent,
    Machine, Pong, Ready, Upload,
};
use raster::MethodId;
use scenes::show::{Entry, Stage, ENTRIES_IN_ORDER};
use scenes::{builtin, file, Op, Scene};

use crate::interrupts::{fault, idt, ioapic, pic};
use crate::platform::machine::Identity;
use crate::platform::{exit, heap, machine};
use crate::server::bench;
use crate::show::{demo, player};
use crate::time::clock;
use crate::video::{Drawn, Screen};
use crate::wire::line::{Complete, PendingLine};
use crate::wire::serial;

/// What `announce` found at boot (the firmware, the machine, the display
/// controller and where it sits), for the `READY` command to say again.
static BOOTED: spin::Once<Ready> = spin::Once::new();

/// Tells the host the kernel is up: a `LOG` frame saying which machine it
/// found and by what signs, one if COM1's interrupt did not arrive (the
/// kernel then receives by polling alone), one if the PIT's did not (the
/// server then never halts), one per thing the screen found on its way
/// (a framebuffer missing, or not the VGA's), on the VGA path one per
/// register or DAC entry that did not read back as written, then `READY`
/// naming the firmware, the machine, the display controller and where it
/// sits, the video path (with the count of those mismatches, or where the
/// frame is presented) and its memory type, and the bytes the serial
/// line lost so far.
pub fn announce(screen: &Screen, firmware: Firmware, identity: &Identity) {
    serial::send_log(LogEvent::Machine(identity.evidence()));
    if !serial::interrupt_arrives() {
        serial::send_log(LogEvent::Com1Polling);
    }
    if !pic::timer_arrives() {
        serial::send_log(LogEvent::NoTimerTick);
    }
    if let Some((address, why)) = clock::hpet_refused() {
        serial::send_log(LogEvent::HpetRefused { address, why });
    }
    if let Some(port) = clock::pm_timer_refused() {
        serial::send_log(LogEvent::PmTimerRefused { port });
    }
    for &(address, why) in ioapic::refused() {
        serial::send_log(LogEvent::IoApicRefused { address, why });
    }
    for &finding in screen.findings() {
        serial::send_log(finding);
    }
    for mismatch in screen.mismatches() {
        serial::send_log(LogEvent::VgaMismatch(mismatch));
    }
    let display = screen.display();
    BOOTED.call_once(|| Ready {
        firmware,
        machine: Some(identity.machine),
        display: display.map(|display| display.id),
        display_at: display.map(|display| display.address),
        ..Ready::default()
    });
    serial::send_frame(FrameKind::Ready, ready(screen).to_string().as_bytes());
}

/// What `READY` says now: what `announce` found at boot, the video path,
/// and the line's losses so far.
fn ready(screen: &Screen) -> Ready {
    let booted = BOOTED.get().copied().unwrap_or_default();
    Ready { video: screen.video(), memory: screen.memory_type(), losses: serial::losses(), ..booted }
}

/// Serves the host forever, starting with `first` (the line that stopped
/// the demo), taking the lines that follow from `pending`. `SHOW` draws
/// on `stage`.
pub fn serve(screen: &mut Screen, stage: &mut Stage, mut pending: PendingLine, first: Complete) -> ! {
    let mut server = Server { screen, stage, demo: None, upload: Upload::Nothing };
    let mut complete = first;
    loop {
        match complete {
            Complete::Line(line) => {
                server.execute(&line);
                pending.recycle(line);
            }
            Complete::TooLong => {
                let error = ErrorReply::Command(CommandError::TooLong);
                serial::send_frame(FrameKind::Err, error.to_string().as_bytes());
            }
        }
        // `DEMO` was answered: play until the host's next line.
        complete = match server.demo.take() {
            Some(start) => demo::run(server.screen, server.stage, start, &mut pending),
            None => server.next_line(&mut pending),
        };
    }
}

/// A reply: frame kind and payload. Failures are sent as `ERR` frames.
type Answer<'a> = Result<(FrameKind, Vec<u8>), ErrorReply<'a>>;

struct Server<'a> {
    screen: &'a mut Screen,
    /// Where `SHOW` draws its frames, allocated once.
    stage: &'a mut Stage,
    /// The demo `DEMO` asked for, to play once its answer is sent.
    demo: Option<demo::Start>,
    /// The scene the host uploaded, or is uploading.
    upload: Upload,
}

impl Server<'_> {
    /// Waits for the next complete line; a line left unfinished for its
    /// bound is dropped and the show plays again, until one comes.
    fn next_line(&mut self, pending: &mut PendingLine) -> Complete {
        loop {
            match serial::read_byte(pending.give_up(), pic::timer_arrives().then_some(pic::halt_until_interrupt)) {
                Some(byte) => {
                    if let Some(complete) = pending.push(byte) {
                        return complete;
                    }
                }
                None => {
                    pending.drop_if_idle();
                    return demo::run(self.screen, self.stage, demo::Start::default(), pending);
                }
            }
        }
    }

    /// Runs one line and answers it; a sealed line's answer echoes its
    /// sequence number, a damaged one is answered `ERR` without one and
    /// runs nothing.
    fn execute(&mut self, line: &[u8]) {
        idt::report();
        let (seq, reply) = match protocol::unseal(line) {
            Ok((seq, command)) => (seq, Command::parse(command).map_err(ErrorReply::Command).and_then(|c| self.run(c))),
            Err(Damaged) => (None, Err(ErrorReply::Damaged)),
        };
        match reply {
            Ok((kind, payload)) => serial::send_reply(kind, seq, &payload),
            Err(error) => serial::send_reply(FrameKind::Err, seq, error.to_string().as_bytes()),
        }
    }

    fn run<'a>(&mut self, command: Command<'a>) -> Answer<'a> {
        match command {
            Command::Ping => {
                ok(Pong { losses: serial::losses(), heap: heap::state(), interrupts: Some(idt::counts()) })
            }
            Command::List => Ok((FrameKind::List, listing().to_string().into_bytes())),
            Command::Draw { scene, method } => {
                let scene = find_scene(&self.upload, scene)?;
                let method = scene.method_or(method);
                ok(draw_reply(self.screen.draw(&scene, method)))
            }
            Command::Show { entry, frame, method } => {
                let (_, entry) = show_entry(entry)?;
                let method = method.unwrap_or(entry.method_at(frame));
                ok(player::play(self.screen, self.stage, entry, frame, method, None))
            }
            Command::Clear(color) => {
                self.screen.clear(color);
                ok(Cleared { color })
            }
            Command::Poly { method, spec } => {
                let polygon = file::parse_poly(spec).map_err(ErrorReply::Polygon)?;
                let scene = Scene::new(String::from("POLY"), vec![Op::Fill(polygon)], method);
                ok(draw_reply(self.screen.draw(&scene, method)))
            }
            Command::Upload { name, bytes, memory, crc } => ok(self.upload.start(name, bytes, memory, crc)?),
            Command::Chunk { offset, data } => ok(self.upload.chunk(offset, data)?),
            Command::Dump => Ok((FrameKind::Dump, self.screen.dump())),
            Command::Bench { scene, repeats } => {
                let scene = find_scene(&self.upload, scene)?;
                Ok((FrameKind::Bench, bench::run(self.screen, &scene, repeats).to_string().into_bytes()))
            }
            Command::Demo { entry, method } => {
                let index = entry.map(show_entry).transpose()?.map(|(index, _)| index);
                let start = demo::Start { entry: index.unwrap_or(0), stay: index.is_some(), method };
                self.demo = Some(start);
                ok(DemoReply { from: ENTRIES_IN_ORDER[start.entry].name, stay: start.stay, method })
            }
            Command::VgaCheck => match self.screen.check() {
                check if check.passed() => ok(check),
                check => Err(ErrorReply::VgaCheck(check)),
            },
            Command::Ready => Ok((FrameKind::Ready, ready(self.screen).to_string().into_bytes())),
            Command::Clock => ok(clock::rate()),
            Command::ForceClock { source, stalled } => {
                on_qemu(command.name())?;
                clock::force(source, stalled).map(ok).ok_or(ErrorReply::NoTimer(source))?
            }
            Command::Exit(code) => {
                on_qemu(command.name())?;
                exit::stop(code)
            }
            Command::Fault(kind) => {
                on_qemu(command.name())?;
                ok(fault::provoke(kind))
            }
        }
    }
}

/// The built-in scene called `name`, built, or else the scene of that
/// name in `upload`.
fn find_scene<'s, 'a>(upload: &'s Upload, name: &'a str) -> Result<Cow<'s, Scene>, ErrorReply<'a>> {
    match builtin::scene(name) {
        Some(scene) => Ok(Cow::Owned(scene)),
        None => upload.scene(name).map(Cow::Borrowed).ok_or(ErrorReply::UnknownScene(name)),
    }
}

/// `Ok` on a machine identified as QEMU; else why `command` is refused.
/// The test hooks touch nothing elsewhere: QEMU's exit port is a port
/// nobody identified on a PC, and a fault on request has no place there.
fn on_qemu(command: &'static str) -> Result<(), ErrorReply<'static>> {
    match machine::current() {
        Machine::Qemu => Ok(()),
        Machine::Unknown => Err(ErrorReply::NotQemu(command)),
    }
}

fn ok(text: impl core::fmt::Display) -> Answer<'static> {
    Ok((FrameKind::Ok, text.to_string().into_bytes()))
}

/// The show entry called `name`, and its place in the show.
fn show_entry(name: &str) -> Result<(usize, &'static Entry), ErrorReply<'_>> {
    ENTRIES_IN_ORDER.iter().enumerate().find(|(_, entry)| entry.name == name).ok_or(ErrorReply::UnknownShowEntry(name))
}

/// The `DRAW` and `POLY` answer for what [`Screen::draw`] did.
fn draw_reply(drawn: Drawn) -> DrawReply {
    DrawReply { polygons: drawn.report.polygons, refused: drawn.report.refused, strays: drawn.stray_spans }
}

/// The `LIST` answer: every built-in scene, every show entry in demo
/// order with its frames, every method.
fn listing() -> Listing {
    Listing {
        scenes: builtin::ALL.iter().map(|page| String::from(page.name)).collect(),
        shows: ENTRIES_IN_ORDER.iter().map(|entry| (String::from(entry.name), entry.frames)).collect(),
        methods: MethodId::ALL.iter().map(|method| String::from(method.name())).collect(),
    }
}
