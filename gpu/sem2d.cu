// A prototype GPU kernel of the 2D solver's bulk step (issue 26, item 6: "kernels shaped
// so that a GPU backend could take them over"): plane-strain P-SV spectral elements of
// order 6 on a uniform mesh of square elements, diagonal mass, the leapfrog of model.md
// eq. 15.2, a point force, free sides, no crack. Not part of the Rust build or of CI: run
// on a machine with an NVIDIA GPU and nvcc (gpu/run.sh). It checks its GPU step against a
// scalar CPU step of the same operator (same mesh, same operations) and reports
// node-updates per second (one node advanced one step in all its fields).
//
// Deterministic: the elements are coloured by the parity of their column and row (four
// colours); elements of one colour share no node, so each colour's scatter is a plain
// add, and the colours run in a fixed order: the same bits on every run.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>
#include <chrono>
#include <cuda_runtime.h>

#define N 6
#define M (N + 1)
#define E 4  // elements per thread block

#define CHECK(x) do { cudaError_t e = (x); if (e != cudaSuccess) { \
  fprintf(stderr, "CUDA error %s at %s:%d\n", cudaGetErrorString(e), __FILE__, __LINE__); exit(1);} } while (0)

__constant__ double cD[M * M];   // derivative matrix d[i][j] = l_j'(x_i)
__constant__ double cW[M];       // GLL weights

struct Mesh {
  int nex, nez, nx, nz;  // elements and nodes along x and z
  double h, lam, mu, rho;
};

// P_k(t) for k = n - 1 and n (Legendre's recurrence), n >= 1.
static void legendre(int n, double t, double& pm1, double& p) {
  double p0 = 1.0, p1 = t;
  for (int k = 2; k <= n; k++) { double p2 = ((2 * k - 1) * t * p1 - (k - 1) * p0) / k; p0 = p1; p1 = p2; }
  pm1 = p0; p = p1;
}

// GLL points, weights and derivative matrix of order N (Legendre recurrences, Newton).
static void gll(double* x, double* w, double* d) {
  for (int i = 0; i <= N; i++) x[i] = -cos(M_PI * i / N);
  for (int i = 1; i < N; i++) {
    for (int it = 0; it < 100; it++) {
      // the interior points are the roots of P_{N-1} - t P_N (= (1 - t^2) P_N' / N)
      double t = x[i], p0, p1, q0, q1;
      legendre(N, t, p0, p1);        // P_{N-1}, P_N
      legendre(N - 1, t, q0, q1);    // P_{N-2}, P_{N-1}
      double f = p0 - t * p1;
      double dpn = N * (t * p1 - p0) / (t * t - 1.0);
      double dpnm1 = (N - 1) * (t * p0 - q0) / (t * t - 1.0);
      double dt = f / (dpnm1 - p1 - t * dpn);
      x[i] = t - dt;
      if (fabs(dt) < 1e-16) break;
    }
  }
  double pn[M];
  for (int i = 0; i <= N; i++) {
    double pm1, p;
    legendre(N, x[i], pm1, p);
    pn[i] = p;
    w[i] = 2.0 / (N * (N + 1) * p * p);
  }
  for (int i = 0; i <= N; i++)
    for (int j = 0; j <= N; j++) {
      double v;
      if (i != j) v = pn[i] / (pn[j] * (x[i] - x[j]));
      else if (i == 0) v = -N * (N + 1) / 4.0;
      else if (i == N) v = N * (N + 1) / 4.0;
      else v = 0.0;
      d[i * M + j] = v;
    }
}

// The forces -K u of the elements of one colour (cx, cz): element (ex, ez) with ex % 2 ==
// cx and ez % 2 == cz. Block: M x M x E threads, one per GLL point of E elements.
__global__ void forces(const double* __restrict__ u, double* __restrict__ f, Mesh m, int cx, int cz) {
  __shared__ double sux[E][M][M], suz[E][M][M];
  __shared__ double fxx[E][M][M], fzx[E][M][M], fxz[E][M][M], fzz[E][M][M];
  int a = threadIdx.x, b = threadIdx.y, le = threadIdx.z;
  int ncx = (m.nex - cx + 1) / 2, ncz = (m.nez - cz + 1) / 2;
  int k = blockIdx.x * E + le;
  bool live = k < ncx * ncz;
  int ex = cx + 2 * (live ? k % ncx : 0), ez = cz + 2 * (live ? k / ncx : 0);
  int node = (ez * N + b) * m.nx + ex * N + a;
  if (live) { sux[le][b][a] = u[2 * node]; suz[le][b][a] = u[2 * node + 1]; }
  __syncthreads();
  if (live) {
    double dxx = 0, dxz = 0, dzx = 0, dzz = 0;
    for (int j = 0; j < M; j++) {
      dxx += cD[a * M + j] * sux[le][b][j];
      dxz += cD[a * M + j] * suz[le][b][j];
      dzx += cD[b * M + j] * sux[le][j][a];
      dzz += cD[b * M + j] * suz[le][j][a];
    }
    double s = 2.0 / m.h;
    double exx = dxx * s, ezz = dzz * s, exz = dzx * s + dxz * s;
    double sxx = (m.lam + 2 * m.mu) * exx + m.lam * ezz;
    double szz = m.lam * exx + (m.lam + 2 * m.mu) * ezz;
    double sxz = m.mu * exz;
    double wab = cW[a] * cW[b] * 0.5 * m.h;
    fxx[le][b][a] = wab * sxx; fzx[le][b][a] = wab * sxz;
    fxz[le][b][a] = wab * sxz; fzz[le][b][a] = wab * szz;
  }
  __syncthreads();
  if (live) {
    double gx = 0, gz = 0;
    for (int j = 0; j < M; j++) {
      gx += cD[j * M + a] * fxx[le][b][j] + cD[j * M + b] * fxz[le][j][a];
      gz += cD[j * M + a] * fzx[le][b][j] + cD[j * M + b] * fzz[le][j][a];
    }
    f[2 * node] -= gx;
    f[2 * node + 1] -= gz;
  }
}

