//! The GPU backend of the 2D time loop (feature `gpu`; docs/performance.md section 2a):
//! the displacements, velocities and forces live on an NVIDIA GPU, whose kernels
//! (`gpu.cu`, compiled at run time by NVRTC; the CUDA driver and NVRTC are loaded at run
//! time, so the build needs no CUDA) take the elements' forces through the element-to-node
//! map (the elements coloured so that each colour's scatter is a plain subtraction), the
//! node-wise leapfrog, the absorbing layers, the sources' forces and work (point loads,
//! transducers, plane-wave injection) and the receivers' samples (velocities and
//! stresses). The cracks
//! stay on the host: each step their split nodes' predicted motion comes down, the one
//! per-point contact update of `law/` ([`CrackNodes::update`]) runs on it, and the kicked
//! motion goes back up, a few hundred values each way.
//!
//! The same step as the CPU's (eq. 15.2) in another order of summation: the results agree
//! with the CPU's to round-off (the test `gpu_matches_the_cpu`), and are the same bits on
//! every run (fixed colours, fixed orders, no atomics).

use super::crack::CrackNodes;
use super::stepping::Records;
use super::{Plan, Solid2dOutput};
use crate::error::{Error, Result};
use crate::law::{NormalPart, TangentialPart};
use crate::solver::stepping::{self, Recorder, Schedule, Scheme};
use cudarc::driver::{
    CudaContext, CudaFunction, CudaSlice, CudaStream, LaunchConfig, PushKernelArg,
};
use cudarc::nvrtc::{compile_ptx_with_opts, CompileOptions};
use std::sync::Arc;

/// The kernels' text.
const SOURCE: &str = include_str!("gpu.cu");
/// Elements per thread block of the force kernels.
const ELEMENTS_PER_BLOCK: usize = 4;
/// Threads per block of the node-wise kernels.
const THREADS: u32 = 256;
/// Steps between two interruption checks (as the CPU loop).
const CHECK_EVERY: usize = 64;

fn device(what: impl std::fmt::Display) -> Error {
    Error::Device {
        message: what.to_string().replace(['\n', '\r'], " "),
    }
}

/// `Result` of a CUDA call as this crate's, naming the call.
trait OrDevice<T> {
    fn or_device(self, call: &str) -> Result<T>;
}

impl<T, E: std::fmt::Display> OrDevice<T> for std::result::Result<T, E> {
    fn or_device(self, call: &str) -> Result<T> {
        self.map_err(|e| device(format!("{call}: {e}")))
    }
}

/// The CUDA driver and NVRTC, loaded: an error (no panic) where either is missing.
fn libraries() -> Result<()> {
    // SAFETY: loading a shared library by name; no CUDA call is made
    if !unsafe { cudarc::driver::sys::is_culib_present() } {
        return Err(device(
            "no CUDA driver (libcuda.so) on this machine: use `model.backend = \"cpu\"`",
        ));
    }
    // SAFETY: as above
    if !unsafe { cudarc::nvrtc::sys::is_culib_present() } {
        return Err(device(
            "no NVRTC library (libnvrtc.so): add CUDA's lib64 folder to LD_LIBRARY_PATH",
        ));
    }
    Ok(())
}

/// Colour the elements (`m2` nodes each in `conn`) greedily, in their order, so that no
/// two elements of a colour share a node: each colour's elements, increasing (four
/// colours on the structured mesh, a few more where periodic sides join columns).
fn colours(conn: &[u32], m2: usize, n_nodes: usize) -> Result<Vec<Vec<u32>>> {
    let mut used = vec![0u8; n_nodes];
    let mut out: Vec<Vec<u32>> = Vec::new();
    for (e, nodes) in conn.chunks_exact(m2).enumerate() {
        let taken = nodes.iter().fold(0u8, |a, &g| a | used[g as usize]);
        let c = taken.trailing_ones() as usize;
        if c >= 8 {
            return Err(device("the mesh needs more than eight element colours"));
        }
        for &g in nodes {
            used[g as usize] |= 1 << c;
        }
        if out.len() <= c {
            out.resize_with(c + 1, Vec::new);
        }
        out[c].push(e as u32);
    }
    Ok(out)
}

