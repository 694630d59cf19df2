#!/usr/bin/python3
"""Lowest ND modes of K x = lambda M x by scipy's eigsh (ARPACK) in shift-invert
mode at the same shift as bench_eigen (sigma from shift.txt), on the matrices
bench_eigen --export DIR wrote. The factorisation is scipy's default for
shift-invert: SuperLU of K - sigma M (scipy has no sparse Cholesky).

usage: /usr/bin/python3 bench/eigs_scipy.py DIR [ND]
"""
import os
import sys
import time

import numpy as np
import scipy
import scipy.sparse.linalg as sla

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mtx_io import read_symmetric_mtx, peak_rss_mib  # noqa: E402


def main():
    d = sys.argv[1]
    nd = int(sys.argv[2]) if len(sys.argv) > 2 else 41
    K = read_symmetric_mtx(os.path.join(d, "K.mtx"))
    M = read_symmetric_mtx(os.path.join(d, "M.mtx"))
    sigma = float(open(os.path.join(d, "shift.txt")).read())
    print(f"scipy {scipy.__version__}: n = {K.shape[0]}, nnz(K) = {K.nnz}, sigma = {sigma:.6g}")
    rng = np.random.default_rng(1)
    v0 = rng.uniform(-1.0, 1.0, K.shape[0])
    t0 = time.perf_counter()
    c0 = time.process_time()
    lam, phi = sla.eigsh(K.tocsc(), k=nd, M=M.tocsc(), sigma=sigma, which="LM", v0=v0, tol=1e-10)
    t = time.perf_counter() - t0
    cpu = time.process_time() - c0
    order = np.argsort(lam)
    lam, phi = lam[order], phi[:, order]
    KP, MP = K @ phi, M @ phi
    res = np.linalg.norm(KP - MP * lam, axis=0) / np.maximum(np.linalg.norm(KP, axis=0), 1e-300)
    print(f"time {t:.3f} s wall, {cpu:.3f} s CPU, peak RSS {peak_rss_mib():.0f} MiB")
    print(f"max residual (elastic) {res[6:].max():.2e}")
    ref_path = os.path.join(d, "eigenvalues_ssid.txt")
    if os.path.exists(ref_path):
        ref = np.loadtxt(ref_path)[:nd]
        top = np.abs(ref).max()
        print(f"max |lambda - lambda_ssid| / lambda_max = {np.abs(lam - ref).max() / top:.2e}")
    print("eigenvalues:", " ".join(f"{v:.10g}" for v in lam))


if __name__ == "__main__":
    main()
