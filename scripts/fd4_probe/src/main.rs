//! The least work a bulk step can do, as a ceiling for the 2D solver's node rate: a fused
//! fourth-order staggered-grid P-SV velocity-stress step (Levander 1988), double precision,
//! uniform material, no crack, no absorbing layer, no source, no receiver: five fields read
//! and written once a step (80 bytes a node-update), about 50 flops. Not contactwave's
//! scheme (spectral elements, model.md section 15): a probe of what this machine allows.
//! Arguments: nx nz steps [fused|twopass]; prints node-updates/s (one node-update = one
//! grid node advanced by one step in all five fields).
use rayon::prelude::*;
const C1: f64 = 9.0 / 8.0;
const C2: f64 = -1.0 / 24.0;

struct F {
    vx: Vec<f64>,
    vz: Vec<f64>,
    sxx: Vec<f64>,
    szz: Vec<f64>,
    sxz: Vec<f64>,
}
#[derive(Clone, Copy)]
struct P(*mut f64);
unsafe impl Send for P {}
unsafe impl Sync for P {}

#[inline(always)]
unsafe fn vel_row(p: &[P; 5], nx: usize, j: usize, b: f64) {
    let (vx, vz, sxx, szz, sxz) = (p[0].0, p[1].0, p[2].0, p[3].0, p[4].0);
    let r = j * nx;
    for i in 2..nx - 2 {
        let k = r + i;
        let dsxx = C1 * (*sxx.add(k) - *sxx.add(k - 1)) + C2 * (*sxx.add(k + 1) - *sxx.add(k - 2));
        let dsxz =
            C1 * (*sxz.add(k) - *sxz.add(k - nx)) + C2 * (*sxz.add(k + nx) - *sxz.add(k - 2 * nx));
        *vx.add(k) += b * (dsxx + dsxz);
        let dsxz2 = C1 * (*sxz.add(k + 1) - *sxz.add(k)) + C2 * (*sxz.add(k + 2) - *sxz.add(k - 1));
        let dszz =
            C1 * (*szz.add(k + nx) - *szz.add(k)) + C2 * (*szz.add(k + 2 * nx) - *szz.add(k - nx));
        *vz.add(k) += b * (dsxz2 + dszz);
    }
}
#[inline(always)]
unsafe fn str_row(p: &[P; 5], nx: usize, j: usize, l2m: f64, l: f64, m: f64) {
    let (vx, vz, sxx, szz, sxz) = (p[0].0, p[1].0, p[2].0, p[3].0, p[4].0);
    let r = j * nx;
    for i in 2..nx - 2 {
        let k = r + i;
        let dvxdx = C1 * (*vx.add(k + 1) - *vx.add(k)) + C2 * (*vx.add(k + 2) - *vx.add(k - 1));
        let dvzdz =
            C1 * (*vz.add(k) - *vz.add(k - nx)) + C2 * (*vz.add(k + nx) - *vz.add(k - 2 * nx));
        *sxx.add(k) += l2m * dvxdx + l * dvzdz;
        *szz.add(k) += l * dvxdx + l2m * dvzdz;
        let dvxdz =
            C1 * (*vx.add(k + nx) - *vx.add(k)) + C2 * (*vx.add(k + 2 * nx) - *vx.add(k - nx));
        let dvzdx = C1 * (*vz.add(k) - *vz.add(k - 1)) + C2 * (*vz.add(k + 1) - *vz.add(k - 2));
        *sxz.add(k) += m * (dvxdz + dvzdx);
    }
}

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let nx: usize = a.get(1).map(|s| s.parse().unwrap()).unwrap_or(2300);
    let nz: usize = a.get(2).map(|s| s.parse().unwrap()).unwrap_or(576);
    let steps: usize = a.get(3).map(|s| s.parse().unwrap()).unwrap_or(200);
    let fused: bool = a.get(4).map(|s| s == "fused").unwrap_or(true);
    let n = nx * nz;
    let mut f = F {
        vx: vec![0.0; n],
        vz: vec![0.0; n],
        sxx: vec![0.0; n],
        szz: vec![0.0; n],
        sxz: vec![0.0; n],
    };
    f.sxx[(nz / 2) * nx + nx / 2] = 1.0;
    let (b, l2m, l, m) = (0.3, 0.4, 0.1, 0.15);
    let threads = rayon::current_num_threads();
    let band = (nz - 4 + threads - 1) / threads;
    let p = [
        P(f.vx.as_mut_ptr()),
        P(f.vz.as_mut_ptr()),
        P(f.sxx.as_mut_ptr()),
        P(f.szz.as_mut_ptr()),
        P(f.sxz.as_mut_ptr()),
    ];
    let run = |steps: usize| {
        for _ in 0..steps {
            if fused {
                (0..threads).into_par_iter().for_each(|t| unsafe {
                    let j0 = 2 + t * band;
                    let j1 = (j0 + band).min(nz - 2);
                    let first = t > 0;
                    let last = t + 1 == threads;
                    for j in j0..j1 {
                        vel_row(&p, nx, j, b);
                        if j >= j0 + 2 {
                            let k = j - 2;
                            if !(first && k < j0 + 2) {
                                str_row(&p, nx, k, l2m, l, m);
                            }
                        }
                    }
                    if last {
                        for k in j1.saturating_sub(2).max(j0)..j1 {
                            str_row(&p, nx, k, l2m, l, m);
                        }
                    }
                });
                // seams: the deferred stress rows around each band boundary
                (1..threads).into_par_iter().for_each(|t| unsafe {
                    let s = 2 + t * band;
                    for k in s - 2..s + 2 {
                        if k >= 2 && k < nz - 2 {
                            str_row(&p, nx, k, l2m, l, m);
                        }
                    }
                });
            } else {
                (2..nz - 2)
                    .into_par_iter()
                    .for_each(|j| unsafe { vel_row(&p, nx, j, b) });
                (2..nz - 2)
                    .into_par_iter()
                    .for_each(|j| unsafe { str_row(&p, nx, j, l2m, l, m) });
            }
        }
    };
    run(10);
    let t0 = std::time::Instant::now();
    run(steps);
    let el = t0.elapsed().as_secs_f64();
    let s: f64 = f.vx.iter().map(|x| x.abs()).sum();
    println!(
        "grid {nx}x{nz} threads {threads} fused {fused}: {:.3e} node-updates/s (check {s:.3e})",
        (n * steps) as f64 / el
    );
}
