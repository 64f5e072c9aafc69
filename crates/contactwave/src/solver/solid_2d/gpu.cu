// The GPU backend's kernels (feature `gpu`, solver/solid_2d/gpu.rs): the same step as the
// CPU's (docs/model.md eq. 15.2; kernel.rs): the elements' forces -K u through the
// element-to-node map, the node-wise leapfrog, the sources' forces and work (point loads,
// transducers and plane waves), the receivers' samples (velocities and stresses), the
// absorbing layers, and the gather and scatter of the cracks' split nodes, whose contact
// update runs on the host by the one per-point update of `law/`. Compiled at run time by NVRTC with
// `M` (GLL points per element line) and `E` (elements per thread block) defined before
// this text.
//
// Deterministic: the elements are coloured on the host so that no two elements of one
// colour share a node; each colour's scatter is a plain subtraction, the colours run in a
// fixed order, and every sum has a fixed order: the same bits on every run.

typedef unsigned long long u64;

// The GLL rule into shared memory (thread `t` of the block): the derivative d[i * M + j] =
// l_j'(x_i) and the weights.
__device__ void load_rule(const double* d, const double* w, double* sd, double* sw, int t) {
  if (t < M * M) sd[t] = d[t];
  if (t < M) sw[t] = w[t];
}

// The element `k` of a colour's list this thread serves, whether it exists, and the node
// of its point (a, b).
__device__ bool element_point(const unsigned* conn, const unsigned* list, int n, int k, int a,
                              int b, unsigned* e, unsigned* node) {
  bool live = k < n;
  *e = live ? list[k] : 0;
  *node = conn[(u64)*e * M * M + b * M + a];
  return live;
}

// The forces of the plane-strain elements `list[0..n]` (one colour): f[node] -= g. One
// thread per GLL point (a along x, b along z) of E elements; `par`: per element sx = 2/hx,
// sz = 2/hz, hx/2, hz/2, lambda + 2 mu, lambda, mu; `d`: the derivative d[i * M + j] =
// l_j'(x_i); `w`: the GLL weights.
extern "C" __global__ void psv_forces(const double* __restrict__ u, double* __restrict__ f,
                                      const unsigned* __restrict__ conn,
                                      const double* __restrict__ par,
                                      const double* __restrict__ d,
                                      const double* __restrict__ w,
                                      const unsigned* __restrict__ list, int n) {
  __shared__ double sd[M * M], sw[M];
  __shared__ double sux[E][M][M], suz[E][M][M];
  __shared__ double fxx[E][M][M], fzx[E][M][M], fxz[E][M][M], fzz[E][M][M];
  int a = threadIdx.x, b = threadIdx.y, le = threadIdx.z;
  load_rule(d, w, sd, sw, (le * M + b) * M + a);
  unsigned e, node;
  bool live = element_point(conn, list, n, blockIdx.x * E + le, a, b, &e, &node);
  if (live) {
    sux[le][b][a] = u[2 * (u64)node];
    suz[le][b][a] = u[2 * (u64)node + 1];
  }
  __syncthreads();
  if (live) {
    const double* p = par + 7 * (u64)e;
    double dxx = 0, dxz = 0, dzx = 0, dzz = 0;
    for (int j = 0; j < M; j++) {
      dxx += sd[a * M + j] * sux[le][b][j];
      dxz += sd[a * M + j] * suz[le][b][j];
      dzx += sd[b * M + j] * sux[le][j][a];
      dzz += sd[b * M + j] * suz[le][j][a];
    }
    double exx = dxx * p[0], ezz = dzz * p[1];
    double exz = dzx * p[1] + dxz * p[0];
    double sxx = p[4] * exx + p[5] * ezz;
    double szz = p[5] * exx + p[4] * ezz;
    double sxz = p[6] * exz;
    double wab = sw[a] * sw[b];
    double wx = p[3] * wab, wz = p[2] * wab;
    fxx[le][b][a] = wx * sxx;
    fzx[le][b][a] = wx * sxz;
    fxz[le][b][a] = wz * sxz;
    fzz[le][b][a] = wz * szz;
  }
  __syncthreads();
  if (live) {
    double gx = 0, gz = 0;
    for (int j = 0; j < M; j++) {
      gx += sd[j * M + a] * fxx[le][b][j];
      gz += sd[j * M + a] * fzx[le][b][j];
    }
    for (int j = 0; j < M; j++) {
      gx += sd[j * M + b] * fxz[le][j][a];
      gz += sd[j * M + b] * fzz[le][j][a];
    }
    f[2 * (u64)node] -= gx;
    f[2 * (u64)node + 1] -= gz;
  }
}

