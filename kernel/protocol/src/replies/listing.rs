//! The `LIST` frame's payload: what the kernel can draw and with what.

use alloc::string::{String, ToString};
use alloc::vec::Vec;
use core::fmt;

use super::fields::{Expected, Malformed};

/// The `LIST` frame's payload: a `scene NAME` line per built-in scene, a
/// `show NAME FRAMES` line per show entry in demo order, then a `method
/// NAME` line per method, each ending in `\n`.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct Listing {
    pub scenes: Vec<String>,
    /// The show's entries in demo order: name and number of frames.
    pub shows: Vec<(String, u32)>,
    pub methods: Vec<String>,
}

impl fmt::Display for Listing {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.scenes.iter().try_for_each(|name| writeln!(f, "scene {name}"))?;
        self.shows.iter().try_for_each(|(name, frames)| writeln!(f, "show {name} {frames}"))?;
        self.methods.iter().try_for_each(|name| writeln!(f, "method {name}"))
    }
}

impl Listing {
    /// Parses the payload written by `Display`: lines each ended by `\n`,
    /// names of printable ASCII without spaces.
    pub fn parse(text: &str) -> Result<Self, Malformed> {
        let malformed = |expected| Malformed { reply: "LIST", expected };
        let shape = "lines `scene NAME`, `show NAME FRAMES` and `method NAME`, each ended by a newline";
        let mut listing = Listing::default();
        let Some(body) = text.strip_suffix('\n') else {
            return if text.is_empty() { Ok(listing) } else { Err(malformed(Expected::Shape(shape))) };
        };
        fn name(word: Option<&str>) -> Option<&str> {
            word.filter(|name| !name.is_empty() && name.bytes().all(|byte| byte.is_ascii_graphic()))
        }
        for line in body.split('\n') {
            let mut words = line.split(' ');
            match (words.next(), name(words.next()), words.next(), words.next()) {
                (Some("scene"), Some(name), None, None) => listing.scenes.push(name.to_string()),
                (Some("method"), Some(name), None, None) => listing.methods.push(name.to_string()),
                (Some("show"), Some(name), Some(frames), None) => {
                    let frames = frames.parse().map_err(|_| malformed(Expected::Value("FRAMES")))?;
                    listing.shows.push((name.to_string(), frames));
                }
                _ => return Err(malformed(Expected::Shape(shape))),
            }
        }
        Ok(listing)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use alloc::vec;
    use std::string::ToString;

    #[test]
    fn listings_round_trip_and_reject_garbage() {
        let listing = Listing {
            scenes: vec!["abrash38-1".into(), "abrash40-2".into()],
            shows: vec![("race".into(), 240)],
            methods: vec!["abrash_float".into(), "exact".into()],
        };
        let text = listing.to_string();
        assert_eq!(text, "scene abrash38-1\nscene abrash40-2\nshow race 240\nmethod abrash_float\nmethod exact\n");
        assert_eq!(Listing::parse(&text), Ok(listing));
        assert_eq!(Listing::parse(""), Ok(Listing::default()), "an empty listing");
        let shape =
            Expected::Shape("lines `scene NAME`, `show NAME FRAMES` and `method NAME`, each ended by a newline");
        for (garbage, expected) in [
            ("show race many\n", Expected::Value("FRAMES")),
            ("show race\n", shape),
            ("colour 4\n", shape),
            ("scene a b\n", shape),
            ("scene abrash38-1\n\n", shape),
            ("scene abrash38-1", shape),
            // Found by the `command` fuzz target: `lines()` took the `\r`
            // for a line ending, and the name came back other than read.
            ("scene \r", shape),
            ("scene \r\n", shape),
            ("scene \n", shape),
            ("method a\tb\n", shape),
        ] {
            assert_eq!(Listing::parse(garbage), Err(Malformed { reply: "LIST", expected }), "{garbage:?}");
        }
    }
}
