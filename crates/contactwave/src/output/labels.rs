//! Axis labels a person reads: the name and SI unit of a sweep parameter (a dotted scenario
//! key such as `interface.static_pressure`) or of a summary key (`A2_over_Ainc`), as in
//! docs/scenario.md, e.g. `static pressure p0` in `Pa`.

/// (name, SI unit) of a dotted scenario key or a summary/CSV key; unknown keys get their
/// words (`segment.0.mass` -> `segment 1 mass`) and a unit guessed from the last word
/// (empty when none is known). Interfaces and segments are numbered from 0 in names, as in
/// the keys (`_0`, `interface.0`, `segment.0`): interface 0 is the first in stack order.
pub fn quantity(key: &str) -> (String, &'static str) {
    if let Some((name, unit)) = known(key) {
        return (name.to_string(), unit);
    }
    // per-crack summary keys of 2D runs: `crack_max_gap_0` -> largest opening, crack 0
    if let Some((base, i)) = key.strip_prefix("crack_").and_then(|k| k.rsplit_once('_'))
        && let Ok(i) = i.parse::<usize>()
    {
        let (name, unit) = match base {
            "max_gap" => ("largest opening".to_string(), "m"),
            "max_slip" => ("largest slip".to_string(), "m"),
            "min_adhesion" => ("least adhesion beta".to_string(), ""),
            other => (other.replace('_', " "), guess_unit(other)),
        };
        return (format!("{name}, crack {i}"), unit);
    }
    // per-receiver harmonic keys of 2D runs and measured records: `top_A2_over_A1` ->
    // A2 / A1 at top
    // (the longest first: `top_A2_over_A1` ends in `A1` too)
    let mut harmonics = crate::analysis::HARMONIC_KEYS;
    harmonics.sort_by_key(|h| std::cmp::Reverse(h.len()));
    for h in harmonics {
        if let Some(receiver) = key
            .strip_suffix(h)
            .and_then(|r| r.strip_suffix('_'))
            .filter(|r| !r.is_empty())
        {
            // an amplitude's unit is its record's (m/s or Pa), which the key does not say
            let (name, unit) = match h {
                "A1" | "A2" | "A3" | "A4" | "A5" => (h.to_string(), ""),
                _ => quantity(h),
            };
            return (format!("{name} at {receiver}"), unit);
        }
    }
    // per-interface summary keys: `mean_contact_stiffness_0` -> interface 0 (numbered from
    // 0, as the keys `_0`, `_1` and `interface.0` are)
    if let Some((base, i)) = key.rsplit_once('_')
        && let Ok(i) = i.parse::<usize>()
    {
        let (name, unit) = quantity(base);
        return (format!("{name}, interface {i}"), unit);
    }
    let last = key.rsplit('.').next().unwrap_or(key);
    // indices stay as the key writes them (0-based: `segment.0.mass` -> segment 0 mass)
    let words: Vec<String> = key.split(['.', '_']).map(str::to_string).collect();
    (words.join(" "), guess_unit(last))
}

/// An axis label `name, unit` (`name` alone for a dimensionless quantity); `prefix` is the
/// SI prefix the values were scaled by (e.g. `M` for MPa).
pub fn axis_label(key: &str, prefix: &str) -> String {
    let (name, unit) = quantity(key);
    if unit.is_empty() {
        name
    } else {
        format!("{name}, {prefix}{unit}")
    }
}

fn known(key: &str) -> Option<(&'static str, &'static str)> {
    // parameters (dotted scenario keys) first, then summary keys
    let k = key
        .strip_prefix("interface.")
        .map(|r| ("interface", r))
        .or_else(|| key.strip_prefix("incident.").map(|r| ("incident", r)));
    let v = match (k, key) {
        (Some(("interface", "static_pressure")), _) => ("static pressure p0", "Pa"),
        (Some(("interface", "static_shear")), _) => ("static shear q0", "Pa"),
        (Some(("interface", "traction.stiffness")), _) => ("traction stiffness C_N", "Pa/m"),
        (Some(("interface", "traction.energy")), _) => ("decohesion energy w", "J/m^2"),
        (Some(("interface", "traction.viscosity")), _) => ("viscosity b", "J s/m^2"),
        (Some(("interface", "compression.stiffness")), _) => ("compression stiffness K", "Pa/m"),
        (Some(("interface", "compression.c")), _) => ("power-law coefficient C", "Pa^(1-m)/m"),
        (Some(("interface", "compression.m")), _) => ("power-law exponent m", ""),
        (Some(("interface", "tangential.friction")), _) => ("friction coefficient mu", ""),
        (Some(("interface", "tangential.stiffness")), _) => ("tangential stiffness", "Pa/m"),
        (Some(("incident", "xi")), _) | (_, "xi") => ("load ratio xi", ""),
        (Some(("incident", "amplitude")), _) => ("incident amplitude", "Pa"),
        (Some(("incident", "frequency")), _) => ("frequency f0", "Hz"),
        (Some(("incident", "frequency2")), _) => ("frequency f2", "Hz"),
        (Some(("incident", "cycles")), _) => ("burst cycles", ""),
        (Some(("incident", "shear_amplitude")), _) => ("shear amplitude", "Pa"),
        (_, "excitation.peak") => ("peak force", "N"),
        (_, "excitation.duration") => ("pulse duration", "s"),
        (_, "solver.samples_per_period") => ("samples per period", ""),
        (_, "model.cell_size") => ("cell size", "m"),
        (_, "model.time_step") => ("time step", "s"),
        (_, "model.duration") => ("duration", "s"),
        (_, "amplitude") => ("incident amplitude", "Pa"),
        (_, "static_pressure") => ("static pressure p0", "Pa"),
        (_, "frequency") => ("frequency f0", "Hz"),
        (_, "A_inc") => ("incident velocity A_inc", "m/s"),
        (_, "A2_over_A1") => ("A2 / A1", ""),
        (_, "beta_star") => ("nonlinearity parameter A2 / A1^2", "s/m"),
        (_, "beta_end") => ("adhesion beta at the end", ""),
        (_, "max_gap") => ("largest gap", "m"),
        (_, "first_mode_hz") => ("first mode f1", "Hz"),
        (_, "second_harmonic_hz") => ("second harmonic 2 f1", "Hz"),
        (_, "guide_mode_hz") => ("guide mode", "Hz"),
        (_, "A1") => ("response at the first mode A1", "m/s^2"),
        (_, "peak_force") => ("peak force", "N"),
        (_, "mean_contact_stiffness") => ("mean contact stiffness K", "Pa/m"),
        (_, "min_contact_pressure") => ("minimum contact pressure", "Pa"),
        (_, "static_interface_pressure") => ("static interface pressure", "Pa"),
        (_, "static_interface_closure") => ("static interface closure", "m"),
        (_, "friction_coefficient") => ("friction coefficient mu", ""),
        (_, "friction_ratio") => ("friction ratio", ""),
        (_, "friction_dissipation_fraction") => ("friction dissipation / incident energy", ""),
        _ => return harmonic(key),
    };
    Some(v)
}

