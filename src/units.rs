//! Numbers for people: SI prefixes chosen for the quantity, six significant digits in the readable report, three in
//! messages ([`brief`]).
//!
//! The terminal report and the messages (errors, notes) use these; JSON and CSV keep full precision. It needs nothing
//! of the crate, so that every layer that composes a message can use it. Every function rounds once, by the
//! standard library's correctly rounded `{:e}` formatting, and builds the text from its digits, so a value that
//! rounds up to the next power of a thousand takes the next prefix ("1.00000 kN", never "1000.00 N").

/// Significant digits of the readable report.
pub const DIGITS: usize = 6;

/// SI prefixes by power of ten, from atto to exa. The micro sign is U+00B5, as in the README.
const PREFIXES: [(i32, &str); 13] = [
    (-18, "a"),
    (-15, "f"),
    (-12, "p"),
    (-9, "n"),
    (-6, "µ"),
    (-3, "m"),
    (0, ""),
    (3, "k"),
    (6, "M"),
    (9, "G"),
    (12, "T"),
    (15, "P"),
    (18, "E"),
];

/// Units that take an SI prefix in front of their first symbol ("N s" -> "mN s", "m/s" -> "mm/s").
const PREFIXABLE: [&str; 10] = ["m", "s", "N", "J", "Pa", "W", "m/s", "N s", "N/m", "N s/m"];

/// `value` in `unit` for a reader: the SI prefix that puts the mantissa in [1, 1000), with [`DIGITS`] significant
/// digits: 40 m/s -> "40.0000 m/s", 6.01641e-5 s -> "60.1641 µs", 1005.38 N -> "1.00538 kN".
///
/// Units that cannot take a prefix are handled as a reader expects: a mass in kg is shown in g, mg, ... below
/// 1 kg and in kg above; a stiffness "N/m^n" (n != 1) in exponent form ("1.08786e10 N/m^1.5"); a dimensionless
/// value (unit "") and any other unit (e.g. "s/m") in [`plain`] form. Zero is "0 unit"; infinities "inf unit".
pub fn engineering(value: f64, unit: &str) -> String {
    engineering_digits(value, unit, DIGITS)
}

/// [`engineering`] with `digits` significant digits (at least 1), e.g. 3 for a wall-clock time.
pub fn engineering_digits(value: f64, unit: &str, digits: usize) -> String {
    let digits = digits.max(1);
    if !value.is_finite() || value == 0.0 {
        return with_unit(special(value), unit);
    }
    if unit == "kg" {
        return mass(value, digits);
    }
    if unit.starts_with("N/m^") {
        return with_unit(format!("{value:.*e}", digits - 1), unit);
    }
    if !PREFIXABLE.contains(&unit) {
        return with_unit(plain_digits(value, digits), unit);
    }
    prefixed(value, unit, digits).unwrap_or_else(|| with_unit(format!("{value:.*e}", digits - 1), unit))
}

/// `value` with the SI prefix that puts its rounded mantissa in [1, 1000) in front of `unit`; None beyond the
/// prefixes (atto to exa).
fn prefixed(value: f64, unit: &str, digits: usize) -> Option<String> {
    let (negative, mantissa, exponent) = decompose(value, digits);
    let power = exponent.div_euclid(3) * 3;
    let (_, prefix) = PREFIXES.iter().find(|(p, _)| *p == power)?;
    let sign = if negative { "-" } else { "" };
    Some(format!("{sign}{} {prefix}{unit}", place_point(&mantissa, exponent - power)))
}

/// A dimensionless number with [`DIGITS`] significant digits: fixed notation from 1e-4 up to 999999
/// (0.8 -> "0.800000", 1 -> "1.00000"), exponent form outside it ("1.23457e-7"); zero is "0".
pub fn plain(value: f64) -> String {
    plain_digits(value, DIGITS)
}

/// [`plain`] with `digits` significant digits (at least 1).
pub fn plain_digits(value: f64, digits: usize) -> String {
    let digits = digits.max(1);
    if !value.is_finite() || value == 0.0 {
        return special(value);
    }
    let (negative, mantissa, exponent) = decompose(value, digits);
    let sign = if negative { "-" } else { "" };
    if exponent < -4 || exponent >= digits.max(6) as i32 {
        return format!("{value:.*e}", digits - 1);
    }
    let text = if exponent >= 0 {
        place_point(&mantissa, exponent)
    } else {
        format!("0.{}{mantissa}", "0".repeat((-exponent - 1) as usize))
    };
    format!("{sign}{text}")
}

