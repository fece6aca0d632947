//! Exact references (closed forms and quadratures) — being written.
