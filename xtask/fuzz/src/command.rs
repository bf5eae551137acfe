//! The `command` target: any bytes as a command line, through the
//! protocol's parser (the code the kernel runs on every line it reads),
//! and as the texts the host parses from the kernel's frames. Nothing
//! panics; every accepted command formats back to a line that parses to
//! the same command; a `POLY` command's polygon, when the kernel's
//! `parse_poly` takes it, fills with the command's method inside the
//! screen; every accepted reply text or frame header formats back to
//! itself parsed again. A line that opens as a sealed one opens to the
//! command it seals, which seals again to the same line.

use protocol::{
    unseal, BenchReply, BenchRow, Cleared, Command, CommandError, DemoReply, DrawReply, EndedAt, ErrorReply,
    FatalReport, FaultKind, FrameHeader, FrameKind, LineErrors, LineLosses, Listing, LogEvent, Machine,
    MachineEvidence, Mismatch, PageFaultCode, PciAddress, PciId, Pong, Raised, Ready, RegisterGroup, Sealed, ShowReply,
    StrayRaised, TscRate, VgaCheck, BENCH_MAX_REPEATS,
};
use raster::{CoverageSink, MethodId, Refusal, SCREEN};
use scenes::file;

pub fn check(data: &[u8]) {
    if let Ok((Some(seq), sealed)) = unseal(data) {
        if let Ok(command) = Command::parse(sealed) {
            let line = Sealed { seq, command: &command }.to_string();
            assert_eq!(unseal(line.as_bytes()), Ok((Some(seq), command.to_string().as_bytes())), "{line:?}");
        }
    }
    if let Ok(command) = Command::parse(data) {
        let line = command.to_string();
        assert_eq!(Command::parse(line.as_bytes()), Ok(command), "{command:?} formats as {line:?}");
        if let Command::Poly { method, spec } = command {
            if let Ok(polygon) = file::parse_poly(spec) {
                let mut sink = CoverageSink::new(SCREEN);
                let _ = method.method().fill(&polygon, &mut sink);
                assert_eq!(sink.out_of_bounds(), 0, "{method} drew {spec:?} outside the screen");
            }
        }
    }
    let Ok(text) = std::str::from_utf8(data) else { return };
    if let Ok(reply) = ShowReply::parse(text) {
        assert_eq!(ShowReply::parse(&reply.to_string()), Ok(reply.clone()), "{text:?}");
    }
    if let Ok(pong) = Pong::parse(text) {
        assert_eq!(Pong::parse(&pong.to_string()), Ok(pong), "{text:?}");
    }
    if let Ok(ready) = Ready::parse(text) {
        assert_eq!(Ready::parse(&ready.to_string()), Ok(ready), "{text:?}");
    }
    if let Ok(rate) = TscRate::parse(text) {
        assert_eq!(TscRate::parse(&rate.to_string()), Ok(rate), "{text:?}");
    }
    if let Ok(drawn) = DrawReply::parse(text) {
        assert_eq!(DrawReply::parse(&drawn.to_string()), Ok(drawn), "{text:?}");
    }
    if let Ok(cleared) = Cleared::parse(text) {
        assert_eq!(Cleared::parse(&cleared.to_string()), Ok(cleared), "{text:?}");
    }
    if let Ok(demo) = DemoReply::parse(text) {
        assert_eq!(DemoReply::parse(&demo.to_string()), Ok(demo), "{text:?}");
    }
    if let Ok(bench) = BenchReply::parse(text) {
        assert_eq!(BenchReply::parse(&bench.to_string()), Ok(bench.clone()), "{text:?}");
    }
    if let Ok(listing) = Listing::parse(text) {
        assert_eq!(Listing::parse(&listing.to_string()), Ok(listing.clone()), "{text:?}");
    }
    if let Ok(event) = LogEvent::parse(text) {
        assert_eq!(LogEvent::parse(&event.to_string()), Ok(event), "{text:?}");
    }
    if let Ok(error) = ErrorReply::parse(text) {
        assert_eq!(ErrorReply::parse(&error.to_string()), Ok(error.clone()), "{text:?}");
    }
    if let Ok(report) = FatalReport::parse(text) {
        assert_eq!(FatalReport::parse(&report.to_string()), Ok(report), "{text:?}");
    }
    if let Ok(check) = VgaCheck::parse(text) {
        assert_eq!(VgaCheck::parse(&check.to_string()), Ok(check.clone()), "{text:?}");
    }
    if let Ok(raised) = StrayRaised::parse(text) {
        assert_eq!(StrayRaised::parse(&raised.to_string()), Ok(raised), "{text:?}");
    }
    if let Some(header) = FrameHeader::parse(text) {
        assert_eq!(FrameHeader::parse(&header.to_string()), Some(header), "{text:?}");
    }
}

