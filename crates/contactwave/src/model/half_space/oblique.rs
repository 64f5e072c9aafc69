//! The outgoing P and SV waves of a run at oblique incidence (model.md section 14): their
//! particle velocities from the interface's face velocities, their harmonics (the band
//! analysis of section 6) and energies.

use super::methods::Derived;
use super::shear::ShearResult;
use crate::analysis::methods::{method_bands, plateau, Quantity, Records, Signal};
use crate::analysis::{AnalysisMethod, BandAmplitudes, Summary};
use crate::analytic::oblique::{inv2, PlaneWave};
use crate::scenario::{ObliqueSetup, Scenario};
use crate::solver::half_space::HalfSpaceOutput;

/// Names of the four outgoing waves, in the order of the solver's `wave_energy`.
pub const WAVES: [&str; 4] = [
    "reflected_P",
    "reflected_SV",
    "transmitted_P",
    "transmitted_SV",
];

/// Displacement histories (m, along each wave's polarisation) of a pair of waves from the
/// face displacement components `[normal, tangential]`.
fn split(pair: &[PlaneWave; 2], n: &[f64], t: &[f64]) -> [Vec<f64>; 2] {
    let m = inv2(&[
        [pair[0].polarisation[0], pair[1].polarisation[0]],
        [pair[0].polarisation[1], pair[1].polarisation[1]],
    ]);
    let f = |j: usize| -> Vec<f64> {
        n.iter()
            .zip(t)
            .map(|(a, b)| m[j][0] * a + m[j][1] * b)
            .collect()
    };
    [f(0), f(1)]
}

/// Particle displacement histories of the reflected P, SV and transmitted P, SV waves
/// (m; the transmitted ones empty for a rigid wall).
pub fn wave_displacements(
    o: &ObliqueSetup,
    normal: &HalfSpaceOutput,
    shear: &HalfSpaceOutput,
) -> [Vec<f64>; 4] {
    let g = &o.geometry;
    let [rp, rs] = split(
        &g.reflected,
        &normal.reflected_displacement,
        &shear.reflected_displacement,
    );
    let [tp, ts] = match &g.transmitted {
        Some(t) => split(
            t,
            &normal.transmitted_displacement,
            &shear.transmitted_displacement,
        ),
        None => [Vec::new(), Vec::new()],
    };
    [rp, rs, tp, ts]
}

fn ratio(a: f64, b: f64) -> f64 {
    if b > 0.0 {
        a / b
    } else {
        0.0
    }
}

/// The oblique keys of a run's summary (docs/scenario.md, outputs): angles, and for each
/// outgoing wave its harmonics over the incident particle velocity amplitude by the
/// scenario's analysis method (pulse inversion from the waves of the `derived` solve with
/// the inverted burst, linear reference from those of the linearised interface) and its
/// energy.
pub fn set_summary(
    s: &mut Summary,
    scenario: &Scenario,
    o: &ObliqueSetup,
    solved: (&HalfSpaceOutput, &ShearResult),
    derived: &Derived<ShearResult>,
) {
    let (normal, shear) = solved;
    let g = &o.geometry;
    s.set("angle", o.angle.to_degrees());
    s.set("slowness", g.slowness);
    let a_inc = o.burst.peak() / g.incident.impedance;
    let f0 = o.burst.fundamental();
    let sig = Signal {
        quantity: Quantity::Displacement,
        dt: normal.dt,
        t0: normal.t.first().copied().unwrap_or(0.0),
        f0,
        f2: None,
        plateau: plateau(|t| o.burst.stress(t), o.burst.duration(), f0),
    };
    let method = scenario.spec.analysis.method;
    let disp = wave_displacements(o, normal, &shear.interface);
    let of = |d: &Option<(HalfSpaceOutput, ShearResult)>| {
        d.as_ref()
            .map(|(n, sh)| wave_displacements(o, n, &sh.interface))
    };
    let (inverse, linear) = (of(&derived.inverse), of(&derived.linear));
    let waves: Vec<Option<&PlaneWave>> = vec![
        Some(&g.reflected[0]),
        Some(&g.reflected[1]),
        g.transmitted.as_ref().map(|t| &t[0]),
        g.transmitted.as_ref().map(|t| &t[1]),
    ];
    let incident = normal.energy.incident + shear.interface.energy.incident;
    s.set("energy_wave_incident", incident);
    for (k, name) in WAVES.iter().enumerate() {
        let Some(w) = waves[k] else { continue };
        s.set(&format!("{name}_angle"), w.angle.to_degrees());
        let records = Records {
            response: &disp[k],
            inverse: inverse.as_ref().map(|d| d[k].as_slice()),
            linear: linear.as_ref().map(|d| d[k].as_slice()),
        };
        // every method's records are solved by `analyse_keeping`; band peak if one is not
        let b: BandAmplitudes = method_bands(method, &records, &sig).unwrap_or_else(|| {
            method_bands(AnalysisMethod::BandPeak, &records, &sig).unwrap_or_default()
        });
        let mut a = b.harmonic;
        // a wave that is not there has ratios 0, not noise over noise
        if a[1] <= 1e-9 * a_inc {
            a = [0.0; 6];
        }
        for n in 1..=5 {
            s.set(&format!("{name}_A{n}_over_Ainc"), ratio(a[n], a_inc));
        }
        s.set(&format!("{name}_A2_over_A1"), ratio(a[2], a[1]));
        s.set(&format!("{name}_A3_over_A1"), ratio(a[3], a[1]));
        let e = shear.wave_energy[k];
        s.set(&format!("energy_{name}"), e);
        s.set(&format!("energy_{name}_fraction"), ratio(e, incident));
    }
    name_components(s, scenario, o, shear.a_inc);
}

