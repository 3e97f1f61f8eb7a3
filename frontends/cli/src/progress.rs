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

/// A spinner with the elapsed time for work that reports no steps (a
/// storage build): drawn only on a terminal, and only once the work has
/// taken a second; removed when dropped.
pub struct Spinner {
    bar: Option<ProgressBar>,
    /// Dropped (disconnected) when the work ends, waking the timer thread.
    done: Option<std::sync::mpsc::Sender<()>>,
}

impl Spinner {
    /// Starts the timer for `message` (e.g. "building the octree scene").
    pub fn start(message: String) -> Spinner {
        if !std::io::stderr().is_terminal() {
            return Spinner {
                bar: None,
                done: None,
            };
        }
        let style = ProgressStyle::with_template("{elapsed_precise} {spinner} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_spinner());
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden())
            .with_style(style)
            .with_message(message);
        let (done, wait) = std::sync::mpsc::channel::<()>();
        let shown = bar.clone();
        // Detached: it ends after a second, or as soon as the work does.
        std::thread::spawn(move || {
            let late =
                wait.recv_timeout(QUIET_FOR) == Err(std::sync::mpsc::RecvTimeoutError::Timeout);
            if late && !shown.is_finished() {
                shown.set_draw_target(ProgressDrawTarget::stderr());
                shown.enable_steady_tick(Duration::from_millis(120));
            }
        });
        Spinner {
            bar: Some(bar),
            done: Some(done),
        }
    }
}

impl Drop for Spinner {
    fn drop(&mut self) {
        drop(self.done.take());
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}