/// A command line of every kind with every built-in scene, show entry and
/// method, each built-in polygon as a `POLY`, and a text of each reply.
pub fn seeds() -> Vec<(String, Vec<u8>)> {
    let mut commands = vec![
        Command::Ping,
        Command::List,
        Command::Dump,
        Command::VgaCheck,
        Command::Clear(7),
        Command::Exit(16),
        Command::Demo { entry: None, method: None },
        Command::Ready,
        Command::Clock,
    ];
    for page in &scenes::builtin::ALL {
        commands.push(Command::Draw { scene: page.name, method: None });
        commands.push(Command::Bench { scene: page.name, repeats: BENCH_MAX_REPEATS });
    }
    for entry in scenes::show::ENTRIES_IN_ORDER {
        commands.push(Command::Show { entry: entry.name, frame: entry.frames - 1, method: None });
        commands.push(Command::Demo { entry: Some(entry.name), method: None });
    }
    for method in MethodId::ALL {
        commands.push(Command::Draw { scene: "abrash38-1", method: Some(method) });
        commands.push(Command::Show { entry: "race", frame: 0, method: Some(method) });
        commands.push(Command::Demo { entry: None, method: Some(method) });
    }
    commands.extend(FaultKind::ALL.map(Command::Fault));
    let mut seeds: Vec<(String, Vec<u8>)> = commands
        .iter()
        .enumerate()
        .map(|(i, command)| (format!("command-{i}"), command.to_string().into_bytes()))
        .collect();
    seeds.extend(
        commands
            .iter()
            .enumerate()
            .map(|(i, command)| (format!("sealed-{i}"), Sealed { seq: i as u32, command }.to_string().into_bytes())),
    );
    let polygons = scenes::builtin::ALL.iter().flat_map(|page| page.scene().ops).filter_map(|op| match op {
        scenes::Op::Fill(polygon) => Some(polygon),
        scenes::Op::Clear(_) => None,
    });
    for (i, polygon) in polygons.enumerate().step_by(7) {
        let line = file::poly_line(&polygon);
        let spec = line.strip_prefix("poly ").unwrap_or(&line);
        seeds.push((format!("poly-{i}"), format!("POLY exact {spec}").into_bytes()));
    }
    let show = ShowReply {
        entry: "race",
        frame: 3,
        method: MethodId::Wgt,
        cycles: 12345,
        allocs: 2,
        polygons: 44,
        refused: 0,
        strays: 0,
    };
    // As a kernel of today writes them, every field there, and as an older
    // one did (the defaults leave the later fields out).
    let errors = Some(LineErrors { framing: 1, parity: 0, breaks: 2 });
    let losses = LineLosses { overruns: 0, dropped: 3, errors };
    let ready = Ready {
        machine: Some(Machine::Qemu),
        display: Some(PciId { vendor: 0x1234, device: 0x1111 }),
        display_at: Some(PciAddress { bus: 0, device: 2, function: 0 }),
        memory: Some(protocol::MemoryType::Uncacheable),
        losses,
        ..Ready::default()
    };
    let interrupts = Some(protocol::InterruptCounts { nmis: 1, stray: 2 });
    let readings = protocol::ClockReadings {
        pit: Some(2_593_000_000),
        pm_timer: Some(2_593_100_000),
        hpet: Some(2_592_900_000),
        cpuid: None,
    };
    let replies = [
        show.to_string(),
        Pong::default().to_string(),
        Ready::default().to_string(),
        Pong { losses, interrupts, ..Pong::default() }.to_string(),
        ready.to_string(),
        FrameHeader::for_payload(FrameKind::Ok, b"pong").to_string(),
        FrameHeader::for_reply(FrameKind::Ok, b"pong", Some(17)).to_string(),
        TscRate { hz: 2_593_000_000, source: protocol::ClockSource::Pit, readings }.to_string(),
        DrawReply { polygons: 9, refused: 1, strays: 2 }.to_string(),
        Cleared { color: 7 }.to_string(),
        DemoReply { from: "race", stay: true, method: Some(MethodId::Wgt) }.to_string(),
        BenchReply {
            rows: vec![
                BenchRow { method: MethodId::Pendleton, cycles: 1200, refused: 2, refusal: Some(Refusal::OutOfRange) },
                BenchRow { method: MethodId::Exact, cycles: 900, refused: 0, refusal: None },
            ],
        }
        .to_string(),
        Listing { scenes: vec!["abrash38-1".into()], shows: vec![("race".into(), 240)], methods: vec!["exact".into()] }
            .to_string(),
        LogEvent::Machine(MachineEvidence {
            machine: Machine::Qemu,
            hypervisor: Some(*b"TCGTCGTCGTCG"),
            board: Some(PciId { vendor: 0x1af4, device: 0x1100 }),
        })
        .to_string(),
        LogEvent::Nmi { count: 1, reason: 0x20, serr: false, iochk: false }.to_string(),
        LogEvent::StrayInterrupt { vector: 0x99, count: 2, ended: EndedAt::LocalApic }.to_string(),
        LogEvent::LineDropped { overlong: true, kept: 6, idle_seconds: 10 }.to_string(),
        ErrorReply::Command(CommandError::UnknownMethod("exakt")).to_string(),
        ErrorReply::UnknownShowEntry("nope").to_string(),
        ErrorReply::NotQemu("EXIT").to_string(),
        FatalReport::PageFault { address: 0xdeadbeef000, code: PageFaultCode::new(2), at: 0x20_0000 }.to_string(),
        FatalReport::Exception { vector: 13, error: Some(0x10), at: 0x20_0000 }.to_string(),
        FatalReport::Panic("panicked at src/fault.rs:60:30:\nFAULT panic").to_string(),
        VgaCheck::Vga {
            mismatches: vec![Mismatch { group: RegisterGroup::Dac, index: 4, expected: 0, actual: 63 }],
            window: None,
            pat: 0x0007_0406_0007_0406,
        }
        .to_string(),
        StrayRaised { vector: 0x99, raised: Raised::LocalApic, taken: 1 }.to_string(),
    ];
    seeds.extend(replies.into_iter().enumerate().map(|(i, text)| (format!("reply-{i}"), text.into_bytes())));
    seeds
}

