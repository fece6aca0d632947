//! The readable report (`impact run SCENE` without `--json`) for every law: numbers of at most six significant
//! digits, in units with SI prefixes and without exponent form for ordinary values; only what a law has; V0 of a
//! symmetric impact shown as 0; times of the contact since first contact.

mod common;

use impact::law::LawKind;
use impact::output::table::render;

/// Two steel balls as in docs/references.md (r = 10 mm, E = 210 GPa, nu = 0.3, rho = 7850 kg/m^3) closing at 1 m/s
/// (+0.5 and -0.5 m/s along x), with the given `[contact]` lines; `gap` (m) places them apart on the x axis.
fn steel_pair(contact: &str, gap: Option<f64>) -> String {
    let position = |x: f64| gap.map_or(String::new(), |_| format!("position = [{x:?}, 0.0, 0.0]\n"));
    let body = |name: &str, speed: f64, x: f64| {
        format!(
            "[[bodies]]\nname = \"{name}\"\nradius = 0.01\ndensity = 7850\nvelocity = [{speed:?}, 0.0, 0.0]\n{}\
             young = 2.1e11\npoisson = 0.3\n\n",
            position(x)
        )
    };
    let centres = 0.02 + gap.unwrap_or(0.0);
    format!("{}{}[contact]\n{contact}\n", body("A", 0.5, 0.0), body("B", -0.5, centres))
}

/// `[contact]` lines that every law accepts: Kelvin–Voigt needs a numeric (linear) stiffness, Brilliantov its
/// material time A, Hertz nothing; the others take a nominal e.
fn contact_for(law: &str) -> String {
    match law {
        "hertz" => "law = \"hertz\"".into(),
        "kelvin-voigt" => "law = \"kelvin-voigt\"\nstiffness = 1e7\nrestitution = 0.8".into(),
        "brilliantov" => "law = \"brilliantov\"\ndamping = 1e-6".into(),
        "thornton" => "law = \"thornton\"\nyield_pressure = 1.6e9".into(),
        "hertz-dashpot" => "law = \"hertz-dashpot\"\ndamping = 20.0".into(),
        "mujoco" => "law = \"mujoco\"\nsolref = [0.0002, 0.3]".into(),
        "adams-impact" => "law = \"adams-impact\"\ncmax = 20.0\ndmax = 1e-6".into(),
        other => format!("law = \"{other}\"\nrestitution = 0.8"),
    }
}

fn rendered(toml: &str) -> String {
    render(&common::run(toml))
}

/// The sections of a report: blocks separated by blank lines, each a title line and its rows.
fn sections(text: &str) -> Vec<(&str, Vec<&str>)> {
    text.split("\n\n")
        .filter_map(|block| {
            let mut lines = block.lines();
            Some((lines.next()?, lines.collect()))
        })
        .collect()
}

/// The rows of the first section whose title starts with `title`.
#[track_caller]
fn section<'a>(text: &'a str, title: &str) -> Vec<&'a str> {
    sections(text)
        .into_iter()
        .find(|(heading, _)| heading.starts_with(title))
        .unwrap_or_else(|| panic!("no section `{title}` in\n{text}"))
        .1
}

/// The value of the row labelled exactly `label` in `lines` (rows are "  LABEL   VALUE").
fn value<'a>(lines: &[&'a str], label: &str) -> Option<&'a str> {
    lines.iter().find_map(|line| {
        let rest = line.trim_start().strip_prefix(label)?;
        rest.starts_with("  ").then(|| rest.trim())
    })
}

#[track_caller]
fn row<'a>(text: &'a str, title: &str, label: &str) -> &'a str {
    value(&section(text, title), label).unwrap_or_else(|| panic!("no row `{label}` in section `{title}`:\n{text}"))
}

/// The numbers written in a line: its words, stripped of brackets and punctuation, that parse as numbers.
fn numbers(line: &str) -> Vec<&str> {
    line.split(|c: char| c.is_whitespace() || c == ',')
        .map(|word| word.trim_matches(|c: char| "[]()=:;".contains(c)))
        .filter(|word| word.parse::<f64>().is_ok() && word.chars().any(|c| c.is_ascii_digit()))
        .collect()
}

