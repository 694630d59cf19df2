#!/usr/bin/env python3
"""Writes the receptance FRFs of the 3-DOF chain of docs/identification.md as a
universal file (dataset 58, complex double): masses 1, 2, 1.5 kg, springs 2e4,
1.5e4, 1e4 N/m (the first to ground), Rayleigh damping C = 0.5 M + 2e-4 K, force
at DOF 1, responses at DOFs 1-3 (nodes 1, 2, 3 in +X), 0-500 Hz every 0.25 Hz.
The same system as tests/estimator/identification/chain_model.hpp and the FRFs of
tests/cli/chain_frf.hpp.

    python3 samples/identify/chain_frf.py OUT.unv
"""
import math
import sys


def chain(v):
    n = len(v)
    k = [[0.0] * n for _ in range(n)]
    k[0][0] += v[0]
    for i in range(1, n):
        k[i - 1][i - 1] += v[i]
        k[i][i] += v[i]
        k[i - 1][i] -= v[i]
        k[i][i - 1] -= v[i]
    return k


def solve(a, b):
    """a x = b by Gaussian elimination with partial pivoting (complex, small)."""
    n = len(b)
    a = [row[:] + [b[i]] for i, row in enumerate(a)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(a[r][c]))
        a[c], a[p] = a[p], a[c]
        for r in range(c + 1, n):
            f = a[r][c] / a[c][c]
            for q in range(c, n + 1):
                a[r][q] -= f * a[c][q]
    x = [0j] * n
    for r in reversed(range(n)):
        x[r] = (a[r][n] - sum(a[r][q] * x[q] for q in range(r + 1, n))) / a[r][r]
    return x


def main(path):
    m = [1.0, 2.0, 1.5]
    k = chain([2e4, 1.5e4, 1e4])
    df, lines = 0.25, 2001
    h = []  # h[j][o]: response o to a unit force at DOF 1, line j
    for j in range(lines):
        w = 2 * math.pi * df * j
        # Dynamic stiffness K - w^2 M + i w C with C = 0.5 M + 2e-4 K.
        z = [[k[r][q] * (1 + 2e-4j * w) + (m[r] * (-w * w + 0.5j * w) if r == q else 0) for q in range(3)]
             for r in range(3)]
        h.append(solve(z, [1, 0, 0]))
    out = []
    for o in range(3):
        out += ["    -1", "    58"] + ["NONE"] * 5
        # Record 6: FRF (4), id, version, load case; response and reference: name, node, direction.
        out.append("%5d%10d%5d%10d %-10s%10d%4d %-10s%10d%4d" % (4, o + 1, 0, 0, "NONE", o + 1, 1, "NONE", 1, 1))
        # Record 7: complex double (6), lines, even spacing, first abscissa, increment, z.
        out.append("%10d%10d%10d%13.5E%13.5E%13.5E" % (6, lines, 1, 0.0, df, 0.0))
        out += ["%10d%5d%5d%5d %-20s %-20s" % (0, 0, 0, 0, "NONE", "NONE")] * 4
        values = [x for j in range(lines) for x in (h[j][o].real, h[j][o].imag)]
        for a in range(0, len(values), 4):
            out.append("".join("%20.12E" % v for v in values[a:a + 4]))
        out.append("    -1")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main(sys.argv[1])
