//! What an import could not draw as the SVG asks, gathered by topic so
//! that a drawing of a thousand translucent paths says so in one line.

/// How many elements a note names before it counts the rest.
const NAMED: usize = 8;

/// Notes by topic, in the order the topics were first met, each with the
/// elements it concerns in document order.
#[derive(Default)]
pub(crate) struct Notes {
    topics: Vec<(&'static str, Vec<String>)>,
}

impl Notes {
    /// `element` (a name and what happened to it) under `topic`.
    pub(crate) fn add(&mut self, topic: &'static str, element: String) {
        match self.topics.iter_mut().find(|(known, _)| *known == topic) {
            Some((_, elements)) => elements.push(element),
            None => self.topics.push((topic, vec![element])),
        }
    }

    /// One line per topic: `topic: a, b, c` naming at most [`NAMED`]
    /// elements, then how many more.
    pub(crate) fn lines(&self) -> Vec<String> {
        self.topics
            .iter()
            .map(|(topic, elements)| {
                let named = elements[..elements.len().min(NAMED)].join("; ");
                match elements.len().checked_sub(NAMED) {
                    Some(more) if more > 0 => format!("{topic}: {named}; and {more} more"),
                    _ => format!("{topic}: {named}"),
                }
            })
            .collect()
    }
}

/// A name for an element in notes and errors: `KIND #ID`, or, for one
/// with no id, `KIND N (no id)` where `N` counts that kind from 1 in
/// document order.
pub(crate) fn element_name(kind: &str, id: &str, number: usize) -> String {
    if id.is_empty() {
        format!("{kind} {number} (no id)")
    } else {
        format!("{kind} #{id}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn notes_gather_by_topic_and_count_past_the_named() {
        let mut notes = Notes::default();
        for i in 0..10 {
            notes.add("opacity below 1, drawn opaque", element_name("shape", "", i + 1));
        }
        notes.add("masks ignored", element_name("group", "shadow", 1));
        let lines = notes.lines();
        assert_eq!(lines.len(), 2);
        assert!(lines[0].starts_with("opacity below 1, drawn opaque: shape 1 (no id); shape 2 (no id); "), "{lines:?}");
        assert!(lines[0].ends_with("; shape 8 (no id); and 2 more"), "{lines:?}");
        assert_eq!(lines[1], "masks ignored: group #shadow");
    }
}