/// Significant digits of a number as written: "40.0000" -> 6, "0.000123457" -> 6, "1.5e-7" -> 2, "0" -> 0.
fn significant_digits(number: &str) -> usize {
    let mantissa = number.split(['e', 'E']).next().unwrap_or(number);
    let digits: String = mantissa.chars().filter(char::is_ascii_digit).collect();
    digits.trim_start_matches('0').len()
}

fn exponent_form(number: &str) -> bool {
    number.contains(['e', 'E'])
}

#[test]
fn every_law_renders_readable_numbers() {
    let laws = LawKind::names();
    assert_eq!(laws.len(), 18, "docs/laws.md lists 18 laws");
    for law in laws {
        let text = rendered(&steel_pair(&contact_for(law), None));
        assert!(text.contains(&format!("law: {law}")), "{law}: the law is named\n{text}");
        for line in text.lines() {
            for number in numbers(line) {
                assert!(
                    significant_digits(number) <= 6,
                    "{law}: `{number}` has more than 6 digits in `{line}`\n{text}"
                );
            }
        }
        // Ordinary values never in exponent form; only the stiffness (N/m^n has no prefix), relative errors,
        // differences from the simulation, the energy balance's closure and the solver's tolerances may be.
        let ordinary = ["impact", "contact (", "coefficient of restitution", "energy", "bodies", "instantaneous"];
        let checked = sections(&text).into_iter().filter(|(title, _)| ordinary.iter().any(|o| title.starts_with(o)));
        // Five sections, and one or two instantaneous impacts (none with the nominal e when damping was given).
        assert!(checked.clone().count() >= 6, "{law}: sections missing\n{text}");
        let error_size = |line: &&str| line.contains("difference") || line.contains("balance");
        for line in checked.flat_map(|(_, rows)| rows).filter(|line| !error_size(line)) {
            assert!(!numbers(line).into_iter().any(exponent_form), "{law}: exponent form in `{line}`\n{text}");
        }
        // (Brilliantov's law has no exact reference.)
        let reference = sections(&text).into_iter().filter(|(title, _)| title.starts_with("exact reference"));
        for line in reference.flat_map(|(_, rows)| rows).skip(2) {
            let exact = numbers(line).into_iter().next();
            assert!(!exact.is_some_and(exponent_form), "{law}: exact value in exponent form in `{line}`\n{text}");
        }
        // Closing at 0.5 - (-0.5) = 1 m/s.
        assert_eq!(row(&text, "impact", "approach speed v0"), "1.00000 m/s", "{law}");
        // Equal masses at +0.5 and -0.5 m/s: V0 = (m 0.5 + m (-0.5)) / 2m = 0, whatever the law.
        assert_eq!(row(&text, "contact", "common normal velocity V0"), "0 m/s", "{law}:\n{text}");
        assert_eq!(row(&text, "bodies", "at maximum compression"), "[0, 0, 0] m/s", "{law}:\n{text}");
        // Steel balls at 1 m/s touch for tens of microseconds over tens of micrometres (docs/references.md: 60.2 us and
        // 20.4 um elastic; a linear k = 1e7 N/m gives pi sqrt(m*/k) = pi sqrt(0.016441/1e7) = 127 us).
        let contact = section(&text, "contact");
        assert!(value(&contact, "separation at (= contact duration)").is_some_and(|t| t.ends_with(" µs")), "{law}");
        assert!(value(&contact, "maximum penetration").is_some_and(|d| d.ends_with(" µm")), "{law}");
        assert!(value(&contact, "deformation impulse").is_some_and(|p| p.ends_with(" mN s")), "{law}");
    }
}

