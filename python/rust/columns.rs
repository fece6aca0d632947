//! Columns for Python: numbers as float64 numpy arrays (NaN for an empty cell), text as numpy arrays of `str`
//! objects (one Python string per distinct text, shared by the rows that hold it).

use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyString;

/// A column read from CSV text.
pub enum Cells {
    Numbers(Vec<f64>),
    /// Codes into the distinct strings.
    Texts {
        codes: Vec<u32>,
        strings: Vec<String>,
    },
}

pub type TextColumns = Vec<(String, Cells)>;

/// Columns as Python sees them: each name with its numpy array.
pub type PyColumns<'py> = Vec<(String, Bound<'py, PyAny>)>;

/// The columns of CSV text written by the core (a history, a world's series): a column whose every non-empty cell is
/// a number is numbers (an empty cell NaN), any other is text. Cells hold no quotes or commas (the history's and the
/// series' cells are numbers and names).
pub fn parse_csv(text: &str) -> TextColumns {
    let mut lines = text.lines();
    let names: Vec<String> = lines.next().unwrap_or_default().split(',').map(str::to_string).collect();
    let rows: Vec<Vec<&str>> = lines.map(|line| line.split(',').collect()).collect();
    names
        .into_iter()
        .enumerate()
        .map(|(k, name)| {
            fn cell<'a>(row: &[&'a str], k: usize) -> &'a str {
                row.get(k).copied().unwrap_or("")
            }
            let numbers: Option<Vec<f64>> = rows
                .iter()
                .map(|row| match cell(row, k) {
                    "" => Some(f64::NAN),
                    text => text.parse::<f64>().ok(),
                })
                .collect();
            let cells = match numbers {
                Some(values) => Cells::Numbers(values),
                None => {
                    let mut strings: Vec<String> = Vec::new();
                    let codes = rows
                        .iter()
                        .map(|row| {
                            let text = cell(row, k);
                            match strings.iter().position(|s| s == text) {
                                Some(code) => code as u32,
                                None => {
                                    strings.push(text.to_string());
                                    (strings.len() - 1) as u32
                                }
                            }
                        })
                        .collect();
                    Cells::Texts { codes, strings }
                }
            };
            (name, cells)
        })
        .collect()
}

/// A numpy array of `str` objects from codes into `strings`.
pub fn text_array<'py>(py: Python<'py>, codes: &[u32], strings: &[String]) -> Bound<'py, PyAny> {
    let objects: Vec<Py<PyAny>> = strings.iter().map(|s| PyString::new(py, s).into_any().unbind()).collect();
    let items: Vec<Py<PyAny>> = codes.iter().map(|&code| objects[code as usize].clone_ref(py)).collect();
    PyArray1::from_vec(py, items).into_any()
}

/// The columns as (name, numpy array) pairs, moved into numpy.
pub fn to_python(py: Python<'_>, columns: TextColumns) -> PyResult<PyColumns<'_>> {
    Ok(columns
        .into_iter()
        .map(|(name, cells)| {
            let array = match cells {
                Cells::Numbers(values) => PyArray1::from_vec(py, values).into_any(),
                Cells::Texts { codes, strings } => text_array(py, &codes, &strings),
            };
            (name, array)
        })
        .collect())
}