// The antiplane forces of the elements `list[0..n]` (one colour); `par` as for
// psv_forces, of which sx, sz, hx/2, hz/2 and mu are used.
extern "C" __global__ void sh_forces(const double* __restrict__ u, double* __restrict__ f,
                                     const unsigned* __restrict__ conn,
                                     const double* __restrict__ par,
                                     const double* __restrict__ d,
                                     const double* __restrict__ w,
                                     const unsigned* __restrict__ list, int n) {
  __shared__ double sd[M * M], sw[M];
  __shared__ double suy[E][M][M], fx[E][M][M], fz[E][M][M];
  int a = threadIdx.x, b = threadIdx.y, le = threadIdx.z;
  load_rule(d, w, sd, sw, (le * M + b) * M + a);
  unsigned e, node;
  bool live = element_point(conn, list, n, blockIdx.x * E + le, a, b, &e, &node);
  if (live) suy[le][b][a] = u[node];
  __syncthreads();
  if (live) {
    const double* p = par + 7 * (u64)e;
    double dx = 0, dz = 0;
    for (int j = 0; j < M; j++) {
      dx += sd[a * M + j] * suy[le][b][j];
      dz += sd[b * M + j] * suy[le][j][a];
    }
    double wab = sw[a] * sw[b];
    fx[le][b][a] = wab * (p[3] * p[6] * p[0]) * dx;
    fz[le][b][a] = wab * (p[2] * p[6] * p[1]) * dz;
  }
  __syncthreads();
  if (live) {
    double g = 0;
    for (int j = 0; j < M; j++) g += sd[j * M + a] * fx[le][b][j];
    for (int j = 0; j < M; j++) g += sd[j * M + b] * fz[le][j][a];
    f[node] -= g;
  }
}

// The node-wise leapfrog of all `n` nodes of `c` components: v += dt f / m, u += dt v,
// f = 0 (`im`: the inverse masses, 0 on rigid sides).
extern "C" __global__ void advance(double* u, double* v, double* f, const double* im, double dt,
                                   int c, int n) {
  int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  double s = dt * im[i];
  for (int k = 0; k < c; k++) {
    u64 j = (u64)c * i + k;
    double vv = v[j] + s * f[j];
    v[j] = vv;
    u[j] += dt * vv;
    f[j] = 0.0;
  }
}

// The sources' forces of the level: node `node[i]` gets the values of its loads
// `first[i]..first[i + 1]` in their order (one thread a node: the same order as one loop
// over the loads).
extern "C" __global__ void add_loads(double* f, const unsigned* node, const unsigned* first,
                                     const double* value, int n) {
  int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  double x = f[node[i]];
  for (unsigned l = first[i]; l < first[i + 1]; l++) x += value[l];
  f[node[i]] = x;
}

// Each load's work over the step, f^n dt (v^{n+1/2} + v^{n-1/2}) / 2, added to its own
// sum acc[l] (summed over the loads on the host at the end); `old`: each load's velocity of
// the previous half level; `index`: each load's entry of v.
extern "C" __global__ void load_work(const double* v, const unsigned* index,
                                     const double* value, double* old, double* acc, double dt,
                                     int n) {
  int l = blockIdx.x * blockDim.x + threadIdx.x;
  if (l >= n) return;
  double vn = v[index[l]];
  acc[l] += value[l] * dt * 0.5 * (vn + old[l]);
  old[l] = vn;
}

// The receivers' velocities of the half level: out[slot[i] + step] = v[index[i]].
extern "C" __global__ void record(const double* v, const unsigned* index, const u64* slot,
                                  double* out, u64 step, int n) {
  int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) out[slot[i] + step] = v[index[i]];
}