/// `A2_over_Ainc`, `shear_A3_over_A1`, `shear_tr_A3_over_A1`, the oblique waves'
/// `reflected_P_A1_over_Ainc` ...: harmonic ratios.
fn harmonic(key: &str) -> Option<(&'static str, &'static str)> {
    Some(match key {
        "A1_over_Ainc" => ("A1 / A_inc", ""),
        "A2_over_Ainc" => ("A2 / A_inc", ""),
        "A3_over_Ainc" => ("A3 / A_inc", ""),
        "shear_A3_over_A1" => ("A3 / A1 (shear, reflected)", ""),
        "shear_tr_A3_over_A1" => ("A3 / A1 (shear, transmitted)", ""),
        "reflected_P_A1_over_Ainc" => ("A1 / A_inc (reflected P)", ""),
        "reflected_SV_A1_over_Ainc" => ("A1 / A_inc (reflected SV)", ""),
        "reflected_P_A2_over_A1" => ("A2 / A1 (reflected P)", ""),
        "reflected_SV_A2_over_A1" => ("A2 / A1 (reflected SV)", ""),
        _ => return None,
    })
}

fn guess_unit(last: &str) -> &'static str {
    // a source's angle of incidence or delay law, degrees; then the SI unit of a key with
    // a dimension (what its unit strings convert to)
    if last == "angle" {
        return "deg";
    }
    if let Some(d) = crate::scenario::units::dimension_of_key(last) {
        return d.si_unit();
    }
    let l = last.to_ascii_lowercase();
    if l.contains("pressure") || l.contains("amplitude") || l.contains("modulus") {
        "Pa"
    } else if l.contains("stiffness") {
        "Pa/m"
    } else if l.contains("frequency") || l.ends_with("_hz") {
        "Hz"
    } else if l.contains("energy") {
        "J/m^2"
    } else if l == "mass" {
        "kg"
    } else if l == "length" || l.contains("gap") || l == "x" {
        "m"
    } else if l == "density" {
        "kg/m^3"
    } else if l == "damping" {
        "1/s"
    } else if l.contains("duration") || l.contains("time") {
        "s"
    } else {
        ""
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_and_units_of_keys() {
        assert_eq!(
            axis_label("interface.static_pressure", "M"),
            "static pressure p0, MPa"
        );
        assert_eq!(axis_label("incident.xi", ""), "load ratio xi");
        assert_eq!(axis_label("source.0.angle", ""), "source 0 angle, deg");
        assert_eq!(axis_label("crack.0.length", "m"), "crack 0 length, mm");
        assert_eq!(axis_label("layer.0.s_speed", ""), "layer 0 s speed, m/s");
        assert_eq!(
            axis_label("mean_contact_stiffness_0", "T"),
            "mean contact stiffness K, interface 0, TPa/m"
        );
        assert_eq!(axis_label("segment.0.mass", ""), "segment 0 mass, kg");
        assert_eq!(
            axis_label("solver.unknown_thing", ""),
            "solver unknown thing"
        );
        // 2D sweeps: a crack's extrema, a receiver's harmonics
        assert_eq!(
            axis_label("crack_max_slip_0", "n"),
            "largest slip, crack 0, nm"
        );
        assert_eq!(
            axis_label("crack_max_gap_1", ""),
            "largest opening, crack 1, m"
        );
        assert_eq!(axis_label("top_far_A2_over_A1", ""), "A2 / A1 at top_far");
    }
}
