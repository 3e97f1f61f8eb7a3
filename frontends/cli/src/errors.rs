//! Errors as the CLI's one line: clap's message and its hints (the valid
//! values, the closest flag, how to pass a value that starts with `-`),
//! without the usage block; and control characters (a newline in a file
//! name) escaped, so that a message stays one line.

use std::io::Write;

use clap::error::{ContextKind, ContextValue, ErrorKind};

/// Writes one formatted line to standard error, as `eprintln!` does, but
/// never panics: with standard error closed or a broken pipe the line is
/// lost and the exit code still tells (`eprintln!` would panic, turning an
/// exit 2 into 101, or a signal's exit into a run that goes on).
#[macro_export]
macro_rules! say {
    ($($arg:tt)*) => {
        $crate::errors::write_line(::std::format_args!($($arg)*))
    };
}

/// The line [`say!`] writes, ignoring a failure to write it.
pub fn write_line(line: std::fmt::Arguments<'_>) {
    let _ = writeln!(std::io::stderr().lock(), "{line}");
}

/// What a failed parse ends with: help and version go to stdout with exit
/// 0; a parse error is [`one_line`] on stderr, and exit 2.
pub fn clap_failure(error: &clap::Error, argv: &[String]) -> std::process::ExitCode {
    if matches!(
        error.kind(),
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion
    ) {
        let _ = error.print();
        return std::process::ExitCode::SUCCESS;
    }
    write_line(format_args!("{}", one_line(error, argv)));
    std::process::ExitCode::from(2)
}

/// `error` rendered on one line starting with `error:`; `argv` is the
/// command line (for the tip about negative values).
pub fn one_line(error: &clap::Error, argv: &[String]) -> String {
    let mut text = error.render().to_string();
    // A value clap quotes is written as given: escape the control
    // characters of those that have them before the lines are joined.
    for arg in argv.iter().filter(|a| a.chars().any(char::is_control)) {
        text = text.replace(arg.as_str(), &escape_controls(arg));
    }
    let mut line = String::new();
    // The usage block runs from "Usage:" to the next blank line (one line
    // per form: `voxtrace [OPTIONS]`, then `voxtrace <COMMAND>`).
    let mut in_usage = false;
    for part in text.lines().map(str::trim) {
        in_usage = part.starts_with("Usage:") || (in_usage && !part.is_empty());
        if in_usage || part.is_empty() || part.starts_with("For more information") {
            continue;
        }
        if !line.is_empty() {
            // "...: <list>" and "[possible values: ...]" read on; other
            // parts are separate sentences.
            let sep = if line.ends_with(':') || part.starts_with('[') {
                " "
            } else {
                "; "
            };
            line.push_str(sep);
        }
        line.push_str(part);
    }
    if let Some(tip) = negative_value_tip(error, argv).or_else(|| vox_file_tip(error)) {
        line.push_str("; ");
        line.push_str(&tip);
    }
    if line.starts_with("error:") {
        line
    } else {
        format!("error: {line}")
    }
}

/// For `--size -5`: clap takes `-5` for a flag; say how to pass it.
fn negative_value_tip(error: &clap::Error, argv: &[String]) -> Option<String> {
    if error.kind() != ErrorKind::UnknownArgument {
        return None;
    }
    let Some(ContextValue::String(arg)) = error.get(ContextKind::InvalidArg) else {
        return None;
    };
    if text_has_tip(error) || arg.parse::<f64>().is_err() {
        return None;
    }
    let at = argv.iter().position(|a| a == arg)?;
    let flag = argv.get(at.checked_sub(1)?)?;
    flag.starts_with("--")
        .then(|| format!("tip: to pass '{arg}' as the value of {flag}, write {flag}={arg}"))
}

/// For `voxtrace study.vox`: a .vox file where a subcommand would be (the
/// first word that is no flag); say that `--vox` renders it.
fn vox_file_tip(error: &clap::Error) -> Option<String> {
    if error.kind() != ErrorKind::InvalidSubcommand {
        return None;
    }
    let Some(ContextValue::String(arg)) = error.get(ContextKind::InvalidSubcommand) else {
        return None;
    };
    let is_vox = std::path::Path::new(arg)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("vox"));
    // Quoted as a shell would need it when it has spaces.
    let shown = if arg.contains(char::is_whitespace) {
        format!("'{arg}'")
    } else {
        arg.clone()
    };
    is_vox.then(|| format!("tip: to render a .vox file, write --vox {shown}"))
}

fn text_has_tip(error: &clap::Error) -> bool {
    error.render().to_string().contains("tip:")
}

/// `text` with every control character written as Rust writes it in a
/// string literal (`\n`, `\t`, `\r`, else `\u{1b}`), so that a file name or
/// a file's text cannot end an `error:` line or start another.
pub fn escape_controls(text: &str) -> String {
    let mut escaped = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_control() {
            escaped.extend(c.escape_debug());
        } else {
            escaped.push(c);
        }
    }
    escaped
}

#[cfg(test)]
mod tests {
    use super::escape_controls;

    #[test]
    fn control_characters_are_escaped_and_the_rest_kept() {
        assert_eq!(
            escape_controls("a\nb\tc\r\u{1b}[31m\u{7f}\u{85}é ü/x.png"),
            "a\\nb\\tc\\r\\u{1b}[31m\\u{7f}\\u{85}é ü/x.png"
        );
        assert_eq!(escape_controls("plain"), "plain");
    }
}
