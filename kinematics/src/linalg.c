/* Fixed-size dense linear algebra for 6x6 problems; no heap, no recursion. */
#include "kin_internal.h"

tse_real tse_lu_factor6(tse_real A[6][6], int perm[6])
{
    tse_real det = TSE_R(1.0);
    for (int i = 0; i < 6; ++i)
        perm[i] = i;
    for (int k = 0; k < 6; ++k) {
        int p = k;
        for (int i = k + 1; i < 6; ++i)
            if (tse_fabs(A[i][k]) > tse_fabs(A[p][k]))
                p = i;
        if (A[p][k] == TSE_R(0.0))
            return TSE_R(0.0);
        if (p != k) {
            for (int j = 0; j < 6; ++j) {
                const tse_real t = A[k][j];
                A[k][j] = A[p][j];
                A[p][j] = t;
            }
            const int t = perm[k];
            perm[k] = perm[p];
            perm[p] = t;
            det = -det;
        }
        det *= A[k][k];
        for (int i = k + 1; i < 6; ++i) {
            const tse_real f = A[i][k] / A[k][k];
            A[i][k] = f;
            for (int j = k + 1; j < 6; ++j)
                A[i][j] -= f * A[k][j];
        }
    }
    return det;
}

void tse_lu_solve6(const tse_real LU[6][6], const int perm[6], const tse_real b[6], tse_real x[6])
{
    tse_real y[6];
    for (int i = 0; i < 6; ++i) {
        tse_real s = b[perm[i]];
        for (int j = 0; j < i; ++j)
            /* cppcheck-suppress uninitvar ; y[j < i] was set by an earlier pass of this loop */
            s -= LU[i][j] * y[j];
        y[i] = s;
    }
    for (int i = 5; i >= 0; --i) {
        tse_real s = y[i];
        for (int j = i + 1; j < 6; ++j)
            /* cppcheck-suppress uninitvar ; x[j > i] was set by an earlier pass of this loop */
            s -= LU[i][j] * x[j];
        x[i] = s / LU[i][i];
    }
}

void tse_sym_eigen6(tse_real A[6][6], tse_real eig[6])
{
    for (int sweep = 0; sweep < 60; ++sweep) {
        tse_real off = TSE_R(0.0), diag = TSE_R(0.0);
        for (int i = 0; i < 6; ++i) {
            diag += A[i][i] * A[i][i];
            for (int j = i + 1; j < 6; ++j)
                off += A[i][j] * A[i][j];
        }
        if (off <= TSE_REAL_EPS * TSE_REAL_EPS * diag || off == TSE_R(0.0))
            break;
        for (int p = 0; p < 5; ++p) {
            for (int q = p + 1; q < 6; ++q) {
                if (A[p][q] == TSE_R(0.0))
                    continue;
                /* The rotation that zeroes A[p][q], with the smaller of the two angles. */
                const tse_real theta = (A[q][q] - A[p][p]) / (TSE_R(2.0) * A[p][q]);
                const tse_real t = (theta >= TSE_R(0.0) ? TSE_R(1.0) : TSE_R(-1.0)) /
                                   (tse_fabs(theta) + tse_sqrt(theta * theta + TSE_R(1.0)));
                const tse_real cs = TSE_R(1.0) / tse_sqrt(t * t + TSE_R(1.0));
                const tse_real sn = t * cs;
                for (int k = 0; k < 6; ++k) {
                    const tse_real akp = A[k][p], akq = A[k][q];
                    A[k][p] = cs * akp - sn * akq;
                    A[k][q] = sn * akp + cs * akq;
                }
                for (int k = 0; k < 6; ++k) {
                    const tse_real apk = A[p][k], aqk = A[q][k];
                    A[p][k] = cs * apk - sn * aqk;
                    A[q][k] = sn * apk + cs * aqk;
                }
            }
        }
    }
    for (int i = 0; i < 6; ++i)
        eig[i] = A[i][i];
    for (int i = 1; i < 6; ++i) {
        const tse_real v = eig[i];
        int j = i - 1;
        while (j >= 0 && eig[j] < v) {
            eig[j + 1] = eig[j];
            --j;
        }
        eig[j + 1] = v;
    }
}

int tse_weakest_row6(const tse_real A[6][6])
{
    tse_real N[6][6];
    int perm[6];
    for (int i = 0; i < 6; ++i) {
        tse_real n = TSE_R(0.0);
        for (int j = 0; j < 6; ++j)
            n += A[i][j] * A[i][j];
        n = tse_sqrt(n);
        if (!(n > TSE_R(0.0)))
            return i;
        for (int j = 0; j < 6; ++j)
            N[i][j] = A[i][j] / n;
    }
    if (tse_lu_factor6(N, perm) == TSE_R(0.0))
        return -1;
    /* Row r's distance to the span of the others is 1 / |column r of N^-1|. */
    int worst = 0;
    tse_real worst_norm = TSE_R(-1.0);
    for (int r = 0; r < 6; ++r) {
        tse_real e[6] = {0}, x[6];
        e[r] = TSE_R(1.0);
        tse_lu_solve6(N, perm, e, x);
        tse_real n = TSE_R(0.0);
        for (int j = 0; j < 6; ++j)
            n += x[j] * x[j];
        if (n > worst_norm) {
            worst_norm = n;
            worst = r;
        }
    }
    return worst;
}
