//! The host end of the serial protocol: commands out, typed replies in.

use std::io::Write;
use std::time::Duration;

use anyhow::{bail, ensure, Context, Result};
use base64::Engine;
use protocol::{
    BenchRow, ChunkReply, Cleared, ClockSource, Command, DrawReply, LineLosses, Listing, LogEvent, Pong, Ready,
    ShowReply, TscRate, UploadReply, CHUNK_BYTES, UPLOAD_BUDGET,
};
use raster::MethodId;
use scenes::{builtin, packed, show, Scene};

use super::channel::Channel;
use super::frame_reader::FrameReader;
use super::reply::{Dump, Reply, REPLY_TIMEOUT};
use super::sealing::{LineStats, Sealing};

/// Longest wait for the READY frame: SeaBIOS, the bootloader's stages and
/// the mode set under TCG, on a loaded 2-core machine.
pub const READY_TIMEOUT: Duration = Duration::from_secs(120);
/// What uploading a scene took.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Uploaded {
    /// The name the kernel knows the scene by.
    pub name: String,
    /// Its packed bytes.
    pub packed: usize,
    /// The memory it unpacks to.
    pub memory: usize,
    /// The bytes of every command line sent for it, terminators included
    /// (each try of a retried one counted once).
    pub sent: usize,
}

/// `scene` packed (`scenes::packed`) and the memory it unpacks to, if
/// both fit the kernel's budget for an uploaded scene; else an error
/// naming its size and the budget. What [`Console::upload`] sends, and
/// what a command checks before it boots anything.
pub fn pack_for_upload(scene: &Scene) -> Result<(Vec<u8>, usize)> {
    let bytes = packed::pack(scene);
    let memory = packed::memory(scene);
    ensure!(
        bytes.len() + memory <= UPLOAD_BUDGET,
        "{} is too large for the kernel: {} bytes packed and {memory} unpacked, {} in all, where the kernel's \
         budget for an uploaded scene is {UPLOAD_BUDGET} bytes (docs/protocol.md#uploading-a-scene)",
        scene.name,
        bytes.len(),
        bytes.len() + memory
    );
    Ok((bytes, memory))
}

/// The name a scene is uploaded under: its own, with every character that
/// is not a letter, a digit, `.`, `_` or `-` made `-` (a command word holds
/// no space), and `-file` added to a built-in page's name, which the
/// kernel keeps for the page.
pub fn upload_name(name: &str) -> String {
    let word: String =
        name.chars().map(|c| if c.is_ascii_alphanumeric() || "._-".contains(c) { c } else { '-' }).collect();
    match word.as_str() {
        "" => "scene".to_string(),
        _ if builtin::named(&word).is_some() => format!("{word}-file"),
        _ => word,
    }
}

/// A protocol session over a serial line.
pub struct Console {
    pub(crate) channel: Channel,
    /// How commands go out on a line that can damage bytes (sealed, each
    /// reply matched to its line, steps retried); `None`: plain lines, as
    /// over QEMU's stdio, which loses nothing.
    sealing: Option<Sealing>,
    /// What the last upload took.
    last_upload: Option<Uploaded>,
}

impl Console {
    /// A console that sends plain lines to `input` and reads frames from
    /// `frames`.
    pub fn new(input: impl Write + Send + 'static, frames: FrameReader) -> Self {
        Self { channel: Channel::new(input, frames), sealing: None, last_upload: None }
    }

    /// A console that seals every command (`sealing.rs`) and retries a
    /// step the line damaged up to `retries` times.
    pub fn sealed(input: impl Write + Send + 'static, frames: FrameReader, retries: u32) -> Self {
        Self { sealing: Some(Sealing::new(retries)), ..Self::new(input, frames) }
    }

    /// Waits for the READY frame and returns what it says (display
    /// adapter, VGA read-back mismatches, serial losses). LOG frames before
    /// it are kept in [`Console::logs`].
    pub fn wait_ready(&mut self) -> Result<Ready> {
        match self.reply_within(READY_TIMEOUT).context("waiting for the kernel's READY frame")? {
            Reply::Ready(text) => Ready::parse(&text).with_context(|| format!("READY \"{text}\" does not parse")),
            other => bail!("the kernel's first frame is {}, not READY", other.describe()),
        }
    }

