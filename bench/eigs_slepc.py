#!/usr/bin/python3
"""Lowest ND modes of K x = lambda M x by SLEPc's Krylov-Schur (generalised
Hermitian problem) with a shift-and-invert spectral transformation at the same
shift as bench_eigen, the inner solves by a MUMPS Cholesky factorisation of
K - sigma M, on the matrices bench_eigen --export DIR wrote.
Debian packages: python3-slepc4py, python3-petsc4py (found below even when the
petsc/slepc alternatives of the -dev packages are not installed).

usage: /usr/bin/python3 bench/eigs_slepc.py DIR [ND]
"""
import glob
import os
import sys
import time

import numpy as np

for pattern in ("/usr/lib/petscdir/petsc*/x86_64-linux-gnu-real/lib/python3/dist-packages",
                "/usr/lib/slepcdir/slepc*/x86_64-linux-gnu-real/lib/python3/dist-packages"):
    sys.path.extend(sorted(glob.glob(pattern)))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mtx_io import read_symmetric_mtx, peak_rss_mib  # noqa: E402

import petsc4py  # noqa: E402

petsc4py.init(sys.argv[:1])
import slepc4py  # noqa: E402

slepc4py.init(sys.argv[:1])
from petsc4py import PETSc  # noqa: E402
from slepc4py import SLEPc  # noqa: E402


def to_petsc(A):
    A = A.tocsr()
    A.sort_indices()
    m = PETSc.Mat().createAIJ(size=A.shape, csr=(A.indptr.astype(PETSc.IntType),
                                                 A.indices.astype(PETSc.IntType), A.data))
    m.setOption(PETSc.Mat.Option.SYMMETRIC, True)
    m.assemble()
    return m


def main():
    d = sys.argv[1]
    nd = int(sys.argv[2]) if len(sys.argv) > 2 else 41
    Ks = read_symmetric_mtx(os.path.join(d, "K.mtx"))
    Ms = read_symmetric_mtx(os.path.join(d, "M.mtx"))
    sigma = float(open(os.path.join(d, "shift.txt")).read())
    K, M = to_petsc(Ks), to_petsc(Ms)
    print(f"SLEPc {SLEPc.Sys.getVersion()}, PETSc {PETSc.Sys.getVersion()}: n = {Ks.shape[0]}, sigma = {sigma:.6g}")
    t0 = time.perf_counter()
    c0 = time.process_time()
    eps = SLEPc.EPS().create()
    eps.setOperators(K, M)
    eps.setProblemType(SLEPc.EPS.ProblemType.GHEP)
    eps.setType(SLEPc.EPS.Type.KRYLOVSCHUR)
    eps.setDimensions(nev=nd)
    eps.setTarget(sigma)
    eps.setWhichEigenpairs(SLEPc.EPS.Which.TARGET_MAGNITUDE)
    eps.setTolerances(tol=1e-10, max_it=1000)
    st = eps.getST()
    st.setType(SLEPc.ST.Type.SINVERT)
    st.setShift(sigma)
    ksp = st.getKSP()
    ksp.setType(PETSc.KSP.Type.PREONLY)
    pc = ksp.getPC()
    pc.setType(PETSc.PC.Type.CHOLESKY)
    pc.setFactorSolverType(PETSc.Mat.SolverType.MUMPS)
    eps.setFromOptions()
    eps.solve()
    t = time.perf_counter() - t0
    cpu = time.process_time() - c0
    nconv = eps.getConverged()
    its = eps.getIterationNumber()
    lam = []
    vr = K.createVecRight()
    res = []
    for i in range(min(nconv, nd)):
        lam.append(eps.getEigenpair(i, vr).real)
        res.append(eps.computeError(i, SLEPc.EPS.ErrorType.RELATIVE))
    lam = np.array(lam)
    order = np.argsort(lam)
    lam = lam[order]
    print(f"time {t:.3f} s wall, {cpu:.3f} s CPU, converged {nconv}, iterations {its}, peak RSS {peak_rss_mib():.0f} MiB")
    # SLEPc's relative error |lambda| scaled: meaningless for the rigid-body
    # modes (lambda ~ 0), so the elastic ones (after the six zero ones) are shown.
    print(f"max relative error estimate (elastic) {max(res[6:]):.2e}")
    ref_path = os.path.join(d, "eigenvalues_ssid.txt")
    if os.path.exists(ref_path) and len(lam) >= nd:
        ref = np.loadtxt(ref_path)[:nd]
        print(f"max |lambda - lambda_ssid| / lambda_max = {np.abs(lam[:nd] - ref).max() / np.abs(ref).max():.2e}")
    print("eigenvalues:", " ".join(f"{v:.10g}" for v in lam))


if __name__ == "__main__":
    main()
