//! `impact models`: the law table.

use crate::law::catalogue::LAWS;
use clap::Args;

#[derive(Debug, Args)]
pub struct ModelsArgs {}

pub fn run(_args: &ModelsArgs) -> anyhow::Result<()> {
    print!("{}", render());
    Ok(())
}

/// The table of laws, as printed.
pub fn render() -> String {
    let mut text =
        String::from("Contact laws (`law = \"...\"` in [contact]); d penetration, d' its rate, v0 approach speed\n\n");
    for law in &LAWS {
        text += &format!("{}\n", law.name);
        text += &format!("    force     F = {}\n", law.formula);
        text += &format!("    e -> damping  {}\n", law.map);
        text += &format!("    damping   {}\n", law.damping_units);
        text += &format!("    source    {}\n\n", law.source);
    }
    text
}