/// A number as given, for inputs such as an exponent or a nominal e: [`plain`] without trailing zeros
/// (1.5 -> "1.5", 0.8 -> "0.8", 1 -> "1", 1.5e-7 -> "1.5e-7").
pub fn short(value: f64) -> String {
    short_digits(value, DIGITS)
}

/// A value a user gave that breaks a rule, as a message echoes it: [`short`], with more digits (up to 17) where six
/// would read as a value that keeps the rule — a restitution of 1.0000001 against [0, 1] is "1.0000001", not "1".
/// (A value that keeps the rule is [`short`].)
pub fn short_outside(value: f64, keeps_rule: impl Fn(f64) -> bool) -> String {
    (DIGITS..=17)
        .map(|digits| short_digits(value, digits))
        .find(|text| !text.parse::<f64>().is_ok_and(&keeps_rule))
        .unwrap_or_else(|| short(value))
}

/// A value a user gave, echoed exactly: [`short`], with as many more digits (up to 17) as it takes to read back as
/// `value` — 0.1 -> "0.1", 1.00000000000001 -> "1.00000000000001", 1e300 -> "1e300".
pub fn short_exact(value: f64) -> String {
    (DIGITS..=17)
        .map(|digits| short_digits(value, digits))
        .find(|text| text.parse::<f64>().is_ok_and(|read| read == value))
        .unwrap_or_else(|| short_digits(value, 17))
}

/// [`short`] with `digits` significant digits (at least 1): 1.0000001 with 8 digits -> "1.0000001".
pub fn short_digits(value: f64, digits: usize) -> String {
    trim_zeros(&plain_digits(value, digits))
}

/// Significant digits of a number in a message ([`brief`]).
pub const BRIEF_DIGITS: usize = 3;

/// A number in a message (an error, a note): `value` in `unit` as the readable report writes it, with three
/// significant digits and no trailing zeros — 1.0933620739432781 m -> "1.09 m", 0.01 m -> "10 mm", 0.0329 kg ->
/// "32.9 g", 2.1e11 Pa -> "210 GPa". Prefixes go from pico to mega (to giga for pressures and stiffnesses: a reader
/// does not think in "Em/s" or "Gm"): beyond, the exponent form in the base unit ("9.2e18 m/s", "1e-100 m"); a unit that takes no prefix keeps its value in
/// [`plain`] form ("1.09e10 N/m^1.5", "0.5"). Zero is "0 unit", infinities "inf unit", NaN "NaN unit".
pub fn brief(value: f64, unit: &str) -> String {
    brief_digits(value, unit, BRIEF_DIGITS)
}

/// [`brief`] with `digits` significant digits (at least 1), for a message that must tell close values apart
/// ([`apart`]).
pub fn brief_digits(value: f64, unit: &str, digits: usize) -> String {
    let digits = digits.max(1);
    if !value.is_finite() || value == 0.0 {
        return with_unit(special(value), unit);
    }
    let text = match brief_prefix(value, unit, digits) {
        // Rounded once, from the value's own digits (a mass below 1 kg from its grams).
        Some((_, _, "g")) => prefixed(value * 1e3, "g", digits),
        Some(_) => prefixed(value, unit, digits),
        None => None,
    };
    trim_zeros(&text.unwrap_or_else(|| with_unit(plain_digits(value, digits), unit)))
}

/// The prefix [`brief_digits`] gives `value` in `unit`: its factor, the prefix and the unit it goes on ("g" for a
/// mass below 1 kg); None where the value keeps the plain or exponent form.
fn brief_prefix(value: f64, unit: &str, digits: usize) -> Option<(f64, &'static str, &'static str)> {
    // Pressures and stiffnesses are read in GPa and GN/m; other quantities beyond mega read better as powers of ten.
    let top = if matches!(unit, "Pa" | "N/m" | "N s/m") { 12 } else { 9 };
    let readable = |exponent: i32| (-12..top).contains(&exponent);
    let grams = value.abs() * 1e3;
    let (base, exponent, scale) = if unit == "kg" {
        let exponent = decompose(grams, digits).2;
        if !grams.is_finite() || exponent >= 3 {
            return None;
        }
        ("g", exponent, 1e-3)
    } else {
        (*PREFIXABLE.iter().find(|&&u| u == unit)?, decompose(value, digits).2, 1.0)
    };
    if !readable(exponent) {
        return None;
    }
    let power = exponent.div_euclid(3) * 3;
    let (_, prefix) = PREFIXES.iter().find(|(p, _)| *p == power)?;
    Some((scale * 10f64.powi(power), prefix, base))
}

