/* The CHOLMOD side of benches/linear-solvers/compare.sh (a benchmark, not a test).
 *
 *   cholmod_driver MATRIX.mtx ORDERING REPEATS
 *
 * Reads a symmetric Matrix Market file, analyses it once (ORDERING: "default", CHOLMOD's own
 * choice of AMD and METIS; "metis"; "amd"), factors it REPEATS times (supernodal LL^T, double
 * precision: the SuiteSparse of Debian 12 has no single-precision factor) and solves
 * A x = b with b = A 1. Prints one JSON line: times (the factorization's best of REPEATS),
 * the factor's stored entries (the supernodal blocks, L->xsize) and nnz(L), the relative
 * residual, the error against 1, and the peak resident memory of the process. Threads: the
 * BLAS's (OPENBLAS_NUM_THREADS). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "measure.h"
#include <suitesparse/cholmod.h>

int main(int argc, char **argv) {
    if (argc != 4) {
        fprintf(stderr, "usage: %s MATRIX.mtx default|metis|amd REPEATS\n", argv[0]);
        return 2;
    }
    const char *ordering = argv[2];
    int repeats = atoi(argv[3]);
    if (repeats < 1) repeats = 1;
    cholmod_common c;
    cholmod_start(&c);
    c.supernodal = CHOLMOD_SUPERNODAL;
    if (strcmp(ordering, "metis") == 0) {
        c.nmethods = 1;
        c.method[0].ordering = CHOLMOD_METIS;
        c.postorder = 1;
    } else if (strcmp(ordering, "amd") == 0) {
        c.nmethods = 1;
        c.method[0].ordering = CHOLMOD_AMD;
        c.postorder = 1;
    } else if (strcmp(ordering, "default") != 0) {
        fprintf(stderr, "ordering `%s`: expected default, metis or amd\n", ordering);
        return 2;
    }
    double t = now();
    FILE *f = fopen(argv[1], "r");
    if (!f) {
        perror(argv[1]);
        return 2;
    }
    cholmod_sparse *A = cholmod_read_sparse(f, &c);
    fclose(f);
    if (!A || A->stype == 0) {
        fprintf(stderr, "%s: not a symmetric Matrix Market matrix\n", argv[1]);
        return 2;
    }
    double read = now() - t;

    t = now();
    cholmod_factor *L = cholmod_analyze(A, &c);
    double analyse = now() - t;
    if (!L) {
        fprintf(stderr, "cholmod_analyze failed (status %d)\n", c.status);
        return 1;
    }
    double factorize = INFINITY;
    for (int k = 0; k < repeats; k++) {
        t = now();
        cholmod_factorize(A, L, &c);
        double dt = now() - t;
        if (dt < factorize) factorize = dt;
        if (c.status != CHOLMOD_OK) {
            fprintf(stderr, "cholmod_factorize: status %d (not positive definite at column %zu?)\n", c.status, L->minor);
            return 1;
        }
    }

    cholmod_dense *ones = cholmod_ones(A->nrow, 1, CHOLMOD_REAL, &c);
    cholmod_dense *b = cholmod_zeros(A->nrow, 1, CHOLMOD_REAL, &c);
    double alpha[2] = {1, 0}, beta[2] = {0, 0};
    cholmod_sdmult(A, 0, alpha, beta, ones, b, &c);
    t = now();
    cholmod_dense *x = cholmod_solve(CHOLMOD_A, L, b, &c);
    double solve = now() - t;

    /* r = b - A x */
    cholmod_dense *r = cholmod_copy_dense(b, &c);
    double minus[2] = {-1, 0}, one[2] = {1, 0};
    cholmod_sdmult(A, 0, minus, one, x, r, &c);
    double residual = cholmod_norm_dense(r, 2, &c) / cholmod_norm_dense(b, 2, &c);
    double error = 0;
    for (size_t i = 0; i < A->nrow; i++) {
        double e = fabs(((double *)x->x)[i] - 1.0);
        if (e > error) error = e;
    }
    const char *names[] = {"natural", "given", "amd", "metis", "nesdis", "colamd", "nesdis", "postordered"};
    int method = c.method[c.selected].ordering;
    printf("{\"solver\": \"cholmod\", \"version\": \"%d.%d.%d\", \"equations\": %zu, \"ordering\": \"%s\", "
           "\"precision\": \"Double\", \"supernodal\": %s, \"read_s\": %.6f, \"analyse_s\": %.6f, "
           "\"factorize_s\": %.6f, \"solve_s\": %.6f, \"factor_entries\": %zu, \"lnz\": %.0f, "
           "\"residual\": %.3e, \"max_error\": %.3e, \"peak_rss_mb\": %.1f}\n",
           CHOLMOD_MAIN_VERSION, CHOLMOD_SUB_VERSION, CHOLMOD_SUBSUB_VERSION, A->nrow,
           method >= 0 && method < 8 ? names[method] : "?", L->is_super ? "true" : "false", read, analyse,
           factorize, solve, L->is_super ? L->xsize : L->nzmax, c.lnz, residual, error, peak_rss_mb());
    cholmod_free_dense(&r, &c);
    cholmod_free_dense(&x, &c);
    cholmod_free_dense(&b, &c);
    cholmod_free_dense(&ones, &c);
    cholmod_free_factor(&L, &c);
    cholmod_free_sparse(&A, &c);
    cholmod_finish(&c);
    return 0;
}
