//! Joining the shards of a sweep (`impact merge`): every shard of one sweep, each row exactly once, rows back in
//! global order — byte for byte the file the unsharded sweep writes.

use super::table::{ShardInfo, parse_shard_comment};
use super::{MAX_ROWS, SweepError};

/// A shard file's name (for messages) and text.
pub struct ShardFile {
    pub name: String,
    pub text: String,
}

fn usage(message: String) -> SweepError {
    SweepError::Usage(message)
}

/// The merged CSV text of `shards` (any order), or why they do not make up one whole sweep: a file that is not a
/// shard, shards of different sweeps or with different headers, a shard given twice, a row in the wrong shard,
/// a row index given twice, missing rows.
pub fn merge(shards: &[ShardFile]) -> Result<String, SweepError> {
    let Some(first) = shards.first() else { return Err(usage("give the shard files to merge".into())) };
    let (reference, header) = read_head(first)?;
    let mut rows: Vec<Option<&str>> = vec![None; reference.rows];
    let mut seen: Vec<Option<&str>> = vec![None; reference.shard.count];
    for file in shards {
        let (info, file_header) = read_head(file)?;
        if (info.rows, info.shard.count, info.fingerprint)
            != (reference.rows, reference.shard.count, reference.fingerprint)
        {
            return Err(usage(format!(
                "{} and {} are not shards of the same sweep ({} of {} rows, sweep {:016x}; {} of {} rows, sweep \
                 {:016x})",
                first.name,
                file.name,
                reference.shard,
                reference.rows,
                reference.fingerprint,
                info.shard,
                info.rows,
                info.fingerprint
            )));
        }
        if file_header != header {
            return Err(usage(format!("{} and {} have different headers", first.name, file.name)));
        }
        let slot = &mut seen[info.shard.number - 1];
        if let Some(other) = slot {
            return Err(usage(format!("shard {} is given twice: {other} and {}", info.shard, file.name)));
        }
        *slot = Some(&file.name);
        for (number, line) in file.text.split_terminator('\n').enumerate().skip(2) {
            let index = line.split(',').next().and_then(|cell| cell.parse::<usize>().ok());
            let place = |why: &str| usage(format!("{}, line {}: {why}", file.name, number + 1));
            let Some(index) = index else { return Err(place("the row does not start with its index")) };
            if index >= reference.rows {
                return Err(place(&format!("row index {index} is outside the sweep's {} rows", reference.rows)));
            }
            if !info.shard.takes(index) {
                return Err(place(&format!("row {index} does not belong to shard {}", info.shard)));
            }
            if rows[index].replace(line).is_some() {
                return Err(place(&format!("row {index} appears twice")));
            }
        }
    }
    let missing_shards: Vec<String> = (0..reference.shard.count)
        .filter(|&i| seen[i].is_none())
        .map(|i| format!("{}/{}", i + 1, reference.shard.count))
        .collect();
    if !missing_shards.is_empty() {
        return Err(usage(format!("incomplete sweep: shard(s) {} missing", missing_shards.join(", "))));
    }
    let missing: Vec<String> = (0..reference.rows).filter(|&i| rows[i].is_none()).map(|i| i.to_string()).collect();
    if !missing.is_empty() {
        let shown = missing.iter().take(10).cloned().collect::<Vec<_>>().join(", ");
        let more = if missing.len() > 10 { format!(" and {} more", missing.len() - 10) } else { String::new() };
        return Err(usage(format!("incomplete sweep: row(s) {shown}{more} missing (a shard file was cut short?)")));
    }
    let mut text = format!("{header}\n");
    for line in rows.into_iter().flatten() {
        text += line;
        text.push('\n');
    }
    Ok(text)
}

/// The shard comment and the header line of a shard file.
fn read_head(file: &ShardFile) -> Result<(ShardInfo, &str), SweepError> {
    let mut lines = file.text.split_terminator('\n');
    let sane = |info: &ShardInfo| info.rows <= MAX_ROWS && info.shard.count <= MAX_ROWS;
    let info = lines.next().and_then(parse_shard_comment).filter(sane).ok_or_else(|| {
        usage(format!(
            "{} is not a shard of `impact sweep --shard I/N` (its first line should read `# impact sweep: shard I/N \
             of R rows, sweep ID`)",
            file.name
        ))
    })?;
    let header = lines.next().filter(|h| h.starts_with("index,")).ok_or_else(|| {
        usage(format!("{}: the second line should be the CSV header, starting with `index,`", file.name))
    })?;
    Ok((info, header))
}