/// The kernels, loaded once per run.
struct Kernels {
    forces: CudaFunction,
    advance: CudaFunction,
    add_loads: CudaFunction,
    load_work: CudaFunction,
    record: CudaFunction,
    gather: CudaFunction,
    scatter: CudaFunction,
    finite: CudaFunction,
    band_parts: CudaFunction,
    band_assemble: CudaFunction,
    band_nodes: CudaFunction,
    band_stresses: CudaFunction,
    inject_samples: CudaFunction,
    inject_forces: CudaFunction,
    record_stress: CudaFunction,
}

/// One plane-wave source on the device ([`super::plane_wave::Injection`]'s tables and
/// buffers): its sample nodes' delays and scales, the table of the signal's integral, the
/// couplings grouped by target entry, and each target's force and work.
struct InjectionGpu {
    samples: i32,
    delay: CudaSlice<f64>,
    scale: CudaSlice<f64>,
    u_inc: CudaSlice<f64>,
    /// The table `G(k step)` and its derivative `s(k step)`, `len` entries.
    g: CudaSlice<f64>,
    s: CudaSlice<f64>,
    step: f64,
    len: u64,
    /// Per target entry of `f` and `v`: its couplings `first[i]..first[i + 1]` (sample,
    /// weight), in the CPU's order.
    targets: i32,
    target: CudaSlice<u32>,
    first: CudaSlice<u32>,
    sample: CudaSlice<u32>,
    weight: CudaSlice<f64>,
    /// Each target's force of the step, its velocity of the previous half level and its
    /// work so far (J/m; summed on the host at the end).
    force: CudaSlice<f64>,
    old: CudaSlice<f64>,
    work: CudaSlice<f64>,
}

/// The stress receivers on the device (probe.rs's taps, flat): per receiver its row's
/// then its column's `M` nodes and weights, its Lame constants, and its stresses of the
/// last level.
struct ProbesGpu {
    probes: i32,
    node: CudaSlice<u32>,
    weight: CudaSlice<f64>,
    lame: CudaSlice<f64>,
    last: CudaSlice<f64>,
    samples: CudaSlice<f64>,
}

/// The absorbing layers on the device ([`super::pml::Band`]'s tables and fields; see its
/// kernels in `gpu.cu`).
struct BandGpu {
    /// Elements and points.
    elements: i32,
    points: usize,
    par: CudaSlice<f64>,
    conn: CudaSlice<u32>,
    damp: CudaSlice<f64>,
    stress: CudaSlice<f64>,
    part: CudaSlice<f64>,
    /// Per band node: its points (`point[first[i]..first[i + 1]]`), global node, damping
    /// and (inner nodes) the band's share of its mass.
    first: CudaSlice<u32>,
    point: CudaSlice<u32>,
    node: CudaSlice<u32>,
    node_damp: CudaSlice<f64>,
    mass: CudaSlice<f64>,
    fx: CudaSlice<f64>,
    fz: CudaSlice<f64>,
    vx: CudaSlice<f64>,
    vz: CudaSlice<f64>,
    old: CudaSlice<f64>,
    /// Each inner node's flux into the band so far, J/m.
    work: CudaSlice<f64>,
    nodes: i32,
    inner: i32,
}

/// A 2D plan running on the GPU: the fields and tables on the device, the cracks (their
/// split nodes packed, faces renumbered into the packed arrays) on the host.
struct GpuRun<'p, L> {
    plan: &'p Plan<L>,
    stream: Arc<CudaStream>,
    k: Kernels,
    /// Displacements, velocities, forces (`components` per node), inverse masses.
    u: CudaSlice<f64>,
    v: CudaSlice<f64>,
    f: CudaSlice<f64>,
    inv_mass: CudaSlice<f64>,
    conn: CudaSlice<u32>,
    /// Per element: `2/hx, 2/hz, hx/2, hz/2, lambda + 2 mu, lambda, mu`.
    par: CudaSlice<f64>,
    derivative: CudaSlice<f64>,
    weights: CudaSlice<f64>,
    /// Each colour's elements and their count.
    colours: Vec<(CudaSlice<u32>, i32)>,
    /// The loads (index into `f` and `v`; ordered by node, a stable sort), the nodes
    /// they load with each one's first load, this level's values, each load's velocity of
    /// the previous half level and its work so far.
    load_index: CudaSlice<u32>,
    load_nodes: CudaSlice<u32>,
    load_first: CudaSlice<u32>,
    n_load_nodes: i32,
    load_order: Vec<usize>,
    load_value: CudaSlice<f64>,
    load_old: CudaSlice<f64>,
    input: CudaSlice<f64>,
    load_host: Vec<f64>,
    /// The receivers' entries of `v`, their offsets in `samples`, and the samples
    /// (`[receiver][component][step]`).
    record_index: CudaSlice<u32>,
    record_slot: CudaSlice<u64>,
    samples: CudaSlice<f64>,
    n_record: i32,
    /// The split nodes' entries of `u` and `v`, their packed values (u then v) on the
    /// device and the host, and the cracks renumbered into them.
    split_index: CudaSlice<u32>,
    split_buf: CudaSlice<f64>,
    split_host: Vec<f64>,
    cracks: Vec<CrackNodes<L>>,
    flag: CudaSlice<i32>,
    /// The absorbing layers, if any.
    band: Option<BandGpu>,
    /// The plane-wave sources.
    injections: Vec<InjectionGpu>,
    /// The stress receivers, if any.
    probes: Option<ProbesGpu>,
    /// Steps taken.
    step: usize,
}