    /// Waits (at most `timeout`) for `text` on the line outside any frame
    /// and returns what came up to its end.
    pub fn wait_for_text(&mut self, text: &str, timeout: Duration) -> Result<String> {
        self.channel.frames.skip_to_first(&[text], timeout).map(|(_, seen)| seen)
    }

    /// Waits (at most `timeout`) for the first of `texts` on the line
    /// outside any frame (see [`FrameReader::skip_to_first`]): which, and
    /// what came up to its end.
    pub fn wait_for_first_text(&mut self, texts: &[&str], timeout: Duration) -> Result<(usize, String)> {
        self.channel.frames.skip_to_first(texts, timeout)
    }

    /// The LOG frames received so far, in order, each read as the event
    /// it tells.
    pub fn logs(&self) -> &[LogEvent] {
        &self.channel.logs
    }

    /// Sends one command line.
    pub fn send(&mut self, command: &Command) -> Result<()> {
        self.send_bytes(format!("{command}\n").as_bytes()).with_context(|| format!("failed to send `{command}`"))
    }

    /// Sends raw bytes, valid or not.
    pub fn send_bytes(&mut self, bytes: &[u8]) -> Result<()> {
        self.channel.send_bytes(bytes)
    }

    /// The next reply, within [`REPLY_TIMEOUT`]; LOG frames on the way are
    /// kept in [`Console::logs`].
    pub fn reply(&mut self) -> Result<Reply> {
        self.reply_within(REPLY_TIMEOUT)
    }

    /// The next reply within `timeout`: one deadline for the whole wait,
    /// which LOG frames on the way do not extend (a kernel that keeps
    /// logging and never answers still times out).
    pub fn reply_within(&mut self, timeout: Duration) -> Result<Reply> {
        self.channel.reply_within(timeout)
    }

    /// Sends `command` and returns its reply, whatever it is (sealed, if
    /// the console seals its commands).
    pub fn request(&mut self, command: &Command) -> Result<Reply> {
        if let Some(sealing) = self.sealing.as_mut() {
            return sealing.request(&mut self.channel, command);
        }
        self.send(command)?;
        self.reply().with_context(|| format!("waiting for the reply to `{command}`"))
    }

    /// Sends `command` and expects OK; returns its text.
    pub fn ok(&mut self, command: &Command) -> Result<String> {
        match self.request(command)? {
            Reply::Ok(text) => Ok(text),
            other => bail!("`{command}` answered {}", other.describe()),
        }
    }

    /// Sends `command` and expects ERR; returns its text, which
    /// [`protocol::ErrorReply::parse`] reads (the reply's decoding
    /// checked it).
    pub fn refusal(&mut self, command: &Command) -> Result<String> {
        match self.request(command)? {
            Reply::Err(text) => Ok(text),
            other => bail!("`{command}` answered {}, expected ERR", other.describe()),
        }
    }

    /// Clears the screen to `color`, as the `CLEAR` answer must say.
    pub fn clear(&mut self, color: u8) -> Result<()> {
        let command = Command::Clear(color);
        let text = self.ok(&command)?;
        let cleared = Cleared::parse(&text).with_context(|| format!("`{command}` answered OK \"{text}\""))?;
        ensure!(cleared == Cleared { color }, "`{command}` answered OK \"{text}\", another colour");
        Ok(())
    }

    /// Sends a `DRAW` or `POLY` and returns what its answer says was drawn.
    fn draw_command(&mut self, command: &Command) -> Result<DrawReply> {
        let text = self.ok(command)?;
        DrawReply::parse(&text).with_context(|| format!("`{command}` answered OK \"{text}\""))
    }

    /// Clears the screen to black (the host render's starting point) and
    /// draws a built-in scene; returns what the kernel says it drew.
    pub fn draw(&mut self, scene: &str, method: Option<MethodId>) -> Result<DrawReply> {
        self.clear(0)?;
        self.draw_command(&Command::Draw { scene, method })
    }

