use crate::results::Results;
pub fn draw_all(_r: &Results, _o: &std::path::Path) -> anyhow::Result<()> { Ok(()) }