/// Launch `$f` with `$cfg` and the arguments (a macro: the builder borrows them).
macro_rules! launch {
    ($s:expr, $f:expr, $cfg:expr, $name:literal; $($arg:expr),* $(,)?) => {{
        let mut b = $s.launch_builder(&$f);
        $(b.arg($arg);)*
        // SAFETY: the arguments match the kernel's parameters in `gpu.cu` in number, type
        // and order, and every index the kernel reads is inside its arrays (built here)
        unsafe { b.launch($cfg) }.or_device($name)?;
    }};
}

/// Per element: `2/hx, 2/hz, hx/2, hz/2, lambda + 2 mu, lambda, mu` (the kernels' `par`).
fn params(elements: &[super::kernel::ElementData]) -> Vec<f64> {
    elements
        .iter()
        .flat_map(|el| {
            [
                2.0 / el.hx,
                2.0 / el.hz,
                0.5 * el.hx,
                0.5 * el.hz,
                el.lambda + 2.0 * el.mu,
                el.lambda,
                el.mu,
            ]
        })
        .collect()
}

fn grid(n: usize) -> LaunchConfig {
    LaunchConfig {
        grid_dim: ((n as u32).div_ceil(THREADS).max(1), 1, 1),
        block_dim: (THREADS, 1, 1),
        shared_mem_bytes: 0,
    }
}

