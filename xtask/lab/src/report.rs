use crate::results::Results;
pub fn markdown(_r: &Results) -> String { String::new() }
