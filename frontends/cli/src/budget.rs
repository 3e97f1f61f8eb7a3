//! `--time-limit`: a path-traced frame's samples taken in rounds over the
//! whole frame until its time budget is spent, and what `--stats` says of
//! it so that the frame can be made again, byte for byte, without a
//! clock.
//!
//! The clock decides only how many whole rounds a frame takes, and only
//! between rounds: the frame after `n` rounds is the one-pass frame of
//! `voxtrace::Rounds::options_after(n)` (at most `n` rounds' samples a
//! pixel), on any thread count. So two runs of one flag set may differ
//! (in the rounds a busier machine finished), but every frame written is
//! the frame of `--spp N` (fixed samples) or `--max-spp N` (adaptive)
//! with the N that `--stats` prints, which gives its bytes again.

use std::time::{Duration, Instant};

use voxtrace::{EffectPlan, Look, Rounds, RoundsDone};

/// A frame's time budget and how its samples divide into rounds.
#[derive(Clone, Copy, Debug)]
pub struct Budget {
    /// `--time-limit`.
    pub limit: Duration,
    /// The rounds of the frame's plan.
    pub rounds: Rounds,
    /// The frame's plan, for the samples after each round.
    pub plan: EffectPlan,
}

impl Budget {
    /// The budget of `--time-limit` `limit` for frames of `plan`, when it
    /// can change anything: a path-traced frame of more than one round.
    pub fn of(limit: Option<Duration>, plan: &EffectPlan) -> Option<Budget> {
        let rounds = Rounds::of(plan);
        let limit = limit?;
        (plan.look == Look::Path && rounds.most > 1).then_some(Budget {
            limit,
            rounds,
            plan: *plan,
        })
    }

    /// The predicate asked between rounds, the clock started now: another
    /// round begins while the time spent plus the last round's time is
    /// within the limit (later rounds take no more samples than earlier
    /// ones: fewer pixels are left).
    pub fn keep_going(&self) -> impl FnMut(u32) -> bool {
        let (limit, started) = (self.limit, Instant::now());
        let mut round_began = started;
        move |_| {
            let now = Instant::now();
            let last = now - round_began;
            round_began = now;
            now - started + last <= limit
        }
    }

    /// The samples a pixel took at most in a frame of `done` rounds.
    pub fn samples_cap(&self, done: &RoundsDone) -> u16 {
        self.rounds.samples_after(done.rounds)
    }

    /// The flag that makes the frame of `done` again without the limit:
    /// `--max-spp N` for an adaptive frame, `--spp N` for fixed samples.
    pub fn reproduce(&self, done: &RoundsDone) -> String {
        let flag = if self.plan.options.adaptive.is_some() {
            "--max-spp"
        } else {
            "--spp"
        };
        format!("{flag} {}", self.samples_cap(done))
    }

    /// The `--stats` lines of frames that took `done` (one per frame):
    /// rounds taken and the most there are, whether each frame finished
    /// every pixel (then it is also the frame without the limit), the
    /// samples cap of each frame,
    /// and, when every frame agrees, the flag to use instead of
    /// `--time-limit` for the same bytes.
    pub fn stats(&self, done: &[RoundsDone]) -> Vec<String> {
        let list =
            |f: &dyn Fn(&RoundsDone) -> String| done.iter().map(f).collect::<Vec<_>>().join(",");
        let mut lines = vec![
            format!("rounds: {}", list(&|d| d.rounds.to_string())),
            format!("rounds_most: {}", self.rounds.most),
            format!("rounds_complete: {}", list(&|d| d.complete.to_string())),
            format!(
                "samples_cap: {}",
                list(&|d| self.samples_cap(d).to_string())
            ),
        ];
        if let Some(first) = done.first() {
            if done.iter().all(|d| d.rounds == first.rounds) {
                lines.push(format!("reproduce: {}", self.reproduce(first)));
            }
        }
        lines
    }
}

/// A note when `--time-limit` changes nothing for frames of `plan`: not
/// path-traced (one pass), or path-traced in one round (few fixed
/// samples).
pub fn unused_note(plan: &EffectPlan) -> Option<String> {
    if plan.look != Look::Path {
        return Some(
            "the scene is not path-traced: --time-limit changes nothing (its frame is one pass)"
                .to_string(),
        );
    }
    let rounds = Rounds::of(plan);
    (rounds.most == 1).then(|| {
        format!(
            "a pixel's {} samples are one round: --time-limit changes nothing (it stops only between rounds)",
            rounds.samples_per_round
        )
    })
}