impl<'p, L: NormalPart + TangentialPart + Clone> GpuRun<'p, L> {
    fn new(plan: &'p Plan<L>) -> Result<Self> {
        libraries()?;
        let ctx = CudaContext::new(0).or_device("no GPU (cuInit/cuDeviceGet)")?;
        let stream = ctx.default_stream();
        let s = &plan.stiffness;
        let m = s.order + 1;
        let text = format!("#define M {m}\n#define E {ELEMENTS_PER_BLOCK}\n{SOURCE}");
        let ptx = compile_ptx_with_opts(
            text,
            CompileOptions {
                // each product and sum rounded alone, as on the CPU
                fmad: Some(false),
                ..Default::default()
            },
        )
        .or_device("compiling the kernels (NVRTC)")?;
        let module = ctx.load_module(ptx).or_device("loading the kernels")?;
        let f = |name: &str| module.load_function(name).or_device(name);
        let k = Kernels {
            forces: f(if s.antiplane {
                "sh_forces"
            } else {
                "psv_forces"
            })?,
            advance: f("advance")?,
            add_loads: f("add_loads")?,
            load_work: f("load_work")?,
            record: f("record")?,
            gather: f("gather")?,
            scatter: f("scatter")?,
            finite: f("finite")?,
            band_parts: f("band_parts")?,
            band_assemble: f("band_assemble")?,
            band_nodes: f("band_nodes")?,
            band_stresses: f("band_stresses")?,
            inject_samples: f("inject_samples")?,
            inject_forces: f("inject_forces")?,
            record_stress: f("record_stress")?,
        };
        let c = plan.components;
        let n = plan.mesh.n_nodes;
        // (an empty table as one unused entry: CUDA allocations are never empty)
        let up = |x: &[f64]| {
            stream
                .clone_htod(if x.is_empty() { &[0.0][..] } else { x })
                .or_device("copy to the GPU")
        };
        let up32 = |x: &[u32]| {
            stream
                .clone_htod(if x.is_empty() { &[0][..] } else { x })
                .or_device("copy to the GPU")
        };
        let zeros = |len: usize| {
            stream
                .alloc_zeros::<f64>(len.max(1))
                .or_device("GPU memory")
        };
        let par = params(&s.elements);
        let colours = colours(&s.conn, m * m, n)?
            .into_iter()
            .map(|list| Ok((up32(&list)?, list.len() as i32)))
            .collect::<Result<Vec<_>>>()?;
        // the loads ordered by their entry (stable: a node's loads keep their order), and
        // each loaded entry's first load
        let mut load_order: Vec<usize> = (0..plan.loads.len()).collect();
        load_order.sort_by_key(|&l| plan.loads[l].index);
        let load_index: Vec<u32> = load_order
            .iter()
            .map(|&l| plan.loads[l].index as u32)
            .collect();
        let (mut load_nodes, mut load_first) = (Vec::new(), Vec::new());
        for (i, &g) in load_index.iter().enumerate() {
            if load_nodes.last() != Some(&g) {
                load_nodes.push(g);
                load_first.push(i as u32);
            }
        }
        load_first.push(load_index.len() as u32);
        // the receivers' entries, `[receiver][component]`
        let n_t = plan.steps;
        let mut record_index = Vec::new();
        let mut record_slot = Vec::new();
        for (r, &g) in plan.receiver_nodes.iter().enumerate() {
            for cc in 0..c {
                record_index.push((c * g + cc) as u32);
                record_slot.push(((r * c + cc) * n_t) as u64);
            }
        }
        // the split nodes, packed in the order of the cracks and their points
        let mut split_index = Vec::new();
        let mut cracks = plan.cracks.clone();
        for cr in &mut cracks {
            for face in &mut cr.faces {
                let mut pack = |g: usize| {
                    let j = split_index.len() / c;
                    split_index.extend((0..c).map(|cc| (c * g + cc) as u32));
                    j
                };
                *face = (pack(face.0), pack(face.1));
            }
        }
        let n_split = split_index.len();
        let b = &plan.band;
        let band = if b.is_empty() {
            None
        } else {
            // each band node's points, increasing (the CPU's assembly order)
            let nb = b.nodes.len();
            let mut first = vec![0u32; nb + 1];
            for &i in &b.local {
                first[i as usize + 1] += 1;
            }
            for i in 0..nb {
                first[i + 1] += first[i];
            }
            let mut fill = first.clone();
            let mut point = vec![0u32; b.local.len()];
            for (p, &i) in b.local.iter().enumerate() {
                point[fill[i as usize] as usize] = p as u32;
                fill[i as usize] += 1;
            }
            let flat = |x: &[[f64; 2]]| x.iter().flatten().copied().collect::<Vec<f64>>();
            let per_point = if b.antiplane { 2 } else { 6 };
            let points = b.conn.len();
            Some(BandGpu {
                elements: b.data.len() as i32,
                points,
                par: up(&params(&b.data))?,
                conn: up32(&b.conn)?,
                damp: up(&flat(&b.damp))?,
                stress: zeros(points * per_point)?,
                part: zeros(points * 2 * c)?,
                first: up32(&first)?,
                point: up32(&point)?,
                node: up32(&b.nodes)?,
                node_damp: up(&flat(&b.node_damp))?,
                mass: up(&b.band_mass)?,
                fx: zeros(nb * c)?,
                fz: zeros(nb * c)?,
                vx: zeros(nb * c)?,
                vz: zeros(nb * c)?,
                old: zeros(b.n_inner * c)?,
                work: zeros(b.n_inner)?,
                nodes: nb as i32,
                inner: b.n_inner as i32,
            })
        };
        let injections = plan
            .plane_waves
            .iter()
            .map(|pw| {
                // the couplings are sorted by target: each target's run of them
                let count = pw.targets.len();
                let mut first = vec![0u32; count + 1];
                for &(t, _, _) in &pw.pairs {
                    first[t as usize + 1] += 1;
                }
                for i in 0..count {
                    first[i + 1] += first[i];
                }
                let target: Vec<u32> = pw.targets.iter().map(|&d| d as u32).collect();
                let sample: Vec<u32> = pw.pairs.iter().map(|p| p.1).collect();
                let weight: Vec<f64> = pw.pairs.iter().map(|p| p.2).collect();
                Ok(InjectionGpu {
                    samples: pw.delay.len() as i32,
                    delay: up(&pw.delay)?,
                    scale: up(&pw.scale)?,
                    u_inc: zeros(pw.delay.len())?,
                    g: up(&pw.integral.g)?,
                    s: up(&pw.integral.s)?,
                    step: pw.integral.step,
                    len: pw.integral.g.len() as u64,
                    targets: count as i32,
                    target: up32(&target)?,
                    first: up32(&first)?,
                    sample: up32(&sample)?,
                    weight: up(&weight)?,
                    force: zeros(count)?,
                    old: zeros(count)?,
                    work: zeros(count)?,
                })
            })
            .collect::<Result<Vec<_>>>()?;
        let probes = if plan.stress_probes.is_empty() {
            None
        } else {
            let sp = &plan.stress_probes;
            let taps = sp.iter().flat_map(|p| p.row.iter().chain(&p.column));
            let node: Vec<u32> = taps.clone().map(|&(g, _)| g as u32).collect();
            let weight: Vec<f64> = taps.map(|&(_, w)| w).collect();
            if node.len() != 2 * m * sp.len() {
                return Err(device("a stress receiver's taps are not one element line"));
            }
            let lame: Vec<f64> = sp.iter().flat_map(|p| [p.lame.0, p.lame.1]).collect();
            let sc = if c == 1 { 2 } else { 3 };
            Some(ProbesGpu {
                probes: sp.len() as i32,
                node: up32(&node)?,
                weight: up(&weight)?,
                lame: up(&lame)?,
                last: zeros(sp.len() * sc)?,
                samples: zeros(sp.len() * sc * n_t)?,
            })
        };
        Ok(GpuRun {
            band,
            injections,
            probes,
            u: zeros(c * n)?,
            v: zeros(c * n)?,
            f: zeros(c * n)?,
            inv_mass: up(&plan.inv_mass)?,
            conn: up32(&s.conn)?,
            par: up(&par)?,
            derivative: up(&s.derivative)?,
            weights: up(&s.weights)?,
            colours,
            load_index: up32(&load_index)?,
            n_load_nodes: load_nodes.len() as i32,
            load_nodes: up32(&load_nodes)?,
            load_first: up32(&load_first)?,
            load_order,
            load_value: zeros(load_index.len())?,
            load_old: zeros(load_index.len())?,
            input: zeros(load_index.len())?,
            load_host: vec![0.0; load_index.len()],
            n_record: record_index.len() as i32,
            record_index: up32(&record_index)?,
            record_slot: stream
                .clone_htod(if record_slot.is_empty() {
                    &[0][..]
                } else {
                    &record_slot
                })
                .or_device("copy to the GPU")?,
            samples: zeros(record_index.len() * n_t)?,
            split_index: up32(&split_index)?,
            split_buf: zeros(2 * n_split)?,
            split_host: vec![0.0; 2 * n_split],
            cracks,
            flag: stream.alloc_zeros::<i32>(1).or_device("GPU memory")?,
            step: 0,
            k,
            stream,
            plan,
        })
    }

