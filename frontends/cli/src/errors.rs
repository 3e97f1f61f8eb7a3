//! Errors as the CLI's one line: clap's message and its hints (the valid
//! values, the closest flag, how to pass a value that starts with `-`),
//! without the usage block; and control characters (a newline in a file
//! name) escaped, so that a message stays one line.

use std::ffi::{OsStr, OsString};
use std::io::Write;

use clap::builder::{StyledStr, Styles};
use clap::error::{ContextKind, ContextValue, ErrorKind};
use clap::{ArgMatches, Command, FromArgMatches};

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

/// `command`'s parse of `argv` (the program's arguments as given, its
/// name first; bytes that are not UTF-8 kept, for the paths) into a `T`
/// and the matches it came from.
///
/// # Errors
/// What [`clap_failure`] reports. Help and version come as clap renders
/// them; any other error comes from a second parse without styles, so that
/// a hint clap writes a value into holds no escape sequence of clap's own
/// beside the value's own (which [`one_line`] escapes). A value that is
/// not UTF-8 where a text is expected (`--fov`) is named, escaped, where
/// clap would say only that some argument was not UTF-8.
pub fn parse<T: FromArgMatches>(
    command: &Command,
    argv: &[OsString],
) -> Result<(T, ArgMatches), clap::Error> {
    let run = |command: Command| {
        command
            .try_get_matches_from(argv)
            .and_then(|matches| T::from_arg_matches(&matches).map(|t| (t, matches)))
    };
    match run(command.clone()) {
        Err(error) if !is_help(&error) => {}
        done => return done,
    }
    let plain = command.clone().styles(Styles::plain());
    match run(plain.clone()) {
        Err(error) if error.kind() == ErrorKind::InvalidUtf8 => {
            Err(not_utf8(&plain, argv).unwrap_or(error))
        }
        done => done,
    }
}

/// Help and version: printed as clap renders them, on standard output.
fn is_help(error: &clap::Error) -> bool {
    matches!(
        error.kind(),
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion
    )
}

/// For clap's "invalid UTF-8 was detected in one or more arguments": the
/// error naming the argument. Clap checks the values as it meets them,
/// left to right, so the culprit is the first argument whose command line
/// up to it fails that way (one that is not UTF-8 in a path passes).
fn not_utf8(command: &Command, argv: &[OsString]) -> Option<clap::Error> {
    let at = (1..argv.len())
        .filter(|&i| argv[i].to_str().is_none())
        .find(|&i| {
            command
                .clone()
                .try_get_matches_from(&argv[..=i])
                .is_err_and(|e| e.kind() == ErrorKind::InvalidUtf8)
        })?;
    let arg = argv[at].as_encoded_bytes();
    let takes_value = |flag: &[u8]| {
        let long = flag
            .strip_prefix(b"--")
            .and_then(|f| std::str::from_utf8(f).ok());
        let mut commands = std::iter::once(command).chain(command.get_subcommands());
        long.is_some_and(|long| {
            commands.any(|c| {
                c.get_arguments()
                    .any(|a| a.get_long() == Some(long) && a.get_action().takes_values())
            })
        })
    };
    let equals = arg.iter().position(|&b| b == b'=');
    let (flag, value) = match equals {
        Some(i) if takes_value(&arg[..i]) => (Some(&arg[..i]), &arg[i + 1..]),
        _ => match argv[at - 1].as_encoded_bytes() {
            flag if at > 1 && takes_value(flag) => (Some(flag), arg),
            _ => (None, arg),
        },
    };
    let message = match flag {
        Some(flag) => format!(
            "invalid value '{}' for '{}': not UTF-8 (only a file name may hold other bytes)",
            show_bytes(value),
            show_bytes(flag)
        ),
        None => format!(
            "the argument '{}' is not UTF-8 (only a file name may hold other bytes)",
            show_bytes(value)
        ),
    };
    Some(clap::Error::raw(ErrorKind::InvalidUtf8, message))
}

/// What a failed parse ([`parse`]) ends with: help and version go to
/// stdout with exit 0; a parse error is [`one_line`] on stderr, and exit 2.
pub fn clap_failure(error: clap::Error, argv: &[OsString]) -> std::process::ExitCode {
    if is_help(&error) {
        let _ = error.print();
        return std::process::ExitCode::SUCCESS;
    }
    write_line(format_args!("{}", one_line(error, argv)));
    std::process::ExitCode::from(2)
}

/// `error` (one of [`parse`], made without styles) rendered on one line
/// starting with `error:`; `argv` is the command line (for the tip about
/// negative values). Every value it quotes is shown exactly, its control
/// characters escaped, whichever parser refused it: clap's context values
/// and hints, and a value parser's message.
pub fn one_line(mut error: clap::Error, argv: &[OsString]) -> String {
    // Of the values as given: the tips escape what they quote.
    let tip = negative_value_tip(&error, argv)
        .or_else(|| vox_file_tip(&error, argv))
        .or_else(|| first_words_tip(&error));
    escape_context(&mut error, argv);
    let mut text = error.render().ansi().to_string();
    // A value parser's message (after "invalid value '...' for '--flag': ")
    // quotes the value as it was given: a newline in it would end the line.
    if let Some(source) = std::error::Error::source(&error).map(ToString::to_string) {
        if source.contains(char::is_control) {
            text = text.replacen(&source, &escape_controls(&source), 1);
        }
    }
    // Any control character left but the line breaks between clap's parts.
    let text: String = text
        .split('\n')
        .map(escape_controls)
        .collect::<Vec<_>>()
        .join("\n");
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
    if let Some(tip) = tip {
        line.push_str("; ");
        line.push_str(&tip);
    }
    if line.starts_with("error:") {
        line
    } else {
        format!("error: {line}")
    }
}