/// Two values of one quantity for a message that compares them: [`brief`] each, with more digits (up to 17) while
/// their texts would read equal although the values differ — 1 and 1 + 1e-12 -> ("1 m", "1.000000000001 m").
pub fn apart(a: f64, b: f64, unit: &str) -> (String, String) {
    let mut digits = BRIEF_DIGITS;
    loop {
        let pair = (brief_digits(a, unit, digits), brief_digits(b, unit, digits));
        if pair.0 != pair.1 || a == b || digits >= 17 || a.is_nan() || b.is_nan() {
            return pair;
        }
        digits += 1;
    }
}

/// A vector in a message: its components with three significant digits, in one unit with the prefix [`brief`]
/// gives the largest of them — [0.001, 0, -0.0005] m/s -> "[1, 0, -0.5] mm/s"; a dimensionless one plain
/// ("[0.707, 0.707, 0]").
pub fn brief_vector(components: &[f64], unit: &str) -> String {
    brief_vector_digits(components, unit, BRIEF_DIGITS)
}

/// Two vectors of one quantity for a message that compares them, as [`apart`] does for numbers: [`brief_vector`]
/// each, with more digits while they would read equal although they differ.
pub fn apart_vectors(a: &[f64], b: &[f64], unit: &str) -> (String, String) {
    let mut digits = BRIEF_DIGITS;
    loop {
        let pair = (brief_vector_digits(a, unit, digits), brief_vector_digits(b, unit, digits));
        if pair.0 != pair.1 || a == b || digits >= 17 {
            return pair;
        }
        digits += 1;
    }
}

fn brief_vector_digits(components: &[f64], unit: &str, digits: usize) -> String {
    let largest = components.iter().fold(0.0f64, |m, x| if x.abs() > m || x.is_nan() { x.abs() } else { m });
    let prefix = if largest.is_finite() && largest > 0.0 { brief_prefix(largest, unit, digits) } else { None };
    let (scale, unit) = match prefix {
        Some((scale, prefix, base)) => (scale, format!("{prefix}{base}")),
        None => (1.0, unit.to_string()),
    };
    let shown: Vec<String> = components
        .iter()
        .map(|&x| if x.is_finite() && x != 0.0 { trim_zeros(&plain_digits(x / scale, digits)) } else { special(x) })
        .collect();
    with_unit(format!("[{}]", shown.join(", ")), &unit)
}

/// The number at the start of `text` without trailing zeros after its decimal point ("10.0 mm" -> "10 mm",
/// "1.50e-7 m" -> "1.5e-7 m").
fn trim_zeros(text: &str) -> String {
    let end = text.find(' ').unwrap_or(text.len());
    let (number, rest) = text.split_at(end);
    let (mantissa, exponent) = number.split_once('e').map_or((number, None), |(m, e)| (m, Some(e)));
    let mantissa = if mantissa.contains('.') { mantissa.trim_end_matches('0').trim_end_matches('.') } else { mantissa };
    match exponent {
        Some(exponent) => format!("{mantissa}e{exponent}{rest}"),
        None => format!("{mantissa}{rest}"),
    }
}

/// The SI prefix [`engineering`] would choose for a value of size `scale` in a prefixable unit, and its factor:
/// 0.2 -> (1e-3, "m"). For a set of values shown in one unit (the components of a vector). Falls back to no
/// prefix for zero, non-finite or out-of-range scales.
pub fn prefix_for(scale: f64) -> (f64, &'static str) {
    if !scale.is_finite() || scale == 0.0 {
        return (1.0, "");
    }
    let (_, _, exponent) = decompose(scale, DIGITS);
    let power = exponent.div_euclid(3) * 3;
    PREFIXES.iter().find(|(p, _)| *p == power).map_or((1.0, ""), |&(p, prefix)| (10f64.powi(p), prefix))
}

