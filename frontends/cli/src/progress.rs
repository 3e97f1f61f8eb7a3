//! Progress on stderr for work long enough to need it: drawn only when
//! stderr is a terminal, and only once the work has taken a second,
//! whether or not a step has finished by then (one row of a render at
//! `--spp 4096 --ao 4096` can take longer than that).

use std::io::IsTerminal;
use std::sync::{Arc, Condvar, Mutex};
use std::time::Duration;

use indicatif::{HumanDuration, ProgressBar, ProgressDrawTarget, ProgressState, ProgressStyle};

/// How long work runs before its progress appears: a quick run prints
/// nothing.
const QUIET_FOR: Duration = Duration::from_secs(1);

/// How often a shown bar redraws on its own, so that its clock runs
/// between steps.
const TICK: Duration = Duration::from_millis(120);

/// A bar kept hidden until the work has taken a while, then drawn to its
/// target and redrawn every [`TICK`] until it is finished.
struct Delayed {
    bar: ProgressBar,
    /// Whether the work has ended, and the signal that wakes the timer
    /// when it does.
    finished: Arc<(Mutex<bool>, Condvar)>,
}

impl Delayed {
    /// Starts the timer of `bar` (drawn to a hidden target until then):
    /// after `quiet`, unless finished, it draws to `target`.
    fn start(bar: ProgressBar, target: ProgressDrawTarget, quiet: Duration) -> Delayed {
        let finished = Arc::new((Mutex::new(false), Condvar::new()));
        let (shown, gate) = (bar.clone(), Arc::clone(&finished));
        // Detached: it ends at the deadline, or as soon as the work does.
        std::thread::spawn(move || {
            let (lock, ended) = &*gate;
            let finished = lock.lock().unwrap_or_else(|e| e.into_inner());
            // Under the lock: `finish` either came first or waits for this.
            let (finished, _) = ended
                .wait_timeout_while(finished, quiet, |finished| !*finished)
                .unwrap_or_else(|e| e.into_inner());
            if !*finished {
                shown.set_draw_target(target);
                shown.enable_steady_tick(TICK);
            }
        });
        Delayed { bar, finished }
    }

    /// Removes the bar, leaving the target as it was before.
    fn finish(&self) {
        let (lock, ended) = &*self.finished;
        let mut finished = lock.lock().unwrap_or_else(|e| e.into_inner());
        *finished = true;
        ended.notify_all();
        self.bar.finish_and_clear();
    }
}

impl Drop for Delayed {
    fn drop(&mut self) {
        self.finish();
    }
}

/// Stderr when it is a terminal: where progress is drawn.
fn terminal() -> Option<ProgressDrawTarget> {
    std::io::stderr()
        .is_terminal()
        .then(ProgressDrawTarget::stderr)
}

/// The time left, once a row has finished to estimate it from (before,
/// indicatif's estimate reads "0s").
fn time_left(state: &ProgressState, out: &mut dyn std::fmt::Write) {
    let _ = match state.pos() {
        0 => write!(out, "?"),
        _ => write!(out, "{}", HumanDuration(state.eta())),
    };
}

/// Counts finished rows; safe to advance from worker threads.
pub struct Progress {
    shown: Option<Delayed>,
}

impl Progress {
    /// A bar over `rows` rows, drawn only on a terminal.
    pub fn rows(rows: u32) -> Progress {
        Progress::rows_to(rows, terminal(), QUIET_FOR)
    }