    /// The crack update on the host: the split nodes' predicted motion down, the law,
    /// the kicked motion up.
    fn cracks(&mut self, dt: f64, t1: f64) -> Result<()> {
        let n = self.split_host.len() / 2;
        if n == 0 {
            return Ok(());
        }
        let ni = n as i32;
        launch!(self.stream, self.k.gather, grid(n), "gather";
            &self.u, &self.v, &self.split_index, &mut self.split_buf, &ni);
        self.stream
            .memcpy_dtoh(&self.split_buf, &mut self.split_host)
            .or_device("copy from the GPU")?;
        let antiplane = self.plan.components == 1;
        let (u, v) = self.split_host.split_at_mut(n);
        for cr in &mut self.cracks {
            cr.update(u, v, dt, t1, antiplane)?;
        }
        self.stream
            .memcpy_htod(&self.split_host, &mut self.split_buf)
            .or_device("copy to the GPU")?;
        launch!(self.stream, self.k.scatter, grid(n), "scatter";
            &mut self.u, &mut self.v, &self.split_index, &self.split_buf, &ni);
        Ok(())
    }

    fn download(&self, x: &CudaSlice<f64>, out: &mut [f64]) -> Result<()> {
        self.stream
            .memcpy_dtoh(x, out)
            .or_device("copy from the GPU")
    }
}