// A plane wave's incident displacements of level t (plane_wave.rs, Injection::add_forces),
// one thread a sample node: u_inc[i] = scale[i] G(t - delay[i]), G from its table (`g`,
// with the derivative `s`, `len` entries `step` s apart) by cubic Hermite interpolation,
// 0 before the table and its last entry after it.
extern "C" __global__ void inject_samples(double* u_inc, const double* __restrict__ delay,
                                          const double* __restrict__ scale,
                                          const double* __restrict__ g,
                                          const double* __restrict__ s, double step, u64 len,
                                          double t, int n) {
  int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  double tt = t - delay[i], G;
  if (tt <= 0.0) {
    G = 0.0;
  } else {
    double r = tt / step;
    u64 k = (u64)r;
    if (k + 1 >= len) {
      G = g[len - 1];
    } else {
      double x = r - (double)k, h = step;
      double x2 = x * x;
      double x3 = x2 * x;
      G = (2.0 * x3 - 3.0 * x2 + 1.0) * g[k] + (x3 - 2.0 * x2 + x) * h * s[k] +
          (-2.0 * x3 + 3.0 * x2) * g[k + 1] + (x3 - x2) * h * s[k + 1];
    }
  }
  u_inc[i] = scale[i] * G;
}

// A plane wave's forces across its line, one thread a target entry i of v and f
// (`target[i]`): the couplings `first[i]..first[i + 1]` (weights on samples, in their
// order) summed into force[i] and added to f.
extern "C" __global__ void inject_forces(double* f, const unsigned* __restrict__ target,
                                         const unsigned* __restrict__ first,
                                         const unsigned* __restrict__ sample,
                                         const double* __restrict__ weight,
                                         const double* __restrict__ u_inc, double* force,
                                         int n) {
  int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  double x = 0.0;
  for (unsigned p = first[i]; p < first[i + 1]; p++) x += weight[p] * u_inc[sample[p]];
  force[i] = x;
  f[target[i]] += x;
}

// The stress receivers' stresses of the half level (probe.rs and Records::record), one
// thread a receiver r: its stresses of this level from u by the element's derivative
// along its row (`node`/`w` entries 2M r .. 2M r + M) and column (the next M), Lame's
// lambda and mu in `lame`; out[(r sc + k) n_t + step] = (last + now) / 2, `last` kept
// (sc = 3 in plane strain, xx, zz, xz; 2 antiplane, yx, yz).
extern "C" __global__ void record_stress(const double* __restrict__ u,
                                         const unsigned* __restrict__ node,
                                         const double* __restrict__ w,
                                         const double* __restrict__ lame, double* last,
                                         double* out, u64 n_t, u64 step, int c, int n) {
  int r = blockIdx.x * blockDim.x + threadIdx.x;
  if (r >= n) return;
  const unsigned* row = node + (u64)r * 2 * M;
  const double* wr = w + (u64)r * 2 * M;
  double lambda = lame[2 * r], mu = lame[2 * r + 1];
  double now[3];
  int sc;
  if (c == 1) {
    double gx = 0.0, gz = 0.0;
    for (int k = 0; k < M; k++) gx += wr[k] * u[row[k]];
    for (int k = 0; k < M; k++) gz += wr[M + k] * u[row[M + k]];
    now[0] = mu * gx;
    now[1] = mu * gz;
    sc = 2;
  } else {
    double uxx = 0.0, uzx = 0.0, uxz = 0.0, uzz = 0.0;
    for (int k = 0; k < M; k++) uxx += wr[k] * u[2 * (u64)row[k]];
    for (int k = 0; k < M; k++) uzx += wr[k] * u[2 * (u64)row[k] + 1];
    for (int k = 0; k < M; k++) uxz += wr[M + k] * u[2 * (u64)row[M + k]];
    for (int k = 0; k < M; k++) uzz += wr[M + k] * u[2 * (u64)row[M + k] + 1];
    now[0] = (lambda + 2.0 * mu) * uxx + lambda * uzz;
    now[1] = lambda * uxx + (lambda + 2.0 * mu) * uzz;
    now[2] = mu * (uxz + uzx);
    sc = 3;
  }
  for (int k = 0; k < sc; k++) {
    u64 j = (u64)r * sc + k;
    out[j * n_t + step] = 0.5 * (last[j] + now[k]);
    last[j] = now[k];
  }
}

