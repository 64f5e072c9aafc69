//! Unit strings: `frequency = "1 MHz"`, `static_pressure = "0.082 MPa"`,
//! `youngs_modulus = "71 GPa"`. Every key that holds a quantity with a unit knows its
//! dimension ([`dimension_of_key`]); a string there is a number, a space (optional) and a
//! unit of that dimension with an optional SI prefix, converted to SI here. A bare number
//! is SI, as always. An unknown unit, or a unit of another dimension, is an error naming
//! the unit expected.
//!
//! A small table-driven parser (SI prefixes times the few base units of the project)
//! rather than a units crate: the crates that parse unit strings either panic on bad
//! input, type quantities statically (no dimension chosen from a key at run time) or
//! lack compound units such as `Pa/m` and `J/m^2`.

use crate::error::{Error, Result};
use crate::law::spec::{CompressionSpec, TangentialSpec, TractionSpec};

/// The physical dimension of a scenario key.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dimension {
    /// Hz.
    Frequency,
    /// s.
    Time,
    /// m.
    Length,
    /// m^2.
    Area,
    /// Pa (a pressure, a stress, an elastic modulus).
    Pressure,
    /// N.
    Force,
    /// kg.
    Mass,
    /// kg/m^3.
    Density,
    /// m/s.
    Speed,
    /// m/s^2.
    Acceleration,
    /// Pa/m (an interface stiffness).
    Stiffness,
    /// Pa/m^2 (the quadratic coefficient K1 of the quadratic law).
    StiffnessPerLength,
    /// J/m^2 (a decohesion energy).
    EnergyPerArea,
    /// J s/m^2 (the RCCM viscosity b).
    Viscosity,
}

/// SI prefixes: symbol and power of ten (`u` and `µ` both micro).
const PREFIXES: &[(&str, i32)] = &[
    ("Q", 30),
    ("R", 27),
    ("Y", 24),
    ("Z", 21),
    ("E", 18),
    ("P", 15),
    ("T", 12),
    ("G", 9),
    ("M", 6),
    ("k", 3),
    ("h", 2),
    ("da", 1),
    ("d", -1),
    ("c", -2),
    ("m", -3),
    ("u", -6),
    ("µ", -6),
    ("μ", -6),
    ("n", -9),
    ("p", -12),
    ("f", -15),
    ("a", -18),
];

impl Dimension {
    /// Every dimension, in the order of docs/scenario.md.
    pub const ALL: [Dimension; 14] = [
        Dimension::Frequency,
        Dimension::Time,
        Dimension::Length,
        Dimension::Area,
        Dimension::Pressure,
        Dimension::Force,
        Dimension::Mass,
        Dimension::Density,
        Dimension::Speed,
        Dimension::Acceleration,
        Dimension::Stiffness,
        Dimension::StiffnessPerLength,
        Dimension::EnergyPerArea,
        Dimension::Viscosity,
    ];