/// A mass in kg: g and its prefixes below 1 kg (0.06 -> "60.0000 g"), plain kg from 1 kg to 999999 kg, exponent
/// form above.
fn mass(kg: f64, digits: usize) -> String {
    let grams = kg * 1e3;
    if !grams.is_finite() {
        // (A mass near the top of double precision: 1e3 times it overflows.)
        return with_unit(plain_digits(kg, digits), "kg");
    }
    let (_, _, exponent) = decompose(grams, digits);
    // 0.99999996 kg rounds to 1000.00 g: exponent 3, so it is written in kg ("1.00000 kg").
    if exponent < 3
        && let Some(text) = prefixed(grams, "g", digits)
    {
        return text;
    }
    with_unit(plain_digits(kg, digits), "kg")
}

/// Sign, the `digits` significant digits and the decimal exponent of `value` after rounding to those digits:
/// -1005.38 with 6 digits -> (true, "100538", 3).
/// (Callers pass finite values; a non-finite one comes back as zero digits at exponent 0 rather than a panic.)
fn decompose(value: f64, digits: usize) -> (bool, String, i32) {
    let text = format!("{:.*e}", digits - 1, value.abs());
    match text.split_once('e') {
        Some((mantissa, exponent)) => (value < 0.0, mantissa.replace('.', ""), exponent.parse().unwrap_or(0)),
        None => (value < 0.0, "0".repeat(digits), 0),
    }
}

/// Digits with the decimal point after the first `1 + shift` of them ("100538", 0 -> "1.00538").
fn place_point(digits: &str, shift: i32) -> String {
    let whole = (shift + 1) as usize;
    if whole >= digits.len() {
        format!("{digits}{}", "0".repeat(whole - digits.len()))
    } else {
        format!("{}.{}", &digits[..whole], &digits[whole..])
    }
}

fn special(value: f64) -> String {
    if value.is_nan() {
        "NaN".into()
    } else if value.is_infinite() {
        if value > 0.0 { "inf".into() } else { "-inf".into() }
    } else {
        "0".into()
    }
}