    /// Uploads `scene` to the kernel (`UPLOAD`, then its packed bytes in
    /// `CHUNK`s of [`CHUNK_BYTES`], each retried on its own where the line
    /// damages it, as a chunk sent twice does no harm), under the name
    /// [`upload_name`] gives, which it returns with what went over the
    /// line. A scene over the kernel's budget is refused before anything
    /// is sent, naming its size and the budget.
    pub fn upload(&mut self, scene: &Scene) -> Result<Uploaded> {
        let (bytes, memory) = pack_for_upload(scene)?;
        let name = upload_name(&scene.name);
        let start = Command::Upload { name: &name, bytes: bytes.len(), memory, crc: crc32fast::hash(&bytes) };
        let mut sent = start.to_string().len() + 1;
        let text = self.retrying(|console| console.ok(&start))?;
        let reply = UploadReply::parse(&text).with_context(|| format!("`{start}` answered OK \"{text}\""))?;
        ensure!(
            (reply.name, reply.bytes, reply.memory) == (name.as_str(), bytes.len(), memory),
            "`{start}` answered OK \"{text}\", another upload"
        );
        let mut last = None;
        for (i, chunk) in bytes.chunks(CHUNK_BYTES).enumerate() {
            let offset = i * CHUNK_BYTES;
            let data = base64::engine::general_purpose::STANDARD.encode(chunk);
            let command = Command::Chunk { offset, data: &data };
            sent += command.to_string().len() + 1;
            let text = self.retrying(|console| console.ok(&command))?;
            let reply = ChunkReply::parse(&text).with_context(|| format!("`CHUNK {offset}` answered OK \"{text}\""))?;
            let expected = ChunkReply { received: offset + chunk.len(), total: bytes.len() };
            ensure!(reply == expected, "`CHUNK {offset}` answered OK \"{text}\", not \"{expected}\"");
            last = Some(reply);
        }
        ensure!(last.is_none_or(|reply| reply.complete()), "the upload of {name} did not complete");
        let uploaded = Uploaded { name, packed: bytes.len(), memory, sent };
        self.last_upload = Some(uploaded.clone());
        Ok(uploaded)
    }

    /// What the last upload took, if there was one.
    pub fn last_upload(&self) -> Option<&Uploaded> {
        self.last_upload.as_ref()
    }

    /// Clears the screen to black and draws `scene` with `method`:
    /// uploaded whole (see [`Console::upload`]), then drawn by name
    /// (`DRAW`). Returns what went over the line for the upload.
    pub fn draw_scene(&mut self, scene: &Scene, method: MethodId) -> Result<Uploaded> {
        let uploaded = self.upload(scene)?;
        self.clear(0)?;
        let drawn = self.draw_uploaded(&uploaded.name, method)?;
        let polygons = scene.polygons().count();
        ensure!(
            drawn.polygons == polygons,
            "the kernel drew {} polygons of {}, not {polygons}",
            drawn.polygons,
            scene.name
        );
        Ok(uploaded)
    }

    /// Draws the scene uploaded under `name` with `method` (`DRAW`), over
    /// what the screen holds; what its answer says was drawn.
    pub fn draw_uploaded(&mut self, name: &str, method: MethodId) -> Result<DrawReply> {
        self.draw_command(&Command::Draw { scene: name, method: Some(method) })
    }

