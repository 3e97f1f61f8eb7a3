//! Options every report takes: threads, where to write, the plot's font.

use std::io::Write;
use std::path::PathBuf;

/// Where a report runs and writes.
#[derive(Debug, clap::Args)]
pub struct Output {
    /// Worker threads, as the CLI's --threads [default: all cores].
    #[arg(long, value_parser = clap::value_parser!(u16).range(1..))]
    pub threads: Option<u16>,
    /// Folder for the report's markdown table and PNG plot (the README's
    /// figures are updated only when asked: `--out-dir docs/report`).
    #[arg(long, default_value = "target/report")]
    pub out_dir: PathBuf,
    /// TrueType font for the plot's text [default: a system sans-serif].
    #[arg(long)]
    pub font: Option<PathBuf>,
}

impl Output {
    /// Creates the output folder and loads the plot's font: both checked
    /// before minutes of measuring, not after.
    pub fn prepare(&self) -> Result<(), String> {
        // Ctrl-C while a file is being written removes its temporary file.
        voxtrace_cli::atomic::remove_on_signal()?;
        std::fs::create_dir_all(&self.out_dir)
            .map_err(|e| format!("cannot create {}: {e}", self.out_dir.display()))?;
        crate::plot::load_font(self.font.as_deref())
    }

    /// Writes `markdown` as `<name>.md` and draws `charts` as `<name>.png`,
    /// each through an atomic write.
    pub fn write(
        &self,
        name: &str,
        markdown: &str,
        charts: &[crate::plot::Chart],
    ) -> Result<(), String> {
        self.write_markdown(name, markdown)?;
        let plot = self.out_dir.join(format!("{name}.png"));
        crate::plot::draw(&plot, charts)?;
        eprintln!("wrote {}", plot.display());
        Ok(())
    }

    /// Writes `markdown` as `<name>.md` through an atomic write.
    pub fn write_markdown(&self, name: &str, markdown: &str) -> Result<(), String> {
        let table = self.out_dir.join(format!("{name}.md"));
        // Each file whole or not at all (temporary file, then rename), so a
        // failed or interrupted report keeps the previous tables and plots.
        voxtrace_cli::atomic::write_atomic(&table, |out| {
            out.write_all(markdown.as_bytes())
                .map_err(|e| e.to_string())
        })
        .map_err(|e| format!("cannot write {}: {e}", table.display()))?;
        eprintln!("wrote {}", table.display());
        Ok(())
    }
}
