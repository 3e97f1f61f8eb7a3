//! Timing helpers: medians of repeated runs, and the machine's name.

use std::time::Duration;

/// The median of `samples` in milliseconds (the mean of the middle two for
/// an even count). `samples` must not be empty.
#[must_use]
pub fn median_ms(samples: &mut [Duration]) -> f64 {
    assert!(!samples.is_empty(), "a median needs samples");
    samples.sort_unstable();
    let mid = samples.len() / 2;
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    if samples.len() % 2 == 1 {
        ms(samples[mid])
    } else {
        (ms(samples[mid - 1]) + ms(samples[mid])) / 2.0
    }
}

/// Runs `once` `runs` times after one untimed warm-up run and returns the
/// median of the durations it reports.
pub fn median_of<F>(runs: usize, mut once: F) -> Result<f64, String>
where
    F: FnMut() -> Result<Duration, String>,
{
    once()?; // warm caches and page in memory; not counted
    let mut samples = (0..runs.max(1))
        .map(|_| once())
        .collect::<Result<Vec<_>, _>>()?;
    Ok(median_ms(&mut samples))
}

/// The CPU's model name as Linux reports it, or "unknown CPU".
#[must_use]
pub fn cpu_name() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|text| {
            text.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|name| name.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".to_string())
}

/// Milliseconds for a table: three significant figures, seconds from 10 s.
#[must_use]
pub fn format_ms(ms: f64) -> String {
    if ms >= 10_000.0 {
        format!("{:.2} s", ms / 1e3)
    } else if ms >= 100.0 {
        format!("{ms:.0} ms")
    } else if ms >= 10.0 {
        format!("{ms:.1} ms")
    } else {
        format!("{ms:.2} ms")
    }
}

/// Bytes with thousands separators: 3,194,100.
#[must_use]
pub fn format_bytes(bytes: u64) -> String {
    let digits = bytes.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// `count` followed by `word`, plural unless the count is 1: "1 run", "3 runs".
#[must_use]
pub fn count_of(count: usize, word: &str) -> String {
    if count == 1 {
        format!("{count} {word}")
    } else {
        format!("{count} {word}s")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_odd_and_even_counts() {
        let ms = Duration::from_millis;
        assert_eq!(median_ms(&mut [ms(5), ms(1), ms(3)]), 3.0);
        assert_eq!(median_ms(&mut [ms(4), ms(1), ms(3), ms(100)]), 3.5);
    }

    #[test]
    fn bytes_get_separators() {
        assert_eq!(format_bytes(0), "0");
        assert_eq!(format_bytes(999), "999");
        assert_eq!(format_bytes(1000), "1,000");
        assert_eq!(format_bytes(125_000_768), "125,000,768");
    }

    #[test]
    fn counts_take_their_plural() {
        assert_eq!(super::count_of(1, "run"), "1 run");
        assert_eq!(super::count_of(3, "run"), "3 runs");
        assert_eq!(super::count_of(0, "run"), "0 runs");
    }
}
