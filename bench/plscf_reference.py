#!/usr/bin/python3
"""pLSCF (PolyMAX; Peeters et al. 2004) in numpy, the textbook way, on the FRFs that
bench_plscf --export DIR wrote: the same model as ssid's (right matrix fraction,
z = exp(i w dt), dt = 1/(2 f_max), alpha_p = I, each response weighted by 1/RMS of its
FRFs), with the normal-equation blocks formed from the Jacobian by matrix products
(X, Y_o = -X (x) H_o; R = Re X^H X, S_o = Re X^H Y_o, T_o = Re Y_o^H Y_o, once at the
largest order: a lower order's blocks are leading sub-blocks), then per order
M = sum_o T_o - S_o^T R^-1 S_o, alpha, the companion matrix and numpy's eigenvalues.
It shares no code or shortcut with ssid's (no Toeplitz sums, no shared Cholesky).

usage: /usr/bin/python3 bench/plscf_reference.py DIR [MAX_ORDER]
Prints the time of the poles over orders 1..MAX_ORDER and, when DIR/poles_ssid.txt
exists, the largest difference between ssid's and these poles of the largest order.
"""
import sys
import time

import numpy as np


def read_frf(path):
    raw = np.fromfile(path, dtype="<f8")
    nf, no, ni = (int(v) for v in raw[:3])
    hz = raw[3:3 + nf]
    data = raw[3 + nf:].reshape(nf, no, ni, 2)
    return hz, data[..., 0] + 1j * data[..., 1]


def plscf_poles(hz, H, orders):
    """Poles (rad/s, Im >= 0) per order; H is lines x responses x references."""
    band = hz > 0
    hz, H = hz[band], H[band]
    nf, no, ni = H.shape
    P = max(orders)
    dt = 1.0 / (2.0 * hz.max())
    H = H / np.sqrt(np.mean(np.abs(H) ** 2, axis=(0, 2)))[None, :, None]
    X = np.exp(1j * 2 * np.pi * hz * dt)[:, None] ** np.arange(P + 1)[None, :]
    R = np.real(X.conj().T @ X)
    S = np.empty((no, P + 1, (P + 1) * ni))
    T = np.zeros(((P + 1) * ni, (P + 1) * ni))
    for o in range(no):
        Y = -(X[:, :, None] * H[:, o, None, :]).reshape(nf, (P + 1) * ni)
        S[o] = np.real(X.conj().T @ Y)
        T += np.real(Y.conj().T @ Y)
    formed = time.perf_counter()
    out = {}
    for p in orders:
        n = (p + 1) * ni
        Sp = S[:, :p + 1, :n]
        RinvS = np.linalg.solve(R[:p + 1, :p + 1], Sp.transpose(1, 0, 2).reshape(p + 1, no * n))
        M = T[:n, :n] - np.tensordot(Sp, RinvS.reshape(p + 1, no, n).transpose(1, 0, 2), axes=([0, 1], [0, 1]))
        alpha = -np.linalg.solve(M[:p * ni, :p * ni], M[:p * ni, p * ni:])
        C = np.zeros((p * ni, p * ni))
        C[:-ni, ni:] = np.eye((p - 1) * ni)
        C[-ni:, :] = -np.hstack([alpha[j * ni:(j + 1) * ni].T for j in range(p)])
        z = np.linalg.eigvals(C)
        z = z[(z.imag >= 0) & (np.abs(z) > 0)]
        out[p] = np.log(z) / dt
    return out, formed


def main():
    d = sys.argv[1]
    P = int(sys.argv[2]) if len(sys.argv) > 2 else 100
    hz, H = read_frf(d + "/frf.bin")
    print(f"numpy {np.__version__}: {H.shape[2]} references x {H.shape[1]} responses x {H.shape[0]} lines, "
          f"orders 1..{P}")
    t0, c0 = time.perf_counter(), time.process_time()
    poles, formed = plscf_poles(hz, H, list(range(1, P + 1)))
    print(f"pLSCF poles, all orders: {time.perf_counter() - t0:.3f} s wall, {time.process_time() - c0:.3f} s CPU "
          f"(normal-equation blocks {formed - t0:.3f} s wall, then the orders)")
    try:
        ref = np.loadtxt(d + "/poles_ssid.txt")
    except OSError:
        return
    ours = poles[P]
    ssid = ref[:, 0] + 1j * ref[:, 1]
    # Each ssid pole against the nearest pole here, relative to its modulus (poles with
    # damping below 20 %, the ones the stabilisation can keep).
    keep = -ssid.real / np.abs(ssid) < 0.2
    worst = max(np.min(np.abs(ours - s)) / abs(s) for s in ssid[keep])
    print(f"order {P}: {len(ssid)} ssid poles, {len(ours)} here; largest relative distance of an ssid pole "
          f"(damping < 20 %, {keep.sum()} of them) to the nearest pole here: {worst:.2e}")


if __name__ == "__main__":
    main()
