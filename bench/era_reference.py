#!/usr/bin/python3
"""ERA (Juang and Pappa 1985) in numpy, the textbook way, on the FRFs that
bench_plscf --export DIR wrote, as `ssid identify modes --method era` runs it: the
impulse response by the inverse real FFT of the one-sided lines (the last line at the
Nyquist frequency), its first half as Markov parameters, a block Hankel matrix of r block
rows and s block columns (ssid's defaults: r = max(ceil(2N/no), ceil(60/no)),
s = min(K - r, max(r, 4000/ni))), one SVD, then per state dimension n = 2, 4, ..., N
A_n = S_n^-1/2 U_n^T H1 V_n S_n^-1/2 through the shifted Hankel matrix (the textbook
product, once per order; --shared-product forms U_N^T H1 V_N once and takes leading
blocks, as ssid does) and numpy's eigenvalues. It shares no code with ssid's.

usage: /usr/bin/python3 bench/era_reference.py DIR [MAX_STATE] [--shared-product]
Prints the time of the poles over the state dimensions and, when
DIR/era_poles_ssid.txt exists, the largest difference between ssid's and these poles of
the largest dimension.
"""
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plscf_reference import read_frf  # noqa: E402  (bench_plscf --export's file layout)


def era_poles(hz, H, max_state, shared):
    nf, no, ni = H.shape
    df = hz[1] - hz[0]
    n_samples = 2 * (nf - 1)
    # h[n] = df * sum over the two-sided spectrum of H(f_k) e^{2 pi i k n / N}
    h = np.fft.irfft(H, n=n_samples, axis=0) * n_samples * df  # samples x no x ni
    dt = 1.0 / (n_samples * df)
    Y = h[: n_samples // 2]
    K = Y.shape[0]
    r = max(-(-2 * max_state // no), -(-60 // no))
    s = min(K - r, max(r, 4000 // ni))
    H0 = np.empty((r * no, s * ni))
    H1 = np.empty((r * no, s * ni))
    for i in range(r):
        for j in range(s):
            H0[i * no:(i + 1) * no, j * ni:(j + 1) * ni] = Y[i + j]
            H1[i * no:(i + 1) * no, j * ni:(j + 1) * ni] = Y[i + j + 1]
    U, sig, Vt = np.linalg.svd(H0, full_matrices=False)
    G = U[:, :max_state].T @ H1 @ Vt[:max_state].T if shared else None
    out = {}
    for n in range(2, max_state + 1, 2):
        isq = 1.0 / np.sqrt(sig[:n])
        core = G[:n, :n] if shared else U[:, :n].T @ H1 @ Vt[:n].T
        A = isq[:, None] * core * isq[None, :]
        z = np.linalg.eigvals(A).astype(complex)
        z = z[(z.imag >= 0) & (np.abs(z) > 0)]
        out[n] = np.log(z) / dt
    return out


def main():
    d = sys.argv[1]
    args = [a for a in sys.argv[2:] if not a.startswith("--")]
    shared = "--shared-product" in sys.argv
    max_state = int(args[0]) if args else 200
    hz, H = read_frf(d + "/frf.bin")
    t0 = time.perf_counter()
    c0 = time.process_time()
    poles = era_poles(hz, H, max_state, shared)
    t1 = time.perf_counter()
    c1 = time.process_time()
    print(f"numpy ERA, state dimensions 2..{max_state}{' (shared product)' if shared else ''}: "
          f"{t1 - t0:.3f} s wall, {c1 - c0:.3f} s CPU")
    try:
        ssid = np.loadtxt(d + "/era_poles_ssid.txt", ndmin=2)
    except OSError:
        return
    lam = ssid[:, 0] + 1j * ssid[:, 1]
    ref = poles[max_state]
    worst = 0.0
    for p in lam:
        if -p.real / abs(p) > 0.2:
            continue  # heavily damped noise poles are ill-conditioned in both
        worst = max(worst, np.min(np.abs(ref - p)) / abs(p))
    print(f"largest relative difference of ssid's poles (damping < 20 %, {np.sum(-lam.real / np.abs(lam) <= 0.2)}) "
          f"from the nearest numpy pole at state dimension {max_state}: {worst:.2e}")


if __name__ == "__main__":
    main()