    /// What the dimension is, in words.
    pub fn name(self) -> &'static str {
        match self {
            Dimension::Frequency => "a frequency",
            Dimension::Time => "a time",
            Dimension::Length => "a length",
            Dimension::Area => "an area",
            Dimension::Pressure => "a pressure or modulus",
            Dimension::Force => "a force",
            Dimension::Mass => "a mass",
            Dimension::Density => "a density",
            Dimension::Speed => "a speed",
            Dimension::Acceleration => "an acceleration",
            Dimension::Stiffness => "a stiffness per area",
            Dimension::StiffnessPerLength => "a stiffness per area and length",
            Dimension::EnergyPerArea => "an energy per area",
            Dimension::Viscosity => "a viscosity (energy time per area)",
        }
    }

    /// The SI unit (what a bare number means).
    pub fn si_unit(self) -> &'static str {
        self.units()[0].0
    }

    /// An example of a unit string of this dimension.
    pub fn example(self) -> &'static str {
        match self {
            Dimension::Frequency => "\"1 MHz\"",
            Dimension::Time => "\"20 us\"",
            Dimension::Length => "\"30 mm\"",
            Dimension::Area => "\"1 cm^2\"",
            Dimension::Pressure => "\"0.082 MPa\"",
            Dimension::Force => "\"10 kN\"",
            Dimension::Mass => "\"1.6 kg\"",
            Dimension::Density => "\"2710 kg/m^3\"",
            Dimension::Speed => "\"6.3 km/s\"",
            Dimension::Acceleration => "\"9.81 m/s^2\"",
            Dimension::Stiffness => "\"20 TPa/m\"",
            Dimension::StiffnessPerLength => "\"1 PPa/m^2\"",
            Dimension::EnergyPerArea => "\"0.1 J/m^2\"",
            Dimension::Viscosity => "\"10 nJ s/m^2\"",
        }
    }

    /// The dimension whose SI unit is `symbol` (`"m"` -> length).
    pub fn of_si_unit(symbol: &str) -> Option<Dimension> {
        Dimension::ALL
            .iter()
            .copied()
            .find(|d| d.units().first().is_some_and(|u| u.0 == symbol))
    }

    /// Units of the dimension: symbol, factor to SI, and whether an SI prefix may precede
    /// it. The first is the SI unit.
    fn units(self) -> &'static [(&'static str, f64, bool)] {
        match self {
            Dimension::Frequency => &[("Hz", 1.0, true)],
            Dimension::Time => &[("s", 1.0, true)],
            Dimension::Length => &[("m", 1.0, true)],
            Dimension::Area => &[
                ("m^2", 1.0, false),
                ("cm^2", 1e-4, false),
                ("mm^2", 1e-6, false),
            ],
            Dimension::Pressure => &[("Pa", 1.0, true), ("bar", 1e5, true), ("N/m^2", 1.0, false)],
            Dimension::Force => &[("N", 1.0, true)],
            Dimension::Mass => &[("kg", 1.0, false), ("g", 1e-3, true)],
            Dimension::Density => &[("kg/m^3", 1.0, false), ("g/cm^3", 1e3, false)],
            Dimension::Speed => &[("m/s", 1.0, true)],
            Dimension::Acceleration => &[("m/s^2", 1.0, false)],
            Dimension::Stiffness => &[("Pa/m", 1.0, true), ("N/m^3", 1.0, false)],
            Dimension::StiffnessPerLength => &[("Pa/m^2", 1.0, true), ("N/m^4", 1.0, false)],
            Dimension::EnergyPerArea => &[("J/m^2", 1.0, true), ("N/m", 1.0, true)],
            Dimension::Viscosity => &[("J s/m^2", 1.0, true), ("Pa s m", 1.0, true)],
        }
    }

    /// The factor to SI of `unit` (e.g. `MPa` -> 1e6), if it is a unit of this dimension.
    fn factor(self, unit: &str) -> Option<f64> {
        for &(sym, f, prefixable) in self.units() {
            if unit == sym {
                return Some(f);
            }
            if prefixable
                && let Some(head) = unit.strip_suffix(sym)
                && let Some(&(_, e)) = PREFIXES.iter().find(|(p, _)| *p == head)
            {
                return Some(f * 10f64.powi(e));
            }
        }
        None
    }
}