    /// Has the kernel show frame `frame` of show entry `entry`, with
    /// `method` or, for `None`, the entry's own method for that frame. The
    /// reply names an entry of the host's show (`scenes::show`), whose
    /// name it borrows.
    pub fn show(&mut self, entry: &str, frame: u32, method: Option<MethodId>) -> Result<ShowReply<'static>> {
        let command = Command::Show { entry, frame, method };
        let text = self.ok(&command)?;
        let reply =
            ShowReply::parse(&text).with_context(|| format!("`{command}` answered OK \"{text}\", not a SHOW reply"))?;
        let shown = show::entry(reply.entry)
            .with_context(|| format!("`{command}` answered OK \"{text}\", naming an entry the show does not have"))?;
        let ShowReply { frame, method, cycles, allocs, polygons, refused, strays, .. } = reply;
        Ok(ShowReply { entry: shown.name, frame, method, cycles, allocs, polygons, refused, strays })
    }

    pub fn dump(&mut self) -> Result<Dump> {
        match self.request(&Command::Dump)? {
            Reply::Dump(dump) => Ok(*dump),
            other => bail!("`DUMP` answered {}", other.describe()),
        }
    }

    /// Times every method drawing built-in `scene` `repeats` times: per
    /// method in [`MethodId::ALL`] order, the method and the median
    /// rdtsc ticks of one draw (see `protocol::BENCH_UNIT_LINE`).
    pub fn bench(&mut self, scene: &str, repeats: u8) -> Result<Vec<BenchRow>> {
        let command = Command::Bench { scene, repeats };
        match self.request(&command)? {
            Reply::Bench(rows) => Ok(rows),
            other => bail!("`{command}` answered {}", other.describe()),
        }
    }

    /// Sends `PING` and returns what the kernel says the serial line has
    /// lost so far.
    pub fn ping(&mut self) -> Result<LineLosses> {
        Ok(self.pong()?.losses)
    }

    /// Sends `PING` and returns its whole answer: the serial line's losses
    /// and the kernel heap's state.
    pub fn pong(&mut self) -> Result<Pong> {
        let text = self.ok(&Command::Ping)?;
        Pong::parse(&text).with_context(|| format!("`PING` answered OK \"{text}\", not a pong"))
    }

    pub fn list(&mut self) -> Result<Listing> {
        match self.request(&Command::List)? {
            Reply::List(listing) => Ok(listing),
            other => bail!("`LIST` answered {}", other.describe()),
        }
    }

    /// Sends `READY` and returns the kernel's `READY` text as of now.
    pub fn ready_now(&mut self) -> Result<String> {
        match self.request(&Command::Ready)? {
            Reply::Ready(text) => Ok(text),
            other => bail!("`READY` answered {}", other.describe()),
        }
    }

    /// Sends `CLOCK` and returns the kernel's time-stamp counter rate.
    pub fn tsc_rate(&mut self) -> Result<TscRate> {
        self.clock(&Command::Clock)
    }

    /// `CLOCK SOURCE [stalled]` (test only): the kernel measures the TSC
    /// against `source` alone, `stalled` with its own stalls inside the
    /// measurement, and takes that rate as its clock; what it answers.
    pub fn force_clock(&mut self, source: ClockSource, stalled: bool) -> Result<TscRate> {
        self.clock(&Command::ForceClock { source, stalled })
    }

    fn clock(&mut self, command: &Command) -> Result<TscRate> {
        let text = self.ok(command)?;
        TscRate::parse(&text).with_context(|| format!("`{command}` answered OK \"{text}\", not a TSC rate"))
    }

    /// The line's counts, if the console seals its commands.
    pub fn line_stats(&self) -> Option<&LineStats> {
        self.sealing.as_ref().map(|sealing| &sealing.stats)
    }

    /// Sets how long a sealing console waits for a reply that takes the
    /// kernel no work (10 s by default; a dump's and a `BENCH`'s waits
    /// grow from it).
    pub fn set_answer_timeout(&mut self, timeout: Duration) {
        if let Some(sealing) = self.sealing.as_mut() {
            sealing.set_answer_timeout(timeout);
        }
    }

    /// Most retries of one step (0 for a console that does not seal).
    pub fn retries_allowed(&self) -> u32 {
        self.sealing.as_ref().map_or(0, Sealing::retries)
    }

    /// Bytes received so far, frames and noise.
    pub fn bytes_received(&self) -> u64 {
        self.channel.frames.received()
    }

    /// Runs `step`, and while it fails for what the line did (a
    /// [`Trouble`](super::Trouble)) runs it again, up to the
    /// console's retry bound, after letting the line settle. Any other
    /// failure, and a console that does not seal, fail at once.
    pub fn retrying<T>(&mut self, mut step: impl FnMut(&mut Console) -> Result<T>) -> Result<T> {
        let mut retried = 0;
        loop {
            let error = match step(self) {
                Ok(value) => return Ok(value),
                Err(error) => error,
            };
            let Some(sealing) = self.sealing.as_mut() else { return Err(error) };
            sealing.retry_after(&mut self.channel, error, retried)?;
            retried += 1;
        }
    }

    /// Finds the kernel on a sealing console: sends `READY` until it
    /// answers (or sends its `READY` at boot), within `bound`. Returns the
    /// `READY` text and whether it came at boot. Fails with what to check
    /// when nothing answers.
    pub fn wait_for_kernel(&mut self, bound: Duration, device: &str) -> Result<(String, bool)> {
        let Some(sealing) = self.sealing.as_mut() else { bail!("only a sealing console looks for the kernel") };
        sealing.wait_for_kernel(&mut self.channel, bound, device)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use protocol::{
        BenchReply, Firmware, FrameHeader, FrameKind, HeapState, Mismatch, RegisterGroup, Video, FRAMEBUFFER_LEN,
    };
    use scenes::palette::ENTRIES;
    use std::sync::mpsc::{self, Sender};
    use std::sync::{Arc, Mutex};

    /// What the console wrote, shared with the test.
    #[derive(Clone, Default)]
    struct Sent(Arc<Mutex<Vec<u8>>>);

    impl Write for Sent {
        fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
            self.0.lock().unwrap().extend_from_slice(bytes);
            Ok(bytes.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    fn console(frames: &[(FrameKind, &[u8])]) -> (Console, Sent, Sender<Vec<u8>>) {
        let (sender, receiver) = mpsc::channel();
        for (kind, payload) in frames {
            let mut bytes = format!("{}\n", FrameHeader::for_payload(*kind, payload)).into_bytes();
            bytes.extend_from_slice(payload);
            bytes.push(b'\n');
            sender.send(bytes).unwrap();
        }
        let sent = Sent::default();
        (Console::new(sent.clone(), FrameReader::new(receiver)), sent, sender)
    }

    #[test]
    fn commands_go_out_as_lines_and_replies_come_back_typed() {
        let (mut console, sent, _keep) = console(&[
            (FrameKind::Log, b"crtc[0x11]: expected 0x8e, read 0x0e"),
            (FrameKind::Ready, b"firmware=uefi display=1234:1111 video=vga13h vga_mismatches=1 overruns=0 dropped=0"),
            (FrameKind::Ok, b"pong overruns=3 dropped=1 heap_used=96 heap_free_largest=4096"),
            (FrameKind::List, b"scene abrash38-1\nshow race 240\nmethod abrash_float\n"),
        ]);
        let ready = console.wait_ready().unwrap();
        assert_eq!(
            (ready.firmware, ready.display.unwrap().to_string(), ready.video),
            (Firmware::Uefi, "1234:1111".to_string(), Video::Vga13h { mismatches: 1 })
        );
        let pong = console.pong().unwrap();
        assert_eq!(pong.losses, LineLosses { overruns: 3, dropped: 1, errors: None });
        assert_eq!(pong.heap, HeapState { used: 96, free_largest: 4096 });
        let listing = console.list().unwrap();
        let expected = Listing {
            scenes: vec!["abrash38-1".into()],
            shows: vec![("race".into(), 240)],
            methods: vec!["abrash_float".into()],
        };
        assert_eq!(listing, expected);
        let mismatch = Mismatch { group: RegisterGroup::Crtc, index: 0x11, expected: 0x8e, actual: 0x0e };
        assert_eq!(console.logs(), [LogEvent::VgaMismatch(mismatch)]);
        assert_eq!(sent.0.lock().unwrap().as_slice(), b"PING\nLIST\n");
    }

    #[test]
    fn an_unexpected_reply_is_an_error_naming_the_command_and_the_reply() {
        let (mut console, _, _keep) = console(&[(FrameKind::Err, b"unknown scene `x`")]);
        let error = console.ok(&Command::Draw { scene: "x", method: None }).unwrap_err().to_string();
        assert_eq!(error, "`DRAW x` answered ERR \"unknown scene `x`\"");
    }

    #[test]
    fn a_dump_splits_into_framebuffer_and_palette() {
        let mut payload = vec![7; FRAMEBUFFER_LEN];
        payload.extend((0..ENTRIES as u32 * 3).map(|i| (i % 64) as u8));
        let (mut console, _, _keep) = console(&[(FrameKind::Dump, &payload)]);
        let dump = console.dump().unwrap();
        assert_eq!(dump.pixels, vec![7; FRAMEBUFFER_LEN]);
        assert_eq!(dump.palette[1], [3, 4, 5]);
        // Every pixel is index 7, whose DAC entry (21, 22, 23) widens to 8 bits.
        assert_eq!(dump.image().color(0), [87, 88, 95]);
    }

    #[test]
    fn a_bench_reply_comes_back_as_its_rows_and_a_malformed_one_is_an_error_quoting_it() {
        let row = |method, cycles, refused, refusal| BenchRow { method, cycles, refused, refusal };
        let rows = vec![
            row(MethodId::Pendleton, 1200, 2, Some(raster::Refusal::MultipleContours)),
            row(MethodId::Exact, 900, 0, None),
        ];
        let payload = BenchReply { rows: rows.clone() }.to_string();
        let (mut console, sent, _keep) =
            console(&[(FrameKind::Bench, payload.as_bytes()), (FrameKind::Bench, b"exact 900 0\n")]);
        assert_eq!(console.bench("abrash38-1", 3).unwrap(), rows);
        assert_eq!(sent.0.lock().unwrap().as_slice(), b"BENCH abrash38-1 3\n");
        let error = format!("{:#}", console.bench("abrash38-1", 3).unwrap_err());
        assert_eq!(
            error,
            "waiting for the reply to `BENCH abrash38-1 3`: BENCH \"exact 900 0\\n\": malformed BENCH reply: expected \
             its unit line first"
        );
    }

    #[test]
    fn draw_and_clear_answers_are_read_back_and_a_wrong_one_is_an_error() {
        let (mut console, sent, _keep) = console(&[
            (FrameKind::Ok, b"clear 0"),
            (FrameKind::Ok, b"polygons=5 refused=1 strays=2"),
            (FrameKind::Ok, b"clear 1"),
            (FrameKind::Ok, b"clear 0"),
            (FrameKind::Ok, b"drawn"),
        ]);
        let drawn = console.draw("abrash38-1", Some(MethodId::Wgt)).unwrap();
        assert_eq!(drawn, DrawReply { polygons: 5, refused: 1, strays: 2 });
        let error = console.draw("abrash38-1", None).unwrap_err().to_string();
        assert_eq!(error, "`CLEAR 0` answered OK \"clear 1\", another colour");
        let error = format!("{:#}", console.draw("abrash38-1", None).unwrap_err());
        assert_eq!(
            error,
            "`DRAW abrash38-1` answered OK \"drawn\": malformed DRAW reply: expected the field `polygons=` next"
        );
        assert_eq!(
            sent.0.lock().unwrap().as_slice(),
            b"CLEAR 0\nDRAW abrash38-1 wgt\nCLEAR 0\nCLEAR 0\nDRAW abrash38-1\n"
        );
    }

    #[test]
    fn a_list_line_of_no_known_shape_is_an_error() {
        let (mut console, _, _keep) = console(&[(FrameKind::List, b"colour 4\n")]);
        let error = format!("{:#}", console.list().unwrap_err());
        let expected = "waiting for the reply to `LIST`: LIST \"colour 4\\n\": malformed LIST reply: expected lines";
        assert!(error.starts_with(expected), "{error}");
    }

    #[test]
    fn a_show_reply_names_an_entry_of_the_show_and_garbage_is_an_error() {
        let reply = ShowReply {
            entry: "race",
            frame: 30,
            method: MethodId::AbrashInt,
            cycles: 9,
            allocs: 0,
            polygons: 4,
            refused: 0,
            strays: 0,
        };
        let text = reply.to_string();
        let stranger = text.replace("entry=race", "entry=rice");
        let (mut console, sent, _keep) = console(&[
            (FrameKind::Ok, text.as_bytes()),
            (FrameKind::Ok, b"drawn"),
            (FrameKind::Ok, stranger.as_bytes()),
        ]);
        assert_eq!(console.show("race", 30, None).unwrap(), reply);
        let error = format!("{:#}", console.show("race", 0, Some(MethodId::Exact)).unwrap_err());
        assert_eq!(
            error,
            "`SHOW race 0 exact` answered OK \"drawn\", not a SHOW reply: malformed SHOW reply: expected the field \
             `entry=` next"
        );
        let error = console.show("race", 30, None).unwrap_err().to_string();
        assert_eq!(error, format!("`SHOW race 30` answered OK \"{stranger}\", naming an entry the show does not have"));
        assert_eq!(sent.0.lock().unwrap().as_slice(), b"SHOW race 30\nSHOW race 0 exact\nSHOW race 30\n");
    }

    #[test]
    fn a_ready_or_pong_of_the_wrong_shape_is_an_error() {
        let (mut console, _, _keep) = console(&[(FrameKind::Ready, b"vga: 0 mismatches"), (FrameKind::Ok, b"pong")]);
        let error = console.wait_ready().unwrap_err().to_string();
        assert_eq!(error, "READY \"vga: 0 mismatches\" does not parse");
        let error = format!("{:#}", console.ping().unwrap_err());
        assert_eq!(
            error,
            "`PING` answered OK \"pong\", not a pong: malformed PING reply: expected `pong` and its fields"
        );
    }

    #[test]
    fn log_frames_do_not_extend_the_deadline_of_a_reply() {
        let (console, _, sender) = console(&[]);
        // A kernel that logs every 20 ms and never answers.
        std::thread::spawn(move || {
            let payload = b"COM1: its interrupt (IRQ 4) did not arrive; receiving by polling alone";
            let mut frame = format!("{}\n", FrameHeader::for_payload(FrameKind::Log, payload)).into_bytes();
            frame.extend_from_slice(payload);
            frame.push(b'\n');
            while sender.send(frame.clone()).is_ok() {
                std::thread::sleep(Duration::from_millis(20));
            }
        });
        let (done, outcome) = mpsc::channel();
        std::thread::spawn(move || {
            let mut console = console;
            let _ = done.send(console.reply_within(Duration::from_millis(300)).map_err(|e| e.to_string()));
        });
        // Far beyond the 300 ms deadline, to stay clear of a busy machine.
        let error =
            outcome.recv_timeout(Duration::from_secs(20)).expect("the wait for a reply never ended").unwrap_err();
        assert!(error.starts_with("no reply within 0.3 s, only "), "{error}");
    }

    #[test]
    fn a_first_frame_other_than_ready_is_an_error() {
        let (mut console, _, _keep) = console(&[(FrameKind::Fatal, b"panic: at boot")]);
        let error = console.wait_ready().unwrap_err().to_string();
        assert_eq!(error, "the kernel's first frame is FATAL \"panic: at boot\", not READY");
    }

    #[test]
    fn a_log_err_or_fatal_text_the_protocol_does_not_write_is_an_error() {
        for (kind, text) in [
            (FrameKind::Log, "vga: CRTC 0x11 reads 0x0e"),
            (FrameKind::Err, "no such thing"),
            (FrameKind::Fatal, "panic at boot"),
        ] {
            let (mut console, _, _keep) = console(&[(kind, text.as_bytes())]);
            let error = format!("{:#}", console.reply_within(Duration::from_secs(10)).unwrap_err());
            assert!(error.starts_with(&format!("{} \"{text}\": malformed", kind.name())), "{error}");
        }
    }
}
