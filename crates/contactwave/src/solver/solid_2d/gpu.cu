// The GPU backend's kernels (feature `gpu`, solver/solid_2d/gpu.rs): the same step as the
// CPU's (docs/model.md eq. 15.2; kernel.rs): the elements' forces -K u through the
// element-to-node map, the node-wise leapfrog, the sources' forces and work, the receivers'
// samples, and the gather and scatter of the cracks' split nodes, whose contact update runs
// on the host by the one per-point update of `law/`. Compiled at run time by NVRTC with
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