impl<L: NormalPart + TangentialPart + Clone> Scheme for GpuRun<'_, L> {
    fn step(&mut self, t: f64, t1: f64) -> Result<()> {
        let p = self.plan;
        let (c, dt) = (p.components, p.dt);
        let n_loads = p.loads.len();
        if n_loads > 0 {
            for (x, &l) in self.load_host.iter_mut().zip(&self.load_order) {
                *x = p.load_value(&p.loads[l], t);
            }
            self.stream
                .memcpy_htod(&self.load_host, &mut self.load_value)
                .or_device("copy to the GPU")?;
            let nn = self.n_load_nodes;
            launch!(self.stream, self.k.add_loads, grid(nn as usize), "add_loads";
                &mut self.f, &self.load_nodes, &self.load_first, &self.load_value, &nn);
        }
        for pw in &mut self.injections {
            launch!(self.stream, self.k.inject_samples, grid(pw.samples as usize), "inject_samples";
                &mut pw.u_inc, &pw.delay, &pw.scale, &pw.g, &pw.s, &pw.step, &pw.len, &t,
                &pw.samples);
            launch!(self.stream, self.k.inject_forces, grid(pw.targets as usize), "inject_forces";
                &mut self.f, &pw.target, &pw.first, &pw.sample, &pw.weight, &pw.u_inc,
                &mut pw.force, &pw.targets);
        }
        let antiplane = i32::from(c == 1);
        let ci = c as i32;
        if let Some(b) = &mut self.band {
            launch!(self.stream, self.k.band_parts, grid(b.points), "band_parts";
                &b.stress, &mut b.part, &b.par, &self.derivative, &self.weights, &antiplane,
                &b.elements);
            launch!(self.stream, self.k.band_assemble, grid(b.nodes as usize), "band_assemble";
                &b.part, &b.first, &b.point, &b.node, &mut b.fx, &mut b.fz, &mut self.f,
                &self.v, &mut b.old, &ci, &b.inner, &b.nodes);
        }
        let m = (p.stiffness.order + 1) as u32;
        for (list, count) in &self.colours {
            let cfg = LaunchConfig {
                grid_dim: ((*count as u32).div_ceil(ELEMENTS_PER_BLOCK as u32), 1, 1),
                block_dim: (m, m, ELEMENTS_PER_BLOCK as u32),
                shared_mem_bytes: 0,
            };
            launch!(self.stream, self.k.forces, cfg, "forces";
                &self.u, &mut self.f, &self.conn, &self.par, &self.derivative, &self.weights,
                list, count);
        }
        let nodes = p.mesh.n_nodes;
        let ni = nodes as i32;
        launch!(self.stream, self.k.advance, grid(nodes), "advance";
            &mut self.u, &mut self.v, &mut self.f, &self.inv_mass, &dt, &ci, &ni);
        if let Some(b) = &mut self.band {
            launch!(self.stream, self.k.band_nodes, grid(b.nodes as usize), "band_nodes";
                &mut self.u, &mut self.v, &self.inv_mass, &b.node, &b.node_damp, &b.mass,
                &b.fx, &b.fz, &mut b.vx, &mut b.vz, &b.old, &mut b.work, &dt, &ci, &b.inner,
                &b.nodes);
            launch!(self.stream, self.k.band_stresses, grid(b.points), "band_stresses";
                &mut b.stress, &self.v, &b.conn, &b.damp, &b.par, &self.derivative, &dt,
                &antiplane, &b.elements);
        }
        self.cracks(dt, t1)?;
        if n_loads > 0 {
            let nl = n_loads as i32;
            launch!(self.stream, self.k.load_work, grid(n_loads), "load_work";
                &self.v, &self.load_index, &self.load_value, &mut self.load_old,
                &mut self.input, &dt, &nl);
        }
        for pw in &mut self.injections {
            // (a plane wave's work: the loads' kernel on its targets' forces)
            launch!(self.stream, self.k.load_work, grid(pw.targets as usize), "load_work";
                &self.v, &pw.target, &pw.force, &mut pw.old, &mut pw.work, &dt, &pw.targets);
        }
        if let Some(sp) = &mut self.probes {
            let (n_t, step) = (p.steps as u64, self.step as u64);
            launch!(self.stream, self.k.record_stress, grid(sp.probes as usize), "record_stress";
                &self.u, &sp.node, &sp.weight, &sp.lame, &mut sp.last, &mut sp.samples, &n_t,
                &step, &ci, &sp.probes);
        }
        if self.n_record > 0 {
            let step = self.step as u64;
            launch!(self.stream, self.k.record, grid(self.n_record as usize), "record";
                &self.v, &self.record_index, &self.record_slot, &mut self.samples, &step,
                &self.n_record);
        }
        self.step += 1;
        Ok(())
    }

    fn check_finite(&self, t1: f64) -> Result<()> {
        // (the flag is only ever set: the first non-finite value ends the run)
        for x in [&self.u, &self.v] {
            let n = x.len();
            let nn = n as u64;
            launch!(self.stream, self.k.finite, grid(n), "finite"; x, &self.flag, &nn);
        }
        let mut flag = [0i32];
        self.stream
            .memcpy_dtoh(&self.flag, &mut flag)
            .or_device("copy from the GPU")?;
        if flag[0] == 0 {
            Ok(())
        } else {
            Err(Error::numerical(
                t1,
                "2D solver (GPU): non-finite displacement or velocity",
                format!("time step {:e} s", self.plan.dt),
            ))
        }
    }

    fn advance(&mut self) {}
}

