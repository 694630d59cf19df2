#!/usr/bin/python3
"""Independent reference for estimator/identification/frf.cpp: Welch spectra, H1 (several
references: H1 = G_yx G_xx^-1 per line), H2, ordinary and multiple coherence from
scipy.signal.csd / scipy.signal.coherence on the same records.

Usage: welch_reference.py IN.json OUT.json
IN:  {"x": [[...] per sample], "y": [[...] per sample], "dt": s, "nperseg": N,
      "noverlap": L, "window": "hann" | "flattop" | "boxcar" | ["exponential", tau_samples]}
OUT: {"f": [...], "gyx": [line][k][i] as [re, im], "gxx": [line][i][j] as [re, im],
      "gyy": [line][k], "h1": [line][k][i] as [re, im], "h2": [line][k] as [re, im] (one reference),
      "coherence": [line][k][i], "multiple_coherence": [line][k]}
Convention: G_ab(k, i) = E[A_k conj(B_i)] = scipy.signal.csd(b_i, a_k) (csd(x, y) = E[conj(X) Y]).
"""
import json
import sys

import numpy as np
import scipy.signal as sig


def main():
    with open(sys.argv[1]) as f:
        d = json.load(f)
    x = np.asarray(d["x"], dtype=float)
    y = np.asarray(d["y"], dtype=float)
    fs = 1.0 / d["dt"]
    n = int(d["nperseg"])
    nov = int(d["noverlap"])
    w = d["window"]
    if isinstance(w, list):
        window = sig.get_window(("exponential", 0, float(w[1])), n)
    else:
        window = sig.get_window(w, n)
    kw = dict(fs=fs, window=window, nperseg=n, noverlap=nov, detrend=False, scaling="density",
              return_onesided=True)
    ni, no = x.shape[1], y.shape[1]
    f, _ = sig.csd(x[:, 0], x[:, 0], **kw)
    nf = len(f)
    gxx = np.zeros((nf, ni, ni), dtype=complex)
    gyx = np.zeros((nf, no, ni), dtype=complex)
    gyy = np.zeros((nf, no))
    for i in range(ni):
        for j in range(ni):
            gxx[:, i, j] = sig.csd(x[:, j], x[:, i], **kw)[1]
        for k in range(no):
            gyx[:, k, i] = sig.csd(x[:, i], y[:, k], **kw)[1]
    for k in range(no):
        gyy[:, k] = sig.csd(y[:, k], y[:, k], **kw)[1].real
    h1 = np.zeros((nf, no, ni), dtype=complex)
    mcoh = np.zeros((nf, no))
    coh = np.zeros((nf, no, ni))
    for line in range(nf):
        # H1 G_xx = G_yx
        h1[line] = np.linalg.solve(gxx[line].T, gyx[line].T).T
        for k in range(no):
            mcoh[line, k] = (h1[line, k, :] @ gyx[line, k, :].conj()).real / gyy[line, k]
    for k in range(no):
        for i in range(ni):
            coh[:, k, i] = sig.coherence(x[:, i], y[:, k], fs=fs, window=window, nperseg=n, noverlap=nov,
                                         detrend=False)[1]
    out = {
        "f": f.tolist(),
        "gxx": np.stack([gxx.real, gxx.imag], axis=-1).tolist(),
        "gyx": np.stack([gyx.real, gyx.imag], axis=-1).tolist(),
        "gyy": gyy.tolist(),
        "h1": np.stack([h1.real, h1.imag], axis=-1).tolist(),
        "coherence": coh.tolist(),
        "multiple_coherence": mcoh.tolist(),
    }
    if ni == 1:
        # H2 = G_yy / G_xy with G_xy = scipy.signal.csd(y, x) = E[conj(Y) X]
        h2 = np.zeros((nf, no), dtype=complex)
        for k in range(no):
            gxy = sig.csd(y[:, k], x[:, 0], **kw)[1]
            h2[:, k] = gyy[:, k] / gxy
        out["h2"] = np.stack([h2.real, h2.imag], axis=-1).tolist()
    with open(sys.argv[2], "w") as f:
        json.dump(out, f)


if __name__ == "__main__":
    main()