/// At oblique incidence `amplitude` and `A_inc` are the incident wave's (its stress, Pa, and
/// particle velocity amplitude, m/s: what xi and every wave's ratios refer to), and the
/// keys of the interface components are named as such and normalised by that `A_inc`: the
/// normal particle velocity of the reflected field `A*_over_Ainc`, `A2_over_A1`,
/// `beta_star`, the floors → `reflected_normal_*`; its tangential one `shear_*` →
/// `reflected_tangential_*`, the transmitted field's `shear_tr_*` →
/// `transmitted_tangential_*`; the incident tractions `incident_normal_traction`,
/// `incident_tangential_traction` (Pa). `a_inc_t` is the tangential traction's
/// `shear_A_inc` (m/s).
fn name_components(s: &mut Summary, scenario: &Scenario, o: &ObliqueSetup, a_inc_t: f64) {
    let a_inc = o.burst.peak() / o.geometry.incident.impedance;
    let a_inc_n = scenario.incident.peak() / scenario.medium.impedance();
    let (to_n, to_t) = (ratio(a_inc_n, a_inc), ratio(a_inc_t, a_inc));
    s.set("amplitude", o.burst.peak());
    s.set("A_inc", a_inc);
    s.set("incident_normal_traction", scenario.incident.peak());
    s.rename("shear_amplitude", "incident_tangential_traction", 1.0);
    s.remove("shear_A_inc");
    s.remove("shear_frequency");
    let mut normal: Vec<String> = ["Asub", "Af2", "Asum", "Adiff"]
        .iter()
        .map(|a| format!("{a}_over_Ainc"))
        .collect();
    for n in 1..=5 {
        normal.push(format!("A{n}_over_Ainc"));
        normal.push(format!("A{n}_floor_over_Ainc"));
    }
    for k in &normal {
        s.rename(k, &format!("reflected_normal_{k}"), to_n);
    }
    for k in ["A2_over_A1", "beta_star"] {
        s.rename(k, &format!("reflected_normal_{k}"), 1.0);
    }
    for (from, to) in [
        ("shear_", "reflected_tangential_"),
        ("shear_tr_", "transmitted_tangential_"),
    ] {
        for n in 1..=5 {
            let k = format!("A{n}_over_Ainc");
            s.rename(&format!("{from}{k}"), &format!("{to}{k}"), to_t);
        }
        for k in ["A2_over_A1", "A3_over_A1", "A3_over_A1_cubed"] {
            s.rename(&format!("{from}{k}"), &format!("{to}{k}"), 1.0);
        }
    }
}

/// The band amplitudes (m/s) of the incident wave's particle velocity along its
/// polarisation, from the normal and tangential face displacements of the incident wave.
pub fn incident_wave_bands(
    o: &ObliqueSetup,
    normal: &HalfSpaceOutput,
    shear: &HalfSpaceOutput,
) -> BandAmplitudes {
    let pol = o.geometry.incident.polarisation;
    let along: Vec<f64> = normal
        .incident_displacement
        .iter()
        .zip(&shear.incident_displacement)
        .map(|(n, t)| pol[0] * n + pol[1] * t)
        .collect();
    crate::analysis::velocity_bands(&along, normal.dt, o.burst.fundamental(), None)
}

/// The incident wave's own harmonics at oblique incidence, `incident_A1_over_Ainc` ...
/// `incident_A5_over_Ainc` over `A_inc` (`run` only), from [`incident_wave_bands`].
pub fn set_incident(s: &mut Summary, o: &ObliqueSetup, bands: &BandAmplitudes) {
    let a_inc = o.burst.peak() / o.geometry.incident.impedance;
    for n in 1..=5 {
        s.set(
            &format!("incident_A{n}_over_Ainc"),
            ratio(bands.harmonic[n], a_inc),
        );
    }
}

/// Measured transfer coefficients at frequency `f` (Hz) of a run: the Fourier sums at `f`
/// of the reflected P, SV and transmitted P, SV particle velocities (from the interface
/// tractions at the grid points) over the incident wave's, `[R_P, R_SV, T_P, T_SV]`. For
/// a linear interface and a run that ends at rest this is the interface's transfer
/// function at `f`, to the integration error plus the aliasing of the burst's spectrum
/// (the closed forms of `crate::analytic::oblique::coefficients`).
pub fn transfer_at(
    out: &crate::solver::coupled::CoupledOutput,
    g: &crate::analytic::oblique::Geometry,
    burst: &dyn crate::excitation::Excitation,
    f: f64,
) -> [rustfft::num_complex::Complex64; 4] {
    use crate::analytic::oblique::Geometry;
    use rustfft::num_complex::Complex64;
    let w = 2.0 * std::f64::consts::PI * f;
    let rw = Geometry::traction_to_waves(&g.reflected);
    let tw = g.transmitted.map(|t| Geometry::traction_to_waves(&t));
    let mut acc = [Complex64::new(0.0, 0.0); 5];
    for (k, &t) in out.normal.t.iter().enumerate() {
        let e = Complex64::from_polar(1.0, -w * t);
        acc[4] += e * (-burst.stress(t) / g.incident.impedance);
        let r = [
            out.normal.reflected_stress[k],
            out.shear.reflected_stress[k],
        ];
        let s = [
            out.normal.transmitted_stress[k],
            out.shear.transmitted_stress[k],
        ];
        for j in 0..2 {
            acc[j] += e * (rw[j][0] * r[0] + rw[j][1] * r[1]);
            if let Some(m) = &tw {
                acc[2 + j] += e * (m[j][0] * s[0] + m[j][1] * s[1]);
            }
        }
    }
    [
        acc[0] / acc[4],
        acc[1] / acc[4],
        acc[2] / acc[4],
        acc[3] / acc[4],
    ]
}