// The split nodes' values to the host: buf = [u of every entry, then v of every entry].
extern "C" __global__ void gather(const double* u, const double* v, const unsigned* index,
                                  double* buf, int n) {
  int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) {
    buf[i] = u[index[i]];
    buf[n + i] = v[index[i]];
  }
}

// The split nodes' values back from the host (the inverse of gather).
extern "C" __global__ void scatter(double* u, double* v, const unsigned* index,
                                   const double* buf, int n) {
  int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) {
    u[index[i]] = buf[i];
    v[index[i]] = buf[n + i];
  }
}

// flag[0] = 1 if any of x[0..n] is not finite.
extern "C" __global__ void finite(const double* x, int* flag, u64 n) {
  u64 i = (u64)blockIdx.x * blockDim.x + threadIdx.x;
  // (the exponent all ones: an infinity or a NaN)
  const u64 e = 0x7ff0000000000000ULL;
  if (i < n && (__double_as_longlong(x[i]) & e) == e) flag[0] = 1;
}

// The absorbing layers (pml.rs, model.md section 15.7), one thread per element point of
// the band's `n` elements: `par` per element as for psv_forces, `conn` the points' global
// nodes, `damp` their (d_x, d_z), `stress` their split stresses (P-SV: xx, zz, xz of
// sigma^x, then of sigma^z; SH: yx, yz), `part` the x and z parts of their forces.

// The parts of the points' forces from the stresses of level n (Band::forces_m).
extern "C" __global__ void band_parts(const double* __restrict__ stress,
                                      double* __restrict__ part,
                                      const double* __restrict__ par,
                                      const double* __restrict__ d,
                                      const double* __restrict__ w, int antiplane, int n) {
  u64 q = (u64)blockIdx.x * blockDim.x + threadIdx.x;
  if (q >= (u64)n * M * M) return;
  u64 e = q / (M * M);
  int a = (int)(q % M), b = (int)((q / M) % M);
  const double* p = par + 7 * e;
  double cx = p[3], cz = p[2];
  const u64 base = e * M * M;
  if (antiplane) {
    const double* s = stress + 2 * base;
    double gx = 0, gz = 0;
    for (int k = 0; k < M; k++) {
      gx += w[k] * d[k * M + a] * s[(b * M + k) * 2];
      gz += w[k] * d[k * M + b] * s[(k * M + a) * 2 + 1];
    }
    part[2 * q] = -cx * w[b] * gx;
    part[2 * q + 1] = -cz * w[a] * gz;
  } else {
    const double* s = stress + 6 * base;
    double xx = 0, xz = 0, zx = 0, zz = 0;
    for (int k = 0; k < M; k++) {
      const double* sx = s + (b * M + k) * 6;
      const double* sz = s + (k * M + a) * 6;
      double wa = w[k] * d[k * M + a], wb = w[k] * d[k * M + b];
      xx += wa * (sx[0] + sx[3]);
      xz += wa * (sx[2] + sx[5]);
      zx += wb * (sz[2] + sz[5]);
      zz += wb * (sz[1] + sz[4]);
    }
    part[4 * q] = -cx * w[b] * xx;
    part[4 * q + 1] = -cx * w[b] * xz;
    part[4 * q + 2] = -cz * w[a] * zx;
    part[4 * q + 3] = -cz * w[a] * zz;
  }
}

// The band nodes' forces, one thread a band node i (`node`: its global node; the first
// `inner` are on the inner boundary): the parts of its points `point[first[i]..first[i+1]]`
// (increasing: the CPU's element order) summed into fx, fz; an inner node adds them to f
// and keeps its velocity of level n - 1/2 in `old`.
extern "C" __global__ void band_assemble(const double* __restrict__ part,
                                         const unsigned* __restrict__ first,
                                         const unsigned* __restrict__ point,
                                         const unsigned* __restrict__ node, double* fx,
                                         double* fz, double* f, const double* v, double* old,
                                         int c, int inner, int n) {
  int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  for (int k = 0; k < c; k++) {
    double x = 0, z = 0;
    for (unsigned r = first[i]; r < first[i + 1]; r++) {
      const double* pp = part + (u64)point[r] * 2 * c;
      x += pp[k];
      z += pp[c + k];
    }
    fx[(u64)i * c + k] = x;
    fz[(u64)i * c + k] = z;
    if (i < inner) {
      u64 j = (u64)node[i] * c + k;
      f[j] += x + z;
      old[(u64)i * c + k] = v[j];
    }
  }
}