/// Every value of `error`'s context with its control characters escaped
/// (clap's rendering would strip ESC, BEL, BS, DEL and VT and keep the
/// others raw), but the usage block, whose lines are clap's own; and a
/// value clap made UTF-8 (lossily) from an argument of `argv` shown as
/// that argument's bytes.
fn escape_context(error: &mut clap::Error, argv: &[OsString]) {
    let exact = |s: &String| shown_exactly(s, argv);
    let escaped: Vec<(ContextKind, ContextValue)> = error
        .context()
        .filter(|(kind, _)| *kind != ContextKind::Usage)
        .filter_map(|(kind, value)| {
            let styled = |s: &StyledStr| StyledStr::from(escape_controls(&s.ansi().to_string()));
            let value = match value {
                ContextValue::String(s) => ContextValue::String(exact(s)),
                ContextValue::Strings(all) => {
                    ContextValue::Strings(all.iter().map(exact).collect())
                }
                ContextValue::StyledStr(s) => ContextValue::StyledStr(styled(s)),
                ContextValue::StyledStrs(all) => {
                    ContextValue::StyledStrs(all.iter().map(styled).collect())
                }
                _ => return None,
            };
            Some((kind, value))
        })
        .collect();
    for (kind, value) in escaped {
        error.insert(kind, value);
    }
}

/// `value` as a message shows it: escaped, and when it holds U+FFFD and is
/// the lossy text of an argument of `argv` (or of either side of its
/// `=`), that argument's bytes as [`show_path`] shows them.
fn shown_exactly(value: &str, argv: &[OsString]) -> String {
    if value.contains(char::REPLACEMENT_CHARACTER) {
        let mut pieces = argv.iter().flat_map(|arg| {
            let bytes = arg.as_encoded_bytes();
            let sides = bytes
                .iter()
                .position(|&b| b == b'=')
                .map(|i| [&bytes[..i], &bytes[i + 1..]]);
            std::iter::once(bytes).chain(sides.into_iter().flatten())
        });
        if let Some(bytes) = pieces.find(|bytes| String::from_utf8_lossy(bytes) == value) {
            return show_bytes(bytes);
        }
    }
    escape_controls(value)
}

/// For `--size -5`: clap takes `-5` for a flag; say how to pass it.
fn negative_value_tip(error: &clap::Error, argv: &[OsString]) -> Option<String> {
    if error.kind() != ErrorKind::UnknownArgument {
        return None;
    }
    let Some(ContextValue::String(arg)) = error.get(ContextKind::InvalidArg) else {
        return None;
    };
    if text_has_tip(error) || arg.parse::<f64>().is_err() {
        return None;
    }
    let at = argv.iter().position(|a| a.as_os_str() == OsStr::new(arg))?;
    let flag = argv.get(at.checked_sub(1)?)?.to_str()?;
    flag.starts_with("--").then(|| {
        escape_controls(&format!(
            "tip: to pass '{arg}' as the value of {flag}, write {flag}={arg}"
        ))
    })
}

/// For `voxtrace study.vox`: a .vox file where a subcommand would be (the
/// first word that is no flag); say that `--vox` renders it.
fn vox_file_tip(error: &clap::Error, argv: &[OsString]) -> Option<String> {
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
    let shown = shown_exactly(arg, argv);
    let shown = if arg.contains(char::is_whitespace) {
        format!("'{shown}'")
    } else {
        shown
    };
    is_vox.then(|| format!("tip: to render a .vox file, write --vox {shown}"))
}

/// For what other renderers' users type first: `-o` (the image is
/// `--out`), `render` as a subcommand (a render needs none), and a size
/// in one flag (`--width 640x360`: it is two).
fn first_words_tip(error: &clap::Error) -> Option<String> {
    let context = |kind| match error.get(kind) {
        Some(ContextValue::String(value)) => Some(value.as_str()),
        _ => None,
    };
    match error.kind() {
        ErrorKind::UnknownArgument if context(ContextKind::InvalidArg)? == "-o" => {
            Some("tip: the image file is --out FILE".into())
        }
        ErrorKind::InvalidSubcommand if context(ContextKind::InvalidSubcommand)? == "render" => {
            Some("tip: voxtrace renders without a subcommand: drop 'render'".into())
        }
        ErrorKind::ValueValidation => {
            let flag = context(ContextKind::InvalidArg)?;
            let (w, h) = context(ContextKind::InvalidValue)?.split_once(['x', 'X'])?;
            let size = |n: &str| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit());
            let is_size_flag = flag.starts_with("--width") || flag.starts_with("--height");
            (is_size_flag && size(w) && size(h))
                .then(|| format!("tip: a size is two flags: --width {w} --height {h}"))
        }
        _ => None,
    }
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

/// `path` as a message shows it, on one line and exactly: control
/// characters escaped as [`escape_controls`] does, and bytes that are not
/// UTF-8 (a Unix file name may hold any byte but `/` and NUL) written as
/// `\xff`, where `Path::display` would print U+FFFD and name another file.
pub fn show_path(path: &std::path::Path) -> String {
    show_bytes(path.as_os_str().as_encoded_bytes())
}

/// `bytes` (an argument or a file name) as [`show_path`] shows them.
fn show_bytes(bytes: &[u8]) -> String {
    let mut shown = String::new();
    for chunk in bytes.utf8_chunks() {
        shown.push_str(&escape_controls(chunk.valid()));
        for byte in chunk.invalid() {
            shown.push_str(&format!("\\x{byte:02x}"));
        }
    }
    shown
}
