//! Warning lines about a file's values, capped per kind of chunk: a
//! hostile file can hold a warning every few bytes (a camera every 20, a
//! material key every 12), MagicaVoxel's own files a handful.

use std::format;
use std::string::String;
use std::vec::Vec;

/// The most lines one kind of chunk lists; the rest are counted.
pub(crate) const MAX_WARNINGS: usize = 16;

/// The first [`MAX_WARNINGS`] lines about one kind of chunk, and a count
/// of the rest.
pub(crate) struct Capped {
    kind: &'static str,
    lines: Vec<String>,
    more: usize,
}

impl Capped {
    /// No lines yet about chunks of `kind` ("MATL", "rCAM").
    pub(crate) fn new(kind: &'static str) -> Capped {
        Capped {
            kind,
            lines: Vec::new(),
            more: 0,
        }
    }

    /// Keeps `line`, or counts it once [`MAX_WARNINGS`] are kept.
    pub(crate) fn push(&mut self, line: String) {
        if self.lines.len() < MAX_WARNINGS {
            self.lines.push(line);
        } else {
            self.more += 1;
        }
    }

    /// Appends the lines kept to `out`, then "... and N more KIND
    /// warnings" when some were only counted.
    pub(crate) fn append_to(self, out: &mut Vec<String>) {
        out.extend(self.lines);
        if self.more > 0 {
            out.push(format!("... and {} more {} warnings", self.more, self.kind));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec;

    #[test]
    fn keeps_the_first_lines_and_counts_the_rest() {
        let mut out = vec![String::from("before")];
        let mut few = Capped::new("MATL");
        few.push("one".into());
        few.append_to(&mut out);
        assert_eq!(out, ["before", "one"]);
        let mut many = Capped::new("rCAM");
        for i in 0..MAX_WARNINGS + 5 {
            many.push(format!("line {i}"));
        }
        let mut out = Vec::new();
        many.append_to(&mut out);
        assert_eq!(out.len(), MAX_WARNINGS + 1);
        assert_eq!(out[MAX_WARNINGS - 1], format!("line {}", MAX_WARNINGS - 1));
        assert_eq!(out[MAX_WARNINGS], "... and 5 more rCAM warnings");
    }
}