#[test]
fn only_what_the_law_has_is_printed() {
    let damping_rows =
        ["damping c", "damping alpha", "damping a", "material time A", "damping m* b", "full damping c_max"];
    for law in LawKind::names() {
        let text = rendered(&steel_pair(&contact_for(law), None));
        let lines = section(&text, "law:");
        let damping = damping_rows.iter().filter(|label| value(&lines, label).is_some()).count();
        let nominal = value(&lines, "nominal e");
        let dissipated = value(&section(&text, "energy"), "dissipated by damping");
        match law {
            // Elastic: no damping parameter, no nominal e to choose, nothing dissipated by damping.
            "hertz" => {
                assert_eq!(damping, 0, "hertz has no damping:\n{text}");
                assert_eq!(nominal, None, "hertz:\n{text}");
                assert_eq!(dissipated, None, "hertz:\n{text}");
            }
            // The damping was given: there is no nominal e.
            "brilliantov" => {
                assert_eq!(damping, 1, "{text}");
                assert_eq!(nominal, None, "{text}");
                assert_eq!(row(&text, "law:", "material time A"), "1.00000 µs", "A = 1e-6 s as given");
            }
            // Plastic: no damping, no nominal e; its yield pressure and speed, and what the dent took.
            "thornton" => {
                assert_eq!(damping, 0, "thornton has no damping:\n{text}");
                assert_eq!(nominal, None, "thornton:\n{text}");
                assert_eq!(row(&text, "law:", "yield pressure p_y"), "1.60000 GPa", "p_y as given");
                assert!(value(&section(&text, "energy"), "dissipated in the plastic dent").is_some(), "{text}");
            }
            // The simulators' laws take their damping from their own keys: no nominal e.
            "hertz-dashpot" | "mujoco" | "adams-impact" => {
                assert_eq!(damping, 1, "{law} has one damping parameter:\n{text}");
                assert_eq!(nominal, None, "{law}: no nominal e\n{text}");
                assert!(dissipated.is_some(), "{law}:\n{text}");
            }
            _ => {
                assert_eq!(damping, 1, "{law} has one damping parameter:\n{text}");
                assert_eq!(nominal, Some("0.8"), "{law}: the nominal e as given\n{text}");
                assert!(dissipated.is_some(), "{law}:\n{text}");
            }
        }
        assert!(value(&lines, "stiffness K").or(value(&lines, "stiffness k")).is_some(), "{law}:\n{text}");
    }
}

/// docs/references.md for the steel pair: m = (4/3) pi r^3 rho, m* = m/2, E* = E / (2 (1 - nu^2)), R* = r/2,
/// K = (4/3) E* sqrt(R*), dmax = (5 m* v0^2 / (4K))^(2/5), Fmax = K dmax^(3/2), tc = 2.9432751843 dmax / v0.
/// Returns (m*, dmax, tc, Fmax).
fn hertz_steel_pair_by_hand() -> (f64, f64, f64, f64) {
    let (r, young, nu, rho, v0) = (0.01_f64, 2.1e11_f64, 0.3_f64, 7850.0_f64, 1.0_f64);
    let m = 4.0 / 3.0 * std::f64::consts::PI * r.powi(3) * rho;
    let m_eff = m / 2.0;
    let k = 4.0 / 3.0 * (young / (2.0 * (1.0 - nu * nu))) * (r / 2.0).sqrt();
    let dmax = (5.0 * m_eff * v0 * v0 / (4.0 * k)).powf(0.4);
    (m_eff, dmax, 2.9432751843 * dmax / v0, k * dmax.powf(1.5))
}

/// Asserts that `written` (a number with a prefixed unit) is `exact` to six significant digits.
#[track_caller]
fn six_digits(written: f64, exact: f64) {
    assert!(((written - exact) / exact).abs() < 5e-6, "{written} is not {exact} to six digits");
}

#[test]
fn hertz_steel_pair_reads_in_microseconds_micrometres_and_kilonewtons() {
    let (m_eff, dmax, tc, fmax) = hertz_steel_pair_by_hand();
    // docs/references.md: dmax = 2.04412e-5 m, tc = 6.01641e-5 s, Fmax = 1005.38 N; the strings below are those values
    // written with their SI prefixes, checked against the hand calculation first.
    six_digits(16.4410e-3, m_eff);
    six_digits(20.4412e-6, dmax);
    six_digits(60.1641e-6, tc);
    six_digits(30.0821e-6, tc / 2.0);
    six_digits(1.00538e3, fmax);
    six_digits(8.22050e-3, m_eff / 2.0); // kinetic energy (1/2) m* v0^2 in the centre-of-mass frame
    let text = rendered(&steel_pair(&contact_for("hertz"), None));
    assert_eq!(row(&text, "impact", "effective mass m*"), "16.4410 g");
    assert_eq!(row(&text, "contact", "first contact, in the scene's time"), "t = 0 s");
    assert_eq!(row(&text, "contact", "maximum compression (d' = 0) at"), "30.0821 µs");
    assert_eq!(row(&text, "contact", "separation at (= contact duration)"), "60.1641 µs");
    assert_eq!(row(&text, "contact", "maximum penetration"), "20.4412 µm");
    assert_eq!(row(&text, "contact", "maximum force"), "1.00538 kN");
    // The deformation impulse of a symmetric pair is m* v0 = 16.4410 mN s.
    assert_eq!(row(&text, "contact", "deformation impulse"), "16.4410 mN s");
    assert_eq!(row(&text, "energy", "kinetic energy before"), "8.22050 mJ");
    assert_eq!(row(&text, "bodies", "velocity before"), "[0.500000, 0, 0] m/s");
    assert!(row(&text, "exact reference", "contact duration").starts_with("60.1641 µs "), "{text}");
    // e = 1 to rounding, three ways.
    assert_eq!(row(&text, "coefficient of restitution", "velocity ratio (Newton)"), "1.00000");
}

