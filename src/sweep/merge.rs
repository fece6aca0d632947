//! Joining the shards of a sweep (`impact merge`): every shard of one sweep, each row exactly once, rows back in
//! global order — byte for byte the file the unsharded sweep writes.

use super::table::{ShardInfo, cell_count, parse_shard_comment};
use super::{MAX_ROWS, SweepError};

/// A shard file's name (for messages) and text.
pub struct ShardFile {
    pub name: String,
    pub text: String,
}

fn usage(message: String) -> SweepError {
    SweepError::Usage(message)
}

/// The whole sweep joined from its shards: the header line and the rows in index order (each without its line
/// end), borrowed from the shard texts.
#[derive(Debug)]
pub struct Merged<'a> {
    pub header: &'a str,
    pub rows: Vec<&'a str>,
}

impl Merged<'_> {
    /// The merged CSV text.
    pub fn text(&self) -> String {
        let mut text = format!("{}\n", self.header);
        for row in &self.rows {
            text += row;
            text.push('\n');
        }
        text
    }
}

/// One row as found: its index, its text, and where it is (file, 1-based line) for messages.
struct Found<'a> {
    index: usize,
    text: &'a str,
    file: &'a str,
    line: usize,
}

/// Joins `shards` (any order) into the whole sweep, or says why they do not make up one: a file that is not a shard
/// or is cut off (no final line end, a row with fewer cells than the header), shards of different sweeps or with
/// different headers, a shard given twice, a row in the wrong shard, a row index given twice, missing shards or rows.
///
/// Nothing is sized by what a shard's first line claims (it may be forged, or corrupt): the rows found are
/// gathered, sorted by index and checked to be exactly 0, 1, ..., rows - 1.
pub fn merge(shards: &[ShardFile]) -> Result<Merged<'_>, SweepError> {
    let Some(first) = shards.first() else { return Err(usage("give the shard files to merge".into())) };
    let (reference, header) = read_head(first)?;
    let cells = cell_count(header);
    let mut seen: Vec<(usize, &str)> = Vec::new();
    let mut rows: Vec<Found> = Vec::new();
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
        seen.push((info.shard.number, &file.name));
        let lines = file.text.split_terminator('\n').count();
        if !file.text.ends_with('\n') {
            return Err(usage(format!(
                "{}, line {lines}: the last line has no line end: the file was cut off (a shard still being \
                 written?)",
                file.name
            )));
        }
        for (number, line) in file.text.split_terminator('\n').enumerate().skip(2) {
            let place = |why: &str| usage(format!("{}, line {}: {why}", file.name, number + 1));
            let index = line.split(',').next().and_then(|cell| cell.parse::<usize>().ok());
            let Some(index) = index else { return Err(place("the row does not start with its index")) };
            if index >= reference.rows {
                return Err(place(&format!("row index {index} is outside the sweep's {} rows", reference.rows)));
            }
            if !info.shard.takes(index) {
                return Err(place(&format!("row {index} does not belong to shard {}", info.shard)));
            }
            let found = cell_count(line);
            if found != cells {
                return Err(place(&format!("the row has {found} cells, the header {cells}: a row cut off?")));
            }
            rows.push(Found { index, text: line, file: &file.name, line: number + 1 });
        }
    }

    seen.sort_unstable();
    if let Some(pair) = seen.windows(2).find(|pair| pair[0].0 == pair[1].0) {
        let shard = format!("{}/{}", pair[0].0, reference.shard.count);
        return Err(usage(format!("shard {shard} is given twice: {} and {}", pair[0].1, pair[1].1)));
    }
    let count = reference.shard.count;
    if seen.len() < count {
        let missing = first_missing(seen.iter().map(|(number, _)| number - 1), count);
        let names: Vec<String> = missing.iter().map(|i| format!("{}/{count}", i + 1)).collect();
        let more = more(count - seen.len(), names.len());
        return Err(usage(format!("incomplete sweep: shard(s) {}{more} missing", names.join(", "))));
    }

    // Stable: of two copies of a row, the second found is the one named.
    rows.sort_by_key(|row| row.index);
    if let Some(pair) = rows.windows(2).find(|pair| pair[0].index == pair[1].index) {
        let row = &pair[1];
        return Err(usage(format!("{}, line {}: row {} appears twice", row.file, row.line, row.index)));
    }
    if rows.len() < reference.rows {
        let missing = first_missing(rows.iter().map(|row| row.index), reference.rows);
        let shown: Vec<String> = missing.iter().map(usize::to_string).collect();
        let more = more(reference.rows - rows.len(), shown.len());
        return Err(usage(format!(
            "incomplete sweep: row(s) {}{more} missing (a shard file was cut short?)",
            shown.join(", ")
        )));
    }
    Ok(Merged { header, rows: rows.into_iter().map(|row| row.text).collect() })
}

/// How many a message lists of what is missing.
const SHOWN: usize = 10;

/// The first [`SHOWN`] numbers of 0..end absent from `present` (increasing, distinct, below `end`): found by
/// walking the gaps, so that a count claimed in a header is never allocated.
fn first_missing(present: impl Iterator<Item = usize>, end: usize) -> Vec<usize> {
    let mut missing = Vec::new();
    let mut next = 0;
    for found in present.chain([end]) {
        while next < found && missing.len() < SHOWN {
            missing.push(next);
            next += 1;
        }
        if missing.len() == SHOWN {
            break;
        }
        next = found + 1;
    }
    missing
}

/// " and N more" when `total` exceed the `shown`.
fn more(total: usize, shown: usize) -> String {
    if total > shown { format!(" and {} more", total - shown) } else { String::new() }
}

/// The shard comment and the header line of a shard file.
fn read_head(file: &ShardFile) -> Result<(ShardInfo, &str), SweepError> {
    let mut lines = file.text.split_terminator('\n');
    let sane = |info: &ShardInfo| info.rows <= MAX_ROWS && info.shard.count <= MAX_ROWS;
    let info = lines.next().and_then(parse_shard_comment).filter(sane).ok_or_else(|| {
        usage(format!(
            "{} is not a shard of `impact sweep --shard I/N` (its first line should read `# impact sweep: shard I/N \
             of R rows, sweep ID`, with R and N at most {MAX_ROWS})",
            file.name
        ))
    })?;
    let header = lines.next().filter(|h| h.starts_with("index,")).ok_or_else(|| {
        usage(format!("{}: the second line should be the CSV header, starting with `index,`", file.name))
    })?;
    Ok((info, header))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_missing_walks_the_gaps() {
        assert_eq!(first_missing([1, 2, 5].into_iter(), 7), vec![0, 3, 4, 6]);
        assert_eq!(first_missing([0, 1, 2].into_iter(), 3), Vec::<usize>::new());
        // A claimed count of a hundred million costs ten numbers.
        assert_eq!(first_missing(std::iter::empty(), 100_000_000), (0..10).collect::<Vec<_>>());
    }
}
