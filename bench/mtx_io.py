"""Shared by eigs_scipy.py and eigs_slepc.py: reads the MatrixMarket files that
bench_eigen --export writes (coordinate real symmetric, lower triangle) into
full scipy CSR matrices, fast (numpy's C text reader instead of scipy.io.mmread),
and reports peak memory."""
import resource
import numpy as np
import scipy.sparse as sp


def read_symmetric_mtx(path):
    with open(path) as f:
        header = f.readline()
        if "symmetric" not in header:
            raise ValueError(f"{path}: expected a symmetric MatrixMarket file, got {header.strip()}")
        line = f.readline()
        while line.startswith("%"):
            line = f.readline()
        n, _, nnz = (int(v) for v in line.split())
        data = np.loadtxt(f, dtype=np.float64, ndmin=2)
    if data.shape[0] != nnz:
        raise ValueError(f"{path}: {data.shape[0]} entries, header says {nnz}")
    i = data[:, 0].astype(np.int64) - 1
    j = data[:, 1].astype(np.int64) - 1
    v = data[:, 2]
    low = sp.coo_matrix((v, (i, j)), shape=(n, n)).tocsr()
    full = low + sp.tril(low, -1).T
    return full.tocsr()


def peak_rss_mib():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