// After the interior's update, one thread a band node: an inner node's flux into the band
// over the step added to its own sum `work[i]` (`mass`: the band's share of its lumped
// mass); a pure band node's split velocities of level n + 1/2 (`ndamp`: its (d_x, d_z)),
// their sum into v and u moved along.
extern "C" __global__ void band_nodes(double* u, double* v, const double* im,
                                      const unsigned* __restrict__ node,
                                      const double* __restrict__ ndamp,
                                      const double* __restrict__ mass,
                                      const double* fx, const double* fz, double* vx,
                                      double* vz, const double* old, double* work, double dt,
                                      int c, int inner, int n) {
  int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  u64 g = node[i];
  if (i < inner) {
    double mb = mass[i], s = 0;
    for (int k = 0; k < c; k++) {
      u64 j = g * c + k, l = (u64)i * c + k;
      double vn = v[j], vo = old[l], force = fx[l] + fz[l];
      s -= 0.5 * dt * (vn + vo) * force - 0.5 * mb * (vn * vn - vo * vo);
    }
    work[i] += s;
    return;
  }
  double m = im[g];
  double ax = 0.5 * dt * ndamp[2 * i], az = 0.5 * dt * ndamp[2 * i + 1];
  for (int k = 0; k < c; k++) {
    u64 j = g * c + k, l = (u64)i * c + k;
    double x = ((1.0 - ax) * vx[l] + dt * m * fx[l]) / (1.0 + ax);
    double z = ((1.0 - az) * vz[l] + dt * m * fz[l]) / (1.0 + az);
    vx[l] = x;
    vz[l] = z;
    double nv = x + z;
    u[j] += dt * (nv - v[j]);
    v[j] = nv;
  }
}

// The stresses of level n + 1 from the velocities of level n + 1/2 (Band::stresses_m).
extern "C" __global__ void band_stresses(double* __restrict__ stress, const double* v,
                                         const unsigned* __restrict__ conn,
                                         const double* __restrict__ damp,
                                         const double* __restrict__ par,
                                         const double* __restrict__ d, double dt,
                                         int antiplane, int n) {
  u64 q = (u64)blockIdx.x * blockDim.x + threadIdx.x;
  if (q >= (u64)n * M * M) return;
  u64 e = q / (M * M);
  int a = (int)(q % M), b = (int)((q / M) % M);
  const double* p = par + 7 * e;
  const unsigned* cn = conn + e * M * M;
  double sx = p[0], sz = p[1], l2m = p[4], lam = p[5], mu = p[6];
  double ax = 0.5 * dt * damp[2 * q], az = 0.5 * dt * damp[2 * q + 1];
  double px = (1.0 - ax) / (1.0 + ax), pz = dt / (1.0 + ax);
  double qx = (1.0 - az) / (1.0 + az), qz = dt / (1.0 + az);
  double xx = 0, xz = 0, zx = 0, zz = 0;
  int c = antiplane ? 1 : 2;
  for (int k = 0; k < M; k++) {
    u64 gr = (u64)cn[b * M + k] * c, gc = (u64)cn[k * M + a] * c;
    xx += d[a * M + k] * v[gr];
    zx += d[b * M + k] * v[gc];
    if (!antiplane) {
      xz += d[a * M + k] * v[gr + 1];
      zz += d[b * M + k] * v[gc + 1];
    }
  }
  double vxx = sx * xx, vxz = sz * zx, vzx = sx * xz, vzz = sz * zz;
  if (antiplane) {
    double* s = stress + 2 * q;
    s[0] = px * s[0] + pz * mu * vxx;
    s[1] = qx * s[1] + qz * mu * vxz;
  } else {
    double* s = stress + 6 * q;
    s[0] = px * s[0] + pz * l2m * vxx;
    s[1] = px * s[1] + pz * lam * vxx;
    s[2] = px * s[2] + pz * mu * vzx;
    s[3] = qx * s[3] + qz * lam * vzz;
    s[4] = qx * s[4] + qz * l2m * vzz;
    s[5] = qx * s[5] + qz * mu * vxz;
  }
}