fn with_unit(number: String, unit: &str) -> String {
    if unit.is_empty() { number } else { format!("{number} {unit}") }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn masses_at_the_top_of_double_precision_do_not_overflow_into_grams() {
        // 1e308 kg in grams would be 1e311: past f64::MAX (1.8e308), so it stays in kg.
        assert_eq!(engineering(1e308, "kg"), "1.00000e308 kg");
        assert_eq!(engineering(5e307, "J"), "5.00000e307 J");
    }

    #[test]
    fn prefixes_put_the_mantissa_between_1_and_1000() {
        // 40 = 4.0 x 10^1: no prefix, six digits.
        assert_eq!(engineering(40.0, "m/s"), "40.0000 m/s");
        // 6.01641e-5 s = 60.1641e-6 s.
        assert_eq!(engineering(6.01641e-5, "s"), "60.1641 µs");
        // 1005.38 N = 1.00538e3 N.
        assert_eq!(engineering(1005.38, "N"), "1.00538 kN");
        // 2.04412e-5 m = 20.4412e-6 m.
        assert_eq!(engineering(2.04412e-5, "m"), "20.4412 µm");
        // 0.0328820 N s = 32.8820e-3 N s: the prefix goes on the first symbol.
        assert_eq!(engineering(0.032882, "N s"), "32.8820 mN s");
        // 2.1e11 Pa = 210e9 Pa.
        assert_eq!(engineering(2.1e11, "Pa"), "210.000 GPa");
        // 5.4735806287e-14 J = 54.735806287e-15 J -> 54.7358 fJ.
        assert_eq!(engineering(5.4735806287e-14, "J"), "54.7358 fJ");
        // 1 exactly.
        assert_eq!(engineering(1.0, "s"), "1.00000 s");
        assert_eq!(engineering(-0.8, "m/s"), "-800.000 mm/s");
    }

    #[test]
    fn rounding_up_to_a_thousand_takes_the_next_prefix() {
        // 999.9996 rounds to 1000.00 at six digits = 1.00000e3.
        assert_eq!(engineering(999.9996, "N"), "1.00000 kN");
        // 999.9994 stays below: 999.999.
        assert_eq!(engineering(999.9994, "N"), "999.999 N");
        // 9.999996e-7 s rounds to 1.00000e-6 s.
        assert_eq!(engineering(9.999996e-7, "s"), "1.00000 µs");
    }

    #[test]
    fn zero_infinity_and_out_of_range() {
        assert_eq!(engineering(0.0, "m/s"), "0 m/s");
        assert_eq!(engineering(-0.0, "m/s"), "0 m/s");
        assert_eq!(engineering(f64::INFINITY, "kg"), "inf kg");
        // 1.5e-20 m is below atto (1e-18): exponent form in the base unit.
        assert_eq!(engineering(1.5e-20, "m"), "1.50000e-20 m");
        assert_eq!(engineering(3.0e21, "J"), "3.00000e21 J");
    }

    #[test]
    fn masses_are_in_grams_below_a_kilogram() {
        // 0.06 kg = 60 g.
        assert_eq!(engineering(0.06, "kg"), "60.0000 g");
        // 0.016441001554 kg = 16.441001554 g -> 16.4410 g.
        assert_eq!(engineering(0.016441001554, "kg"), "16.4410 g");
        // 2.5e-7 kg = 2.5e-4 g = 250 µg.
        assert_eq!(engineering(2.5e-7, "kg"), "250.000 µg");
        // 0.99999996 kg rounds to 1000.00 g = 1.00000 kg.
        assert_eq!(engineering(0.99999996, "kg"), "1.00000 kg");
        assert_eq!(engineering(1.0, "kg"), "1.00000 kg");
        assert_eq!(engineering(2000.0, "kg"), "2000.00 kg");
        // 5.972e24 kg: exponent form.
        assert_eq!(engineering(5.972e24, "kg"), "5.97200e24 kg");
    }

    #[test]
    fn units_without_prefixes() {
        // A Hertz stiffness: 4/3 E* sqrt(R*) for two 10 mm steel balls = 1.0878565864e10 N/m^1.5.
        assert_eq!(engineering(1.0878565864e10, "N/m^1.5"), "1.08786e10 N/m^1.5");
        // alpha in s/m: 0.18657310168 -> six digits, no prefix.
        assert_eq!(engineering(0.18657310168, "s/m"), "0.186573 s/m");
        // A linear stiffness takes a prefix: 2e4 N/m = 20 kN/m.
        assert_eq!(engineering(2.0e4, "N/m"), "20.0000 kN/m");
        assert_eq!(engineering(0.8, ""), "0.800000");
    }

    #[test]
    fn plain_numbers() {
        assert_eq!(plain(0.8), "0.800000");
        assert_eq!(plain(1.0), "1.00000");
        // 0.88377369295 -> 0.883774 (the 7th digit is 6: round up).
        assert_eq!(plain(0.88377369295), "0.883774");
        assert_eq!(plain(-0.00012345678), "-0.000123457");
        assert_eq!(plain(123456.7), "123457");
        assert_eq!(plain(1234567.0), "1.23457e6");
        assert_eq!(plain(1.2345678e-7), "1.23457e-7");
        assert_eq!(plain(0.0), "0");
        assert_eq!(plain_digits(3.6901870448e-11, 2), "3.7e-11");
    }

    #[test]
    fn short_numbers_drop_trailing_zeros() {
        assert_eq!(short(1.5), "1.5");
        assert_eq!(short(0.8), "0.8");
        assert_eq!(short(1.0), "1");
        assert_eq!(short(100.0), "100");
        assert_eq!(short(-0.25), "-0.25");
        assert_eq!(short(1.5e-7), "1.5e-7");
        // Six significant digits at most: 1.23456789 -> 1.23457.
        assert_eq!(short(1.23456789), "1.23457");
        assert_eq!(short(0.0), "0");
    }

    #[test]
    fn prefix_for_a_scale() {
        assert_eq!(prefix_for(0.2), (1e-3, "m"));
        assert_eq!(prefix_for(2.0), (1.0, ""));
        assert_eq!(prefix_for(1500.0), (1e3, "k"));
        assert_eq!(prefix_for(0.0), (1.0, ""));
    }

    #[test]
    fn numbers_in_messages_read_like_the_report() {
        // A length as a user would write it in a message: 1.0933620739432781 m, and a radius of 1e-2 m.
        assert_eq!(brief(1.0933620739432781, "m"), "1.09 m");
        assert_eq!(brief(1e-2, "m"), "10 mm");
        // 3.288200310757317e-2 kg = 32.882 g.
        assert_eq!(brief(3.288200310757317e-2, "kg"), "32.9 g");
        assert_eq!(brief(2.1e11, "Pa"), "210 GPa");
        assert_eq!(brief(-0.8, "m/s"), "-800 mm/s");
        // 999.6 rounds to 1.00e3 at three digits: the next prefix.
        assert_eq!(brief(999.6, "N"), "1 kN");
        // Beyond giga and below pico: the exponent form in the base unit.
        assert_eq!(brief(9.2e18, "m/s"), "9.2e18 m/s");
        assert_eq!(brief(1e-100, "m"), "1e-100 m");
        assert_eq!(brief(3.0306579066630573e10, "m"), "3.03e10 m");
        assert_eq!(brief(1e300, "kg"), "1e300 kg");
        assert_eq!(brief(5e-20, "kg"), "5e-20 kg");
        // Units without a prefix, and none.
        assert_eq!(brief(1.0878565864e10, "N/m^1.5"), "1.09e10 N/m^1.5");
        assert_eq!(brief(0.5, ""), "0.5");
        assert_eq!(brief(1e-50, ""), "1e-50");
        assert_eq!(brief(0.0, "m"), "0 m");
        assert_eq!(brief(f64::INFINITY, "kg"), "inf kg");
        assert_eq!(brief(f64::NAN, "s"), "NaN s");
    }

    #[test]
    fn close_values_in_a_message_are_told_apart() {
        // 1 and 1 + 1e-12: equal at three digits, apart at thirteen.
        assert_eq!(apart(1.0, 1.0 + 1e-12, "m"), ("1 m".to_string(), "1.000000000001 m".to_string()));
        // 10 mm and 10.5 mm differ at three digits already.
        assert_eq!(apart(0.01, 0.0105, "m"), ("10 mm".to_string(), "10.5 mm".to_string()));
        // Equal values stay brief.
        assert_eq!(apart(0.5, 0.5, ""), ("0.5".to_string(), "0.5".to_string()));
        // 1.0000001 needs eight digits to differ from 1.
        assert_eq!(short_digits(1.0000001, 8), "1.0000001");
        assert_eq!(short_digits(1.0000001, 6), "1");
        assert_eq!(brief_digits(0.0123456, "m", 5), "12.346 mm");
        // Outside [0, 1] by 1e-7: eight digits; 2 is outside at once; 1e-11 is inside (short form).
        assert_eq!(short_outside(1.0000001, |e| (0.0..=1.0).contains(&e)), "1.0000001");
        assert_eq!(short_outside(2.0, |e| (0.0..=1.0).contains(&e)), "2");
        assert_eq!(short_outside(1e-11, |e| (0.0..=1.0).contains(&e)), "1e-11");
        // 0.1 reads back at once; 1 + 1e-14 needs fifteen digits; 1e300 its exponent form.
        assert_eq!(short_exact(0.1), "0.1");
        assert_eq!(short_exact(1.0 + 1e-14), "1.00000000000001");
        assert_eq!(short_exact(1e300), "1e300");
    }

    #[test]
    fn vectors_in_a_message_share_the_largest_component_s_prefix() {
        // 1 mm/s is the largest: every component in mm/s.
        assert_eq!(brief_vector(&[0.001, 0.0, -0.0005], "m/s"), "[1, 0, -0.5] mm/s");
        // 1/sqrt(2) = 0.70710678...
        assert_eq!(
            brief_vector(&[std::f64::consts::FRAC_1_SQRT_2, std::f64::consts::FRAC_1_SQRT_2, 0.0], ""),
            "[0.707, 0.707, 0]"
        );
        assert_eq!(brief_vector(&[1e200, 0.0, 0.0], "m/s"), "[1e200, 0, 0] m/s");
        assert_eq!(brief_vector(&[0.0, 0.0, 0.0], "m/s"), "[0, 0, 0] m/s");
        assert_eq!(brief_vector(&[f64::INFINITY, 1.0, f64::NAN], "m/s"), "[inf, 1, NaN] m/s");
        // 2.5 rad/s takes no prefix.
        assert_eq!(brief_vector(&[2.5, 0.0, 0.0], "rad/s"), "[2.5, 0, 0] rad/s");
        // [1, 0, 0] and [1, 1e-9, 0]: the second component tells them apart at once.
        assert_eq!(apart_vectors(&[1.0, 0.0, 0.0], &[1.0, 1e-9, 0.0], ""), ("[1, 0, 0]".into(), "[1, 1e-9, 0]".into()));
        // 2 and 2 + 4e-9 m/s: ten digits.
        let (a, b) = apart_vectors(&[2.0, 0.0, 0.0], &[2.0 + 4e-9, 0.0, 0.0], "m/s");
        assert_eq!((a.as_str(), b.as_str()), ("[2, 0, 0] m/s", "[2.000000004, 0, 0] m/s"));
    }
}
