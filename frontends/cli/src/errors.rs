//! clap's errors as the CLI's one line: the message and its hints (the
//! valid values, the closest flag, how to pass a value that starts with
//! `-`), without the usage block.

use clap::error::{ContextKind, ContextValue, ErrorKind};

/// `error` rendered on one line starting with `error:`; `argv` is the
/// command line (for the tip about negative values).
pub fn one_line(error: &clap::Error, argv: &[String]) -> String {
    let text = error.render().to_string();
    let mut line = String::new();
    for part in text.lines().map(str::trim) {
        if part.is_empty() || part.starts_with("Usage:") || part.starts_with("For more information")
        {
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
    if let Some(tip) = negative_value_tip(error, argv) {
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

fn text_has_tip(error: &clap::Error) -> bool {
    error.render().to_string().contains("tip:")
}
