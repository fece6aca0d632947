//! `impact validate [--json] [--case NAME]`: the built-in validation suite ([`crate::validate`]): a table of case,
//! quantity, simulated value, reference value, source, relative error, tolerance and pass. Exit 0 when every row
//! passes, 1 otherwise; 2 for a case name that does not exist.

use super::BadInput;
use clap::Args;
use std::fmt::Write as _;

#[derive(Debug, Args)]
pub struct ValidateArgs {
    /// Print the rows as a JSON list instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Run only this case (the table's first column).
    #[arg(long, value_name = "NAME")]
    pub case: Option<String>,
}

pub fn run(args: &ValidateArgs) -> anyhow::Result<()> {
    let rows = match crate::validate::run(args.case.as_deref()) {
        Ok(rows) => rows,
        Err(why) if why.starts_with("no validation case") => return Err(BadInput(why).into()),
        Err(why) => anyhow::bail!(why),
    };
    if args.json {
        println!("{}", serde_json::to_string_pretty(&rows)?);
    } else {
        print!("{}", table(&rows));
    }
    let failed = rows.iter().filter(|r| !r.pass).count();
    if failed > 0 {
        anyhow::bail!("{failed} of {} checks failed", rows.len());
    }
    Ok(())
}

/// The rows as an aligned table, the sources listed once below it.
fn table(rows: &[crate::validate::Row]) -> String {
    let mut sources: Vec<&str> = Vec::new();
    for row in rows {
        if !sources.contains(&row.source.as_str()) {
            sources.push(&row.source);
        }
    }
    let width = rows.iter().map(|r| r.case.len()).max().unwrap_or(4).max(4);
    let quantity = rows.iter().map(|r| r.quantity.len()).max().unwrap_or(8).max(8);
    let mut text = String::new();
    let _ = writeln!(
        text,
        "{:<width$}  {:<quantity$}  {:>17}  {:>17}  {:>6}  {:>9}  {:>9}  pass",
        "case", "quantity", "simulated", "reference", "source", "rel. err", "tolerance"
    );
    for row in rows {
        let source = sources.iter().position(|s| *s == row.source).unwrap_or(0) + 1;
        let _ = writeln!(
            text,
            "{:<width$}  {:<quantity$}  {:>17.10e}  {:>17.10e}  {:>6}  {:>9.1e}  {:>9.1e}  {}",
            row.case,
            row.quantity,
            row.simulated,
            row.reference,
            format!("[{source}]"),
            row.relative_error,
            row.tolerance,
            if row.pass { "yes" } else { "NO" }
        );
    }
    let _ = writeln!(text, "\nsources:");
    for (k, source) in sources.iter().enumerate() {
        let _ = writeln!(text, "  [{}] {source}", k + 1);
    }
    let failed = rows.iter().filter(|r| !r.pass).count();
    let _ = writeln!(text, "\n{} checks, {} passed, {failed} failed", rows.len(), rows.len() - failed);
    text
}