    /// A bar over `rows` rows drawn to `target` (none: nowhere) once
    /// `quiet` has passed.
    fn rows_to(rows: u32, target: Option<ProgressDrawTarget>, quiet: Duration) -> Progress {
        let shown = target.map(|target| {
            let style = ProgressStyle::with_template(
                "{elapsed_precise} [{bar:40}] {pos}/{len} rows, {left} left",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> ")
            .with_key("left", time_left);
            let bar =
                ProgressBar::with_draw_target(Some(u64::from(rows)), ProgressDrawTarget::hidden())
                    .with_style(style);
            Delayed::start(bar, target, quiet)
        });
        Progress { shown }
    }

    /// Records `rows` more finished rows.
    pub fn advance(&self, rows: u32) {
        if let Some(shown) = &self.shown {
            shown.bar.inc(u64::from(rows));
        }
    }

    /// Removes the bar, leaving stderr as it was before.
    pub fn finish(&self) {
        if let Some(shown) = &self.shown {
            shown.finish();
        }
    }
}

/// A spinner with the elapsed time for work that reports no steps (a
/// storage build): drawn only on a terminal, and only once the work has
/// taken a second; removed when dropped.
pub struct Spinner {
    _shown: Option<Delayed>,
}

impl Spinner {
    /// Starts the timer for `message` (e.g. "building the octree scene").
    pub fn start(message: String) -> Spinner {
        let shown = terminal().map(|target| {
            let style = ProgressStyle::with_template("{elapsed_precise} {spinner} {msg}")
                .unwrap_or_else(|_| ProgressStyle::default_spinner());
            let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden())
                .with_style(style)
                .with_message(message);
            Delayed::start(bar, target, QUIET_FOR)
        });
        Spinner { _shown: shown }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use indicatif::TermLike;

    /// A terminal that keeps what is written to it.
    #[derive(Debug, Clone, Default)]
    struct Recorder(Arc<Mutex<String>>);

    impl Recorder {
        fn text(&self) -> String {
            self.0.lock().unwrap().clone()
        }
    }

    impl TermLike for Recorder {
        fn width(&self) -> u16 {
            120
        }
        fn move_cursor_up(&self, _: usize) -> std::io::Result<()> {
            Ok(())
        }
        fn move_cursor_down(&self, _: usize) -> std::io::Result<()> {
            Ok(())
        }
        fn move_cursor_right(&self, _: usize) -> std::io::Result<()> {
            Ok(())
        }
        fn move_cursor_left(&self, _: usize) -> std::io::Result<()> {
            Ok(())
        }
        fn write_line(&self, s: &str) -> std::io::Result<()> {
            self.write_str(&format!("{s}\n"))
        }
        fn write_str(&self, s: &str) -> std::io::Result<()> {
            self.0.lock().unwrap().push_str(s);
            Ok(())
        }
        fn clear_line(&self) -> std::io::Result<()> {
            Ok(())
        }
        fn flush(&self) -> std::io::Result<()> {
            Ok(())
        }
    }

    fn recorded(quiet: Duration) -> (Progress, Recorder) {
        let term = Recorder::default();
        let target = ProgressDrawTarget::term_like(Box::new(term.clone()));
        (Progress::rows_to(16, Some(target), quiet), term)
    }

    #[test]
    fn the_bar_shows_before_any_row_is_done() {
        // A render whose first row outlasts the quiet time: the bar must
        // appear anyway, at 0 rows, and keep its clock running.
        let (progress, term) = recorded(Duration::ZERO);
        // Waits for the timer thread (bounded: a hang fails, not a slow
        // machine; nothing here is timed).
        for _ in 0..1000 {
            if term.text().contains("0/16 rows") {
                break;
            }
            std::thread::sleep(Duration::from_millis(10));
        }
        assert!(
            term.text().contains("0/16 rows, ? left"),
            "{:?}",
            term.text()
        );
        progress.advance(3);
        progress.finish();
        // Finished: nothing is drawn any more.
        let after = term.text();
        progress.advance(1);
        std::thread::sleep(TICK * 2);
        assert_eq!(term.text(), after);
    }

    #[test]
    fn a_quick_run_draws_nothing() {
        let (progress, term) = recorded(Duration::from_secs(3600));
        progress.advance(16);
        progress.finish();
        assert_eq!(term.text(), "");
    }
}
