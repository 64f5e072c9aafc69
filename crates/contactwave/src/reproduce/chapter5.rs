//! Thesis chapter 5 studies.

use super::{Chapter, ChapterResult, Ctx};
use crate::error::Result;

pub(crate) fn run(_ctx: &Ctx) -> Result<ChapterResult> {
    Ok(ChapterResult {
        chapter: Chapter::Five,
        title: "Chapter 5".into(),
        intro: String::new(),
        figures: Vec::new(),
        findings: Vec::new(),
        seconds: 0.0,
        runs: 0,
    })
}