/// The words of the protocol.
pub fn dictionary() -> Vec<String> {
    let mut words: Vec<String> = [
        "PING", "LIST", "DRAW", "SHOW", "CLEAR", "POLY", "DUMP", "BENCH", "VGACHECK", "DEMO", "EXIT", "FAULT", "READY",
        "CLOCK", "*", "#",
    ]
    .map(String::from)
    .into();
    words.extend(MethodId::ALL.map(|method| method.name().to_string()));
    words.extend(FaultKind::ALL.map(|kind| kind.name().to_string()));
    words.extend(scenes::show::ENTRIES_IN_ORDER.iter().map(|entry| entry.name.to_string()));
    words.extend(FrameKind::ALL.map(|kind| format!("@{}", kind.name())));
    words.extend(
        ["entry=", "frame=", "method=", "cycles=", "allocs=", "polygons=", "refused=", "strays=", "pong", "overruns="]
            .map(String::from),
    );
    words.extend(
        [
            "dropped=",
            "heap_used=",
            "heap_free_largest=",
            "display=",
            "display_at=",
            "machine=",
            "qemu",
            "unknown",
            "framing=",
            "parity=",
            "breaks=",
            "none",
            "vga_mismatches=",
            "color=",
            "rule=",
            "nonzero",
            "|",
            "tsc_hz=",
            "source=",
            "clear ",
            "demo ",
            "from=",
            "stay=",
            "own",
            "scene ",
            "show ",
            "method ",
            protocol::BENCH_UNIT_LINE,
        ]
        .map(String::from),
    );
    words
}
