//! Thesis chapter 3 studies.

use super::{Chapter, ChapterResult, Ctx};
use crate::error::Result;

pub(crate) fn run(_ctx: &Ctx) -> Result<ChapterResult> {
    Ok(ChapterResult {
        chapter: Chapter::Three,
        title: "Chapter 3".into(),
        intro: String::new(),
        figures: Vec::new(),
        findings: Vec::new(),
        seconds: 0.0,
        runs: 0,
    })
}