/// What the GPU run keeps besides the device's samples: the CPU's records (times,
/// snapshots, cracks' fields) and a host copy of the velocities for the snapshots.
struct GpuRecords {
    base: Records,
    host: Vec<f64>,
    error: Option<Error>,
}

impl<L: NormalPart + TangentialPart + Clone> Recorder<GpuRun<'_, L>> for GpuRecords {
    fn record(&mut self, t: f64, s: &GpuRun<'_, L>) {
        let dt = s.plan.dt;
        let Some(n) = self.base.next_sample(dt) else {
            return;
        };
        if self.base.snapshots.wants(n) {
            match s.download(&s.v, &mut self.host) {
                Ok(()) => self
                    .base
                    .snapshots
                    .take(n, n as f64 * dt + 0.5 * dt, &self.host),
                Err(e) => {
                    self.error.get_or_insert(e);
                }
            }
        }
        self.base.crack_fields(t, n, &s.cracks);
    }
}

impl<L: NormalPart + TangentialPart + Clone> Plan<L> {
    /// [`Plan::run_with`] on the GPU (see the module).
    pub(super) fn run_gpu(
        &self,
        progress: Option<&(dyn Fn(usize, usize) + Send + Sync)>,
    ) -> Result<Solid2dOutput> {
        let len = self.components * self.mesh.n_nodes;
        let mut recorder = GpuRecords {
            base: Records::new(self),
            host: if self.snapshot_steps.is_empty() {
                Vec::new()
            } else {
                vec![0.0; len]
            },
            error: None,
        };
        let schedule = Schedule {
            t0: 0.0,
            dt: self.dt,
            steps: self.steps,
            record_every: 1,
            check_every: CHECK_EVERY,
            progress,
        };
        let mut run = GpuRun::new(self)?;
        stepping::run(&schedule, &mut run, &mut recorder)?;
        if let Some(e) = recorder.error {
            return Err(e);
        }
        let mut base = recorder.base;
        if !base.receivers.is_empty() {
            run.download(&run.samples, &mut base.receivers)?;
        }
        let (mut u, mut v, mut f) = (vec![0.0; len], vec![0.0; len], vec![0.0; len]);
        run.download(&run.u, &mut u)?;
        run.download(&run.v, &mut v)?;
        if let Some(sp) = &run.probes {
            run.download(&sp.samples, &mut base.stresses)?;
        }
        let mut work = vec![0.0; run.input.len()];
        run.download(&run.input, &mut work)?;
        let mut input: f64 = work.iter().sum();
        for pw in &run.injections {
            let mut w = vec![0.0; pw.work.len()];
            run.download(&pw.work, &mut w)?;
            input += w.iter().sum::<f64>();
        }
        let absorbed = match &run.band {
            Some(b) => {
                let mut w = vec![0.0; b.work.len()];
                run.download(&b.work, &mut w)?;
                w.iter().sum()
            }
            None => 0.0,
        };
        // the cracks' state on the plan's own node numbers
        let cracks: Vec<_> = std::mem::take(&mut run.cracks)
            .into_iter()
            .zip(&self.cracks)
            .map(|(mut done, mine)| {
                done.faces.clone_from(&mine.faces);
                done
            })
            .collect();
        drop(run);
        Ok(self.output(base, &cracks, &u, &v, &mut f, input, absorbed))
    }
}