__global__ void advance(double* u, double* v, double* f, const double* im, double dt, int n) {
  int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  double s = dt * im[i];
  for (int c = 0; c < 2; c++) {
    double vv = v[2 * i + c] + s * f[2 * i + c];
    v[2 * i + c] = vv;
    u[2 * i + c] += dt * vv;
    f[2 * i + c] = 0.0;
  }
}

__global__ void force_at(double* f, int node, double fz) { f[2 * node + 1] += fz; }

// The same step on the CPU, element by element (the reference).
static void cpu_forces(const std::vector<double>& u, std::vector<double>& f, const Mesh& m,
                       const double* D, const double* W) {
  for (int cz = 0; cz < 2; cz++) for (int cx = 0; cx < 2; cx++)
  for (int ez = cz; ez < m.nez; ez += 2) for (int ex = cx; ex < m.nex; ex += 2) {
    double ux[M][M], uz[M][M], Fxx[M][M], Fzx[M][M], Fxz[M][M], Fzz[M][M];
    for (int b = 0; b < M; b++) for (int a = 0; a < M; a++) {
      int node = (ez * N + b) * m.nx + ex * N + a;
      ux[b][a] = u[2 * node]; uz[b][a] = u[2 * node + 1];
    }
    for (int b = 0; b < M; b++) for (int a = 0; a < M; a++) {
      double dxx = 0, dxz = 0, dzx = 0, dzz = 0;
      for (int j = 0; j < M; j++) {
        dxx += D[a * M + j] * ux[b][j]; dxz += D[a * M + j] * uz[b][j];
        dzx += D[b * M + j] * ux[j][a]; dzz += D[b * M + j] * uz[j][a];
      }
      double s = 2.0 / m.h;
      double exx = dxx * s, ezz = dzz * s, exz = dzx * s + dxz * s;
      double sxx = (m.lam + 2 * m.mu) * exx + m.lam * ezz, szz = m.lam * exx + (m.lam + 2 * m.mu) * ezz;
      double sxz = m.mu * exz, wab = W[a] * W[b] * 0.5 * m.h;
      Fxx[b][a] = wab * sxx; Fzx[b][a] = wab * sxz; Fxz[b][a] = wab * sxz; Fzz[b][a] = wab * szz;
    }
    for (int b = 0; b < M; b++) for (int a = 0; a < M; a++) {
      double gx = 0, gz = 0;
      for (int j = 0; j < M; j++) {
        gx += D[j * M + a] * Fxx[b][j] + D[j * M + b] * Fxz[j][a];
        gz += D[j * M + a] * Fzx[b][j] + D[j * M + b] * Fzz[j][a];
      }
      int node = (ez * N + b) * m.nx + ex * N + a;
      f[2 * node] -= gx; f[2 * node + 1] -= gz;
    }
  }
}

struct Run { double seconds, max_u, max_diff; long nodes; int steps; };

