#!/usr/bin/env python3
"""Write the record files read by crates/contactwave/tests/all/measured.rs (committed under
crates/contactwave/tests/data/measured/): the same three records (a drive-amplitude series)
in every format `contactwave analyze` reads, and the variants it must refuse.

    python3 -m venv /tmp/fx && /tmp/fx/bin/pip install numpy scipy h5py
    /tmp/fx/bin/python scripts/make_measured_fixtures.py

The records: t = k dt (dt = 10 ns, 1024 samples), record j (j = 0, 1, 2) =
(j + 1) sin(2 pi 2 MHz t) + 0.01 (j + 1)^2 sin(2 pi 4 MHz t) + 0.25 j (a DC offset);
drive amplitudes 1, 2, 3.
"""
import os
import numpy as np
import scipy.io
import h5py

out = os.path.join(os.path.dirname(__file__), "..", "crates", "contactwave", "tests", "data", "measured")
os.makedirs(out, exist_ok=True)
dt, n, f = 1e-8, 1024, 2e6
t = np.arange(n) * dt
echo = np.stack(
    [(j + 1) * np.sin(2 * np.pi * f * t) + 0.01 * (j + 1) ** 2 * np.sin(4 * np.pi * f * t) + 0.25 * j for j in range(3)],
    axis=1,
)  # samples x records
amp = np.array([1.0, 2.0, 3.0])

# CSV: a time column and one column per record
with open(os.path.join(out, "records.csv"), "w") as fh:
    fh.write("# three records of one echo at drive amplitudes 1, 2, 3 V\n")
    fh.write("t,a1,a2,a3\n")
    for k in range(n):
        fh.write(",".join(repr(float(v)) for v in [t[k], *echo[k]]) + "\n")
# NPY: samples x records, no time (float32, Fortran order: read with --sample-rate 1e8)
np.save(os.path.join(out, "records_f32_fortran.npy"), np.asfortranarray(echo.astype(np.float32)))
# NPZ: named arrays
np.savez(os.path.join(out, "records.npz"), t=t, echo=echo, amplitude=amp)
np.savez(os.path.join(out, "complex.npz"), t=t, echo=echo[:, 0] * (1 + 1j))
# MAT v5 (scipy writes MATLAB 5.0 files; t as a 1 x n row vector as MATLAB users keep it)
scipy.io.savemat(os.path.join(out, "records_v5.mat"), {"t": t[None, :], "echo": echo, "amplitude": amp, "note": "scope CH1"}, do_compression=True)
scipy.io.savemat(os.path.join(out, "complex_v5.mat"), {"t": t[None, :], "echo": echo[:, :1] * (1 + 1j)})
# MAT v7.3, as MATLAB writes it: HDF5 behind a 512-byte userblock holding the MATLAB
# header, every variable with its MATLAB_class, matrices stored column-major (HDF5 shape
# [cols, rows]), compressed in chunks
path = os.path.join(out, "records_v73.mat")
with h5py.File(path, "w", userblock_size=512) as h:
    for name, value in [("t", t[None, :]), ("echo", echo), ("amplitude", amp[None, :])]:
        d = h.create_dataset(name, data=value.T, chunks=True, compression="gzip")
        d.attrs["MATLAB_class"] = np.bytes_("double")
    d = h.create_dataset("note", data=np.frombuffer("scope CH1".encode("utf-16-le"), dtype=np.uint16)[:, None])
    d.attrs["MATLAB_class"] = np.bytes_("char")
header = b"MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: Wed Nov 25 12:00:00 2026 HDF5 schema 1.00 ."
with open(path, "r+b") as fh:
    block = header.ljust(116, b" ") + b"\x00" * 8 + b"\x00\x02" + b"IM"
    fh.write(block.ljust(512, b"\x00"))
# HDF5: an oscilloscope's layout, records in a group
with h5py.File(os.path.join(out, "records.h5"), "w") as h:
    g = h.create_group("scope")
    g.create_dataset("time", data=t)
    for j in range(3):
        g.create_dataset(f"ch{j + 1}", data=echo[:, j], chunks=(256,), compression="gzip")
    h.create_dataset("label", data="echo series")
# a non-uniform time base: one sample missing
with open(os.path.join(out, "gap.csv"), "w") as fh:
    fh.write("t,a1\n")
    for k in range(n):
        if k != 500:
            fh.write(f"{float(t[k])!r},{float(echo[k, 0])!r}\n")
print("wrote", sorted(os.listdir(out)))
