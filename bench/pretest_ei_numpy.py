#!/usr/bin/python3
"""The numpy peer of bench_pretest's effective independence (docs/performance.md
"Pretest"): Kammer's iterative deletion on the modes bench_pretest exported
(--export DIR: phi.bin, c x m doubles row by row; phi.txt: "c m keep", the rows
ssid kept, ssid's log10 det F), with the same rank-one (Sherman-Morrison) update:
deleting row i with E_i = phi_i^T F^-1 phi_i,
    v = F^-1 phi_i,  F^-1 <- F^-1 + v v^T / (1 - E_i),  E_j <- E_j + (phi_j . v)^2 / (1 - E_i),
    det F <- det F (1 - E_i),
never a fresh determinant. Prints the time and whether the kept rows are ssid's.

usage: pretest_ei_numpy.py DIR
"""
import sys
import time

import numpy as np


def effective_independence(phi, keep):
    c, m = phi.shape
    f_inv = np.linalg.inv(phi.T @ phi)
    e = np.einsum("ij,jk,ik->i", phi, f_inv, phi)
    log_det = np.linalg.slogdet(phi.T @ phi)[1] / np.log(10)
    alive = np.ones(c, dtype=bool)
    e_masked = e.copy()
    for _ in range(c - keep):
        i = int(np.argmin(e_masked))  # the lowest index among ties, as ssid
        s = 1.0 - e[i]
        v = f_inv @ phi[i]
        f_inv += np.outer(v, v) / s
        w = phi @ v
        e += w * w / s
        log_det += np.log10(s)
        alive[i] = False
        e_masked = np.where(alive, e, np.inf)
    return np.flatnonzero(alive), log_det


def main():
    d = sys.argv[1]
    with open(d + "/phi.txt") as f:
        c, m, keep = (int(x) for x in f.readline().split())
        ssid_rows = [int(x) for x in f.readline().split()]
        ssid_log_det = float(f.readline())
    phi = np.fromfile(d + "/phi.bin", dtype="<f8").reshape(c, m)
    t0, c0 = time.perf_counter(), time.process_time()
    rows, log_det = effective_independence(phi, keep)
    t1, c1 = time.perf_counter(), time.process_time()
    direct = np.linalg.slogdet(phi[rows].T @ phi[rows])[1] / np.log(10)
    print(f"numpy {np.__version__} EI {c} DOFs -> {keep}, {m} modes: {t1 - t0:.2f} s wall, {c1 - c0:.2f} s CPU; "
          f"log10 det F {log_det:.6f} (updated), {direct:.6f} (direct); ssid's {ssid_log_det:.6f}")
    same = sorted(rows.tolist()) == sorted(ssid_rows)
    print("kept rows: " + ("the same as ssid's" if same else
                           f"DIFFER from ssid's ({len(set(rows.tolist()) ^ set(ssid_rows))} rows in one set only)"))
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