// nex x nez elements of h, `steps` steps of dt; a 5 MHz 5-cycle Hann burst of a vertical
// point force at the top middle; with `check`, the CPU step alongside.
static Run run(int nex, int nez, double h, double dt, int steps, bool check) {
  Mesh m;
  m.nex = nex; m.nez = nez; m.nx = nex * N + 1; m.nz = nez * N + 1; m.h = h;
  double rho = 2700, cp = 6320, cs = 3130;
  m.mu = rho * cs * cs; m.lam = rho * cp * cp - 2 * m.mu; m.rho = rho;
  double x[M], w[M], d[M * M];
  gll(x, w, d);
  CHECK(cudaMemcpyToSymbol(cD, d, sizeof d));
  CHECK(cudaMemcpyToSymbol(cW, w, sizeof w));
  long n = (long)m.nx * m.nz;
  std::vector<double> mass(n, 0.0), im(n);
  for (int ez = 0; ez < nez; ez++) for (int ex = 0; ex < nex; ex++)
    for (int b = 0; b < M; b++) for (int a = 0; a < M; a++)
      mass[(long)(ez * N + b) * m.nx + ex * N + a] += rho * w[a] * w[b] * h * h / 4;
  for (long i = 0; i < n; i++) im[i] = 1.0 / mass[i];
  double *du, *dv, *df, *dim;
  CHECK(cudaMalloc(&du, 2 * n * sizeof(double))); CHECK(cudaMalloc(&dv, 2 * n * sizeof(double)));
  CHECK(cudaMalloc(&df, 2 * n * sizeof(double))); CHECK(cudaMalloc(&dim, n * sizeof(double)));
  CHECK(cudaMemset(du, 0, 2 * n * sizeof(double))); CHECK(cudaMemset(dv, 0, 2 * n * sizeof(double)));
  CHECK(cudaMemset(df, 0, 2 * n * sizeof(double)));
  CHECK(cudaMemcpy(dim, im.data(), n * sizeof(double), cudaMemcpyHostToDevice));
  std::vector<double> u(2 * n, 0.0), v(2 * n, 0.0), f(2 * n, 0.0);
  int src = (m.nx / 2);  // top middle node
  auto signal = [](double t) {
    double f0 = 5e6, T = 5 / f0;
    if (t < 0 || t > T) return 0.0;
    return 1e3 * sin(2 * M_PI * f0 * t) * 0.5 * (1 - cos(2 * M_PI * t / T));
  };
  dim3 blk(M, M, E);
  cudaEvent_t t0, t1;
  CHECK(cudaEventCreate(&t0)); CHECK(cudaEventCreate(&t1));
  CHECK(cudaEventRecord(t0));
  for (int s = 0; s < steps; s++) {
    double fz = signal(s * dt);
    force_at<<<1, 1>>>(df, src, fz);
    for (int c = 0; c < 4; c++) {
      int cx = c % 2, cz = c / 2;
      int ne = ((nex - cx + 1) / 2) * ((nez - cz + 1) / 2);
      forces<<<(ne + E - 1) / E, blk>>>(du, df, m, cx, cz);
    }
    advance<<<(n + 255) / 256, 256>>>(du, dv, df, dim, dt, (int)n);
    if (check) {
      f[2 * src + 1] += fz;
      cpu_forces(u, f, m, d, w);
      for (long i = 0; i < n; i++) for (int c = 0; c < 2; c++) {
        v[2 * i + c] += dt * im[i] * f[2 * i + c];
        u[2 * i + c] += dt * v[2 * i + c];
        f[2 * i + c] = 0.0;
      }
    }
  }
  CHECK(cudaEventRecord(t1)); CHECK(cudaEventSynchronize(t1));
  CHECK(cudaGetLastError());
  float ms; CHECK(cudaEventElapsedTime(&ms, t0, t1));
  std::vector<double> ug(2 * n);
  CHECK(cudaMemcpy(ug.data(), du, 2 * n * sizeof(double), cudaMemcpyDeviceToHost));
  Run r{ms * 1e-3, 0.0, 0.0, n, steps};
  for (long i = 0; i < 2 * n; i++) {
    r.max_u = fmax(r.max_u, fabs(ug[i]));
    if (check) r.max_diff = fmax(r.max_diff, fabs(ug[i] - u[i]));
  }
  cudaFree(du); cudaFree(dv); cudaFree(df); cudaFree(dim);
  return r;
}

int main() {
  double dt = 1.2e-9, h = 0.25e-3;
  // the check: a small plate, GPU against CPU
  Run c = run(40, 10, h, dt, 400, true);
  printf("check: %ld nodes, %d steps: max |u| %.3e m, max |u_gpu - u_cpu| %.3e (%.1e of max |u|)\n",
         c.nodes, c.steps, c.max_u, c.max_diff, c.max_diff / c.max_u);
  // throughput: the reference case's plate (40 x 10 mm: 160 x 40 elements of 0.25 mm) and
  // larger ones
  int sizes[][2] = {{160, 40}, {640, 160}, {1280, 640}, {2560, 1280}};
  for (auto& s : sizes) {
    run(s[0], s[1], h, dt, 20, false);  // warm-up
    Run r = run(s[0], s[1], h, dt, 200, false);
    printf("GPU %d x %d elements of order %d (%ld nodes), %d steps: %.3f s, %.3e node-updates/s\n",
           s[0], s[1], N, r.nodes, r.steps, r.seconds, r.nodes * (double)r.steps / r.seconds);
  }
  return 0;
}