/// The dimension of a scenario key (dotted or not: its last part decides), `None` for a
/// dimensionless key or one that takes no number (`cycles`, `xi`, `m`, `c`, `angle`).
pub fn dimension_of_key(key: &str) -> Option<Dimension> {
    let last = key.rsplit('.').next().unwrap_or(key);
    Some(match last {
        "frequency" | "frequency2" | "first_mode_min" | "first_mode_max" => Dimension::Frequency,
        // (`every`: `[snapshots] every`, the interval between frames)
        "delay" | "duration" | "time_step" | "times" | "every" | "gate" | "taper" => {
            Dimension::Time
        }
        "x" | "length" | "cell_size" | "width" | "thickness" | "element_size" | "pml_thickness"
        | "start" | "end" | "at" | "to" | "z" | "x0" | "x1" | "position" | "gap" => {
            Dimension::Length
        }
        "area" => Dimension::Area,
        "static_pressure"
        | "static_shear"
        | "transition_pressure"
        | "youngs_modulus"
        | "shear_modulus"
        | "amplitude"
        | "pressure" => Dimension::Pressure,
        "static_force" | "static_shear_force" | "peak" => Dimension::Force,
        "mass" => Dimension::Mass,
        "density" => Dimension::Density,
        "cl" | "ct" | "p_speed" | "s_speed" => Dimension::Speed,
        "gravity" => Dimension::Acceleration,
        "stiffness" | "k0" => Dimension::Stiffness,
        "k1" => Dimension::StiffnessPerLength,
        "energy" => Dimension::EnergyPerArea,
        "viscosity" => Dimension::Viscosity,
        // a parameter of a law, in the SI unit its file declares
        _ => {
            return CompressionSpec::unit(last)
                .or_else(|| TractionSpec::unit(last))
                .or_else(|| TangentialSpec::unit(last))
                .and_then(Dimension::of_si_unit);
        }
    })
}

/// Parse a unit string of dimension `dim` into SI (`"0.082 MPa"` -> 82000.0). The error
/// says what is allowed (one line).
pub fn parse(text: &str, dim: Dimension) -> std::result::Result<f64, String> {
    let t = text.trim();
    // the longest leading run that parses as a number
    let numeric = t
        .char_indices()
        .take_while(|&(_, c)| c.is_ascii_digit() || matches!(c, '.' | '+' | '-' | 'e' | 'E'))
        .map(|(i, c)| i + c.len_utf8())
        .last()
        .unwrap_or(0);
    let split = (1..=numeric)
        .rev()
        .find(|&k| t.is_char_boundary(k) && t[..k].parse::<f64>().is_ok());
    let expected = || {
        format!(
            "expected {} in {} (a number) or a number with a unit such as {}",
            dim.name(),
            dim.si_unit(),
            dim.example()
        )
    };
    let Some(k) = split else {
        return Err(expected());
    };
    let value: f64 = t[..k].parse().map_err(|_| expected())?;
    let unit = t[k..].trim();
    if unit.is_empty() {
        return Err(format!(
            "a string needs a unit: {}",
            expected().trim_start_matches("expected ")
        ));
    }
    if let Some(f) = dim.factor(unit) {
        return Ok(value * f);
    }
    match Dimension::ALL.iter().find(|d| d.factor(unit).is_some()) {
        Some(other) => Err(format!(
            "`{unit}` is a unit of {}; {}",
            other.name(),
            expected()
        )),
        None => Err(format!("unknown unit `{unit}`; {}", expected())),
    }
}

/// A number of a file, in SI, for `key`: an integer, a float or, when the key has a
/// dimension, a unit string. The error says what is allowed.
pub fn si_number(v: &toml::Value, key: &str) -> std::result::Result<f64, String> {
    match v {
        toml::Value::Float(x) => Ok(*x),
        toml::Value::Integer(i) => Ok(*i as f64),
        toml::Value::String(s) => match dimension_of_key(key) {
            Some(dim) => parse(s, dim),
            None => Err("expected a number (this key takes no unit)".to_string()),
        },
        _ => Err(match dimension_of_key(key) {
            Some(dim) => format!(
                "expected a number ({}) or a unit string such as {}",
                dim.si_unit(),
                dim.example()
            ),
            None => "expected a number".to_string(),
        }),
    }
}

/// Replace every unit string at a key with a dimension in `table` (nested tables, arrays
/// of tables and arrays of numbers included) by its SI number. Errors name `file`, the
/// field, the value and the unit expected.
pub fn to_si(table: &mut toml::Table, file: &str) -> Result<()> {
    to_si_at(table, "", file)
}