#[test]
fn contact_times_are_measured_from_first_contact_when_positions_are_given() {
    // Centres 21 mm apart, radii 10 mm each: a 1 mm gap closed at 1 m/s, so first contact at t = 1 ms; the contact
    // itself is the one of the unplaced pair (tc/2 = 30.0821 us, tc = 60.1641 us, checked above by hand).
    let (_, _, tc, _) = hertz_steel_pair_by_hand();
    six_digits(30.0821e-6, tc / 2.0);
    let text = rendered(&steel_pair(&contact_for("hertz"), Some(0.001)));
    assert_eq!(row(&text, "contact", "first contact, in the scene's time"), "t = 1.00000 ms", "{text}");
    assert_eq!(row(&text, "contact", "maximum compression (d' = 0) at"), "30.0821 µs", "{text}");
    assert_eq!(row(&text, "contact", "maximum force at"), "30.0821 µs", "{text}");
    assert_eq!(row(&text, "contact", "separation at (= contact duration)"), "60.1641 µs", "{text}");
    assert!(text.contains("\nexact reference (times since first contact)\n"), "{text}");
    assert!(row(&text, "exact reference", "maximum compression at").starts_with("30.0821 µs "), "{text}");
    assert!(row(&text, "exact reference", "contact duration").starts_with("60.1641 µs "), "{text}");
    // The scene time of first contact is given once.
    assert_eq!(text.matches("1.00000 ms").count(), 1, "{text}");
}

#[test]
fn a_real_common_velocity_and_a_wall_are_shown_as_they_are() {
    // Equal masses of 1 kg at +5 and -7.071 m/s: V0 = (5 - 7.071)/2 = -1.0355 m/s, not rounding noise.
    let text = rendered(
        "[[bodies]]\nradius = 0.05\nmass = 1.0\nvelocity = [5.0, 0.0, 0.0]\nyoung = 2.1e11\npoisson = 0.3\n\n\
         [[bodies]]\nradius = 0.05\nmass = 1.0\nvelocity = [-7.071, 0.0, 0.0]\nyoung = 2.1e11\npoisson = 0.3\n\n\
         [contact]\nlaw = \"hertz\"\n",
    );
    assert_eq!(row(&text, "contact", "common normal velocity V0"), "-1.03550 m/s", "{text}");
    assert_eq!(row(&text, "impact", "approach speed v0"), "12.0710 m/s", "5 + 7.071");
    // A 1 kg ball at 0.2 m/s on an immovable flat wall: the wall is named as such, with one velocity.
    let text = rendered(
        "[[bodies]]\nname = \"ball\"\nradius = 0.05\nmass = 1.0\nvelocity = [0.2, 0.0, 0.0]\nyoung = 2.1e11\n\
         poisson = 0.3\n\n[[bodies]]\nname = \"wall\"\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\n\
         young = inf\n\n[contact]\nlaw = \"hertz\"\n",
    );
    let bodies = section(&text, "bodies");
    assert!(bodies.contains(&"  wall: immovable, flat"), "{text}");
    // A speed scale of 0.2 m/s puts every velocity in mm/s.
    assert_eq!(value(&bodies, "velocity before"), Some("[200.000, 0, 0] mm/s"), "{text}");
    assert_eq!(value(&bodies, "velocity throughout"), Some("[0, 0, 0] mm/s"), "{text}");
    assert_eq!(row(&text, "impact", "effective mass m*"), "1.00000 kg", "m* = m for a wall");
}
