//! A progress bar on stderr for renders long enough to need one: drawn only
//! when stderr is a terminal, and only once the work has taken a second.

use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// How long work runs before its bar appears: a quick render prints nothing.
const QUIET_FOR: Duration = Duration::from_secs(1);

/// Counts finished rows; safe to advance from worker threads.
pub struct Progress {
    bar: Option<ProgressBar>,
    started: Instant,
    shown: AtomicBool,
}

impl Progress {
    /// A bar over `rows` rows, hidden unless stderr is a terminal.
    pub fn rows(rows: u32) -> Progress {
        let bar = std::io::stderr().is_terminal().then(|| {
            let style = ProgressStyle::with_template(
                "{elapsed_precise} [{bar:40}] {pos}/{len} rows, {eta} left",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> ");
            ProgressBar::with_draw_target(Some(u64::from(rows)), ProgressDrawTarget::hidden())
                .with_style(style)
        });
        Progress {
            bar,
            started: Instant::now(),
            shown: AtomicBool::new(false),
        }
    }

    /// Records `rows` more finished rows.
    pub fn advance(&self, rows: u32) {
        let Some(bar) = &self.bar else { return };
        bar.inc(u64::from(rows));
        if self.started.elapsed() >= QUIET_FOR && !self.shown.swap(true, Ordering::Relaxed) {
            bar.set_draw_target(ProgressDrawTarget::stderr());
        }
    }

    /// Removes the bar, leaving stderr as it was before.
    pub fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}