fn to_si_at(table: &mut toml::Table, prefix: &str, file: &str) -> Result<()> {
    for (key, v) in table.iter_mut() {
        let path = if prefix.is_empty() {
            key.clone()
        } else {
            format!("{prefix}.{key}")
        };
        convert(v, key, &path, file)?;
    }
    Ok(())
}

fn convert(v: &mut toml::Value, key: &str, path: &str, file: &str) -> Result<()> {
    match v {
        toml::Value::Table(t) => to_si_at(t, path, file),
        toml::Value::Array(items) => {
            for (i, item) in items.iter_mut().enumerate() {
                convert(item, key, &format!("{path}.{i}"), file)?;
            }
            Ok(())
        }
        toml::Value::String(s) => {
            let Some(dim) = dimension_of_key(key) else {
                return Ok(());
            };
            let x =
                parse(s, dim).map_err(|why| Error::invalid(file, path, format!("\"{s}\""), why))?;
            *v = toml::Value::Float(x);
            Ok(())
        }
        _ => Ok(()),
    }
}

/// A serde error message in plain words: "expected f64" becomes "expected a number"
/// (and likewise for the integer types), for people who do not read Rust.
pub fn plain_serde_message(message: &str) -> String {
    let mut m = message.replace('\n', " ");
    for (rust, plain) in [
        ("expected f64", "expected a number"),
        ("expected f32", "expected a number"),
        ("expected usize", "expected a whole number >= 0"),
        ("expected u64", "expected a whole number >= 0"),
        ("expected u32", "expected a whole number >= 0"),
        ("expected i64", "expected a whole number"),
        ("expected i32", "expected a whole number"),
        ("expected a boolean", "expected true or false"),
    ] {
        m = m.replace(rust, plain);
    }
    // Rust type names: `expected struct IncidentSpec`, `expected internally tagged enum
    // TractionSpec` (every tagged enum here is a law, tagged by `law`)
    for (rust, plain) in [
        (
            "expected internally tagged enum ",
            "expected a table naming its law, e.g. { law = \"rigid\" }",
        ),
        ("expected struct ", "expected a table { key = value, ... }"),
    ] {
        while let Some(at) = m.find(rust) {
            let rest = &m[at + rust.len()..];
            let name_len = rest
                .find(|c: char| !c.is_ascii_alphanumeric() && c != '_')
                .unwrap_or(rest.len());
            m = format!("{}{plain}{}", &m[..at], &rest[name_len..]);
        }
    }
    // toml ends some messages with the table they arose in (` in `crack``) and a newline:
    // the error's key names the place already
    let m = m.trim_end();
    match m.rsplit_once(" in `") {
        Some((head, table)) if table.ends_with('`') && !table[..table.len() - 1].contains('`') => {
            head.to_string()
        }
        _ => m.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn serde_messages_read_as_plain_words() {
        assert_eq!(
            plain_serde_message("unknown field `x`, expected `a` or `b` in `crack`\n"),
            "unknown field `x`, expected `a` or `b`"
        );
        assert_eq!(
            plain_serde_message("invalid type: string \"a\", expected f64"),
            "invalid type: string \"a\", expected a number"
        );
        assert_eq!(
            plain_serde_message("invalid type: integer `5`, expected struct IncidentSpec"),
            "invalid type: integer `5`, expected a table { key = value, ... }"
        );
        assert_eq!(
            plain_serde_message(
                "invalid type: string \"free\", expected internally tagged enum TractionSpec"
            ),
            "invalid type: string \"free\", expected a table naming its law, e.g. { law = \"rigid\" }"
        );
    }

    #[test]
    fn unit_strings_convert_to_si() {
        let p = |s, d| parse(s, d).unwrap();
        assert_eq!(p("1 MHz", Dimension::Frequency), 1e6);
        assert_eq!(p("0.082 MPa", Dimension::Pressure), 0.082e6);
        assert_eq!(p("71 GPa", Dimension::Pressure), 71e9);
        assert_eq!(p("5kHz", Dimension::Frequency), 5e3);
        assert!((p("30 mm", Dimension::Length) - 0.03).abs() < 1e-15);
        assert_eq!(p("-30 mm", Dimension::Length), -0.03);
        assert!((p("20 µs", Dimension::Time) - 20e-6).abs() < 1e-18);
        assert_eq!(p("2710 kg/m^3", Dimension::Density), 2710.0);
        assert_eq!(p("1.19 g/cm^3", Dimension::Density), 1190.0);
        assert_eq!(p("2e13 Pa/m", Dimension::Stiffness), 2e13);
        assert_eq!(p("20 TPa/m", Dimension::Stiffness), 20e12);
        assert_eq!(p("6.3 km/s", Dimension::Speed), 6300.0);
        assert_eq!(p("1.5e-3 m", Dimension::Length), 1.5e-3);
        assert_eq!(p("0.1 J/m^2", Dimension::EnergyPerArea), 0.1);
    }

    #[test]
    fn every_unit_a_law_file_declares_is_a_known_dimension() {
        // the parameters of every law of the three tables; a law's key whose unit its
        // file declares is read with unit strings without a line here
        let names = [
            "stiffness",
            "k0",
            "k1",
            "c",
            "m",
            "transition_pressure",
            "zero_pressure_fraction",
            "energy",
            "viscosity",
            "friction",
            "mu_s",
            "mu_d",
            "d_c",
        ];
        let mut declared = 0;
        for name in names {
            for unit in [
                CompressionSpec::unit(name),
                TractionSpec::unit(name),
                TangentialSpec::unit(name),
            ]
            .into_iter()
            .flatten()
            {
                declared += 1;
                let dim = Dimension::of_si_unit(unit);
                assert!(dim.is_some(), "{name}: unit {unit} is no known dimension");
                assert_eq!(
                    dimension_of_key(&format!("interface.x.{name}")),
                    dim,
                    "{name}"
                );
            }
        }
        assert!(declared >= 8, "{declared} units declared");
        // dimensionless parameters have none
        assert_eq!(dimension_of_key("interface.compression.m"), None);
        assert_eq!(dimension_of_key("interface.tangential.mu_s"), None);
        assert_eq!(
            dimension_of_key("interface.tangential.d_c"),
            Some(Dimension::Length)
        );
    }

    #[test]
    fn unknown_and_mismatched_units_are_errors() {
        let e = parse("0.082 MPa", Dimension::Frequency).unwrap_err();
        assert!(e.contains("`MPa` is a unit of a pressure"), "{e}");
        assert!(e.contains("Hz"), "{e}");
        let e = parse("1 MHZ", Dimension::Frequency).unwrap_err();
        assert!(e.contains("unknown unit `MHZ`"), "{e}");
        assert!(parse("MHz", Dimension::Frequency).is_err());
        assert!(parse("15", Dimension::Frequency)
            .unwrap_err()
            .contains("needs a unit"));
    }

    #[test]
    fn tables_convert_in_place_and_errors_name_the_field() {
        let mut t: toml::Table = r#"
            [interface]
            static_pressure = "0.82 MPa"
            compression = { law = "table", pressure = ["0 Pa", "1 MPa"], stiffness = [1e12, "2 TPa/m"] }
            [incident]
            frequency = "1 MHz"
            kind = "tone_burst"
        "#
        .parse()
        .unwrap();
        to_si(&mut t, "s.toml").unwrap();
        assert_eq!(t["interface"]["static_pressure"].as_float(), Some(0.82e6));
        assert_eq!(
            t["interface"]["compression"]["stiffness"][1].as_float(),
            Some(2e12)
        );
        assert_eq!(t["incident"]["kind"].as_str(), Some("tone_burst"));
        let mut bad: toml::Table = "[incident]\nfrequency = \"0.082 MPa\"".parse().unwrap();
        let e = to_si(&mut bad, "s.toml").unwrap_err().to_string();
        assert!(
            e.starts_with("s.toml: field `incident.frequency` = \"0.082 MPa\": `MPa` is a unit"),
            "{e}"
        );
    }
}
