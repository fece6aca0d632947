//! `impact validate` (issue 24; docs/validation.md): the suite runs every case, every row meets its tolerance, the
//! JSON rows carry the contract's keys, `--case` runs one case, and an unknown case is bad input naming the cases.

mod common;

use common::binary::{Scratch, assert_success, impact, stderr, stdout};

#[test]
fn every_validation_case_passes_and_its_rows_carry_the_contract() {
    let scratch = Scratch::new("every_validation_case_passes");
    let output = impact(scratch.path(), &["validate", "--json"]);
    assert_success(&output);
    let rows: serde_json::Value = serde_json::from_str(&stdout(&output)).expect("a JSON list");
    let rows = rows.as_array().expect("a list");
    let cases: std::collections::BTreeSet<&str> = rows.iter().map(|r| r["case"].as_str().unwrap()).collect();
    for case in impact::validate::cases() {
        assert!(cases.contains(case.name), "no row of case {}", case.name);
    }
    for row in rows {
        for key in ["case", "quantity", "simulated", "reference", "source", "relative_error", "tolerance", "pass"] {
            assert!(row.get(key).is_some(), "a row without `{key}`: {row}");
        }
        let (simulated, reference) = (row["simulated"].as_f64().unwrap(), row["reference"].as_f64().unwrap());
        let error = ((simulated - reference) / reference).abs();
        assert!((row["relative_error"].as_f64().unwrap() - error).abs() <= 1e-15 + 1e-12 * error, "{row}");
        assert_eq!(row["pass"].as_bool(), Some(error <= row["tolerance"].as_f64().unwrap()), "{row}");
        assert_eq!(row["pass"].as_bool(), Some(true), "{row}");
    }
}

#[test]
fn one_case_runs_alone_and_an_unknown_one_is_refused_with_the_list() {
    let scratch = Scratch::new("one_validation_case");
    let output = impact(scratch.path(), &["validate", "--case", "cradle-3"]);
    assert_success(&output);
    let text = stdout(&output);
    assert!(text.contains("Herrmann & Schmälzle") && !text.contains("lecture-direct"), "{text}");
    assert!(text.contains("3 checks, 3 passed, 0 failed"), "{text}");
    let refused = impact(scratch.path(), &["validate", "--case", "no-such-case"]);
    assert_eq!(refused.status.code(), Some(2), "{}", stderr(&refused));
    let message = stderr(&refused);
    assert!(message.contains("no-such-case") && message.contains("lecture-direct: "), "{message}");
}
