/* The MUMPS side of benches/linear-solvers/compare.sh (a benchmark, not a test).
 *
 *   mumps_driver MATRIX.mtx ORDERING REPEATS
 *
 * Compiled twice: as is (dmumps, double precision) and with -DSINGLE (smumps, a single-precision
 * factor whose solves are refined in double precision, x += A^-1 (b - A x) with the residual in
 * double, until ||b - A x|| <= 1e-12 ||b||: what Stiction's single-precision factor does).
 * Reads a symmetric Matrix Market file (one triangle), analyses it once (ORDERING: "auto",
 * MUMPS's choice, ICNTL(7) = 7; "scotch"; "pord"; "amd"; "amf"; "qamd"), factors it REPEATS
 * times as a symmetric positive definite matrix (SYM = 1) and solves A x = b with b = A 1.
 * Prints one JSON line like the other drivers'. Sequential MUMPS: threads are the BLAS's
 * (OPENBLAS_NUM_THREADS). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "measure.h"

#ifdef SINGLE
#include <smumps_c.h>
typedef float real;
typedef SMUMPS_STRUC_C Mumps;
#define RUN_MUMPS smumps_c
#define PRECISION "Single"
#else
#include <dmumps_c.h>
typedef double real;
typedef DMUMPS_STRUC_C Mumps;
#define RUN_MUMPS dmumps_c
#define PRECISION "Double"
#endif

#define ICNTL(i) icntl[(i) - 1]
#define INFOG(i) infog[(i) - 1]

/* y = A x for the symmetric matrix stored as one triangle (1-based coordinates). */
static void multiply(long nnz, const int *row, const int *col, const double *a, const double *x, double *y, int n) {
    for (int i = 0; i < n; i++) y[i] = 0;
    for (long k = 0; k < nnz; k++) {
        int i = row[k] - 1, j = col[k] - 1;
        y[i] += a[k] * x[j];
        if (i != j) y[j] += a[k] * x[i];
    }
}

static double norm(const double *v, int n) {
    double s = 0;
    for (int i = 0; i < n; i++) s += v[i] * v[i];
    return sqrt(s);
}

static int ordering_code(const char *name) {
    const char *names[] = {"amd", "", "amf", "scotch", "pord", "metis", "qamd", "auto"};
    for (int k = 0; k < 8; k++)
        if (names[k][0] && strcmp(name, names[k]) == 0) return k;
    return -1;
}

static void check(const Mumps *id, const char *phase) {
    if (id->INFOG(1) < 0) {
        fprintf(stderr, "MUMPS %s failed: INFOG(1) = %d, INFOG(2) = %d\n", phase, id->INFOG(1), id->INFOG(2));
        exit(1);
    }
}

int main(int argc, char **argv) {
    if (argc != 4) {
        fprintf(stderr, "usage: %s MATRIX.mtx auto|scotch|pord|amd|amf|qamd REPEATS\n", argv[0]);
        return 2;
    }
    int ordering = ordering_code(argv[2]);
    if (ordering < 0) {
        fprintf(stderr, "ordering `%s`: expected auto, scotch, pord, amd, amf or qamd\n", argv[2]);
        return 2;
    }
    int repeats = atoi(argv[3]);
    if (repeats < 1) repeats = 1;

    double t = now();
    FILE *f = fopen(argv[1], "r");
    if (!f) {
        perror(argv[1]);
        return 2;
    }
    char line[1100];
    if (!fgets(line, sizeof line, f) || !strstr(line, "coordinate real symmetric")) {
        fprintf(stderr, "%s: expected a `coordinate real symmetric` Matrix Market header\n", argv[1]);
        return 2;
    }
    do {
        if (!fgets(line, sizeof line, f)) {
            fprintf(stderr, "%s: no size line\n", argv[1]);
            return 2;
        }
    } while (line[0] == '%');
    int n, m;
    long nnz;
    if (sscanf(line, "%d %d %ld", &n, &m, &nnz) != 3 || n != m) {
        fprintf(stderr, "%s: expected `N N ENTRIES` for a square matrix\n", argv[1]);
        return 2;
    }
    int *row = malloc(nnz * sizeof *row), *col = malloc(nnz * sizeof *col);
    double *a = malloc(nnz * sizeof *a);
    real *a_mumps = malloc(nnz * sizeof *a_mumps);
    for (long k = 0; k < nnz; k++) {
        if (fscanf(f, "%d %d %lf", &row[k], &col[k], &a[k]) != 3) {
            fprintf(stderr, "%s: entry %ld of %ld unreadable\n", argv[1], k + 1, nnz);
            return 2;
        }
        a_mumps[k] = (real)a[k];
    }
    fclose(f);
    double read = now() - t;

    Mumps id;
    memset(&id, 0, sizeof id);
    id.comm_fortran = -987654; /* USE_COMM_WORLD of the sequential library's MPI stub */
    id.par = 1;
    id.sym = 1;
    id.job = -1;
    RUN_MUMPS(&id);
    check(&id, "initialization");
    id.ICNTL(1) = -1;
    id.ICNTL(2) = -1;
    id.ICNTL(3) = -1;
    id.ICNTL(4) = 0;
    id.ICNTL(7) = ordering;
    id.n = n;
    id.nnz = nnz;
    id.irn = row;
    id.jcn = col;
    id.a = a_mumps;

    t = now();
    id.job = 1;
    RUN_MUMPS(&id);
    check(&id, "analysis");
    double analyse = now() - t;
    double factorize = INFINITY;
    for (int k = 0; k < repeats; k++) {
        t = now();
        id.job = 2;
        RUN_MUMPS(&id);
        check(&id, "factorization");
        double dt = now() - t;
        if (dt < factorize) factorize = dt;
    }

    double *ones = malloc(n * sizeof *ones), *b = malloc(n * sizeof *b), *x = calloc(n, sizeof *x);
    double *r = malloc(n * sizeof *r), *ax = malloc(n * sizeof *ax);
    real *rhs = malloc(n * sizeof *rhs);
    for (int i = 0; i < n; i++) ones[i] = 1;
    multiply(nnz, row, col, a, ones, b, n);
    double b_norm = norm(b, n), residual = 1;
    int solves = 0;
    id.rhs = rhs;
    id.nrhs = 1;
    id.lrhs = n;
    t = now();
    /* one solve in double precision; refined solves with a single-precision factor */
    for (; solves < 10 && residual > 1e-12; solves++) {
        multiply(nnz, row, col, a, x, ax, n);
        for (int i = 0; i < n; i++) {
            r[i] = b[i] - ax[i];
            rhs[i] = (real)r[i];
        }
        residual = norm(r, n) / b_norm;
        if (residual <= 1e-12) break;
        id.job = 3;
        RUN_MUMPS(&id);
        check(&id, "solve");
        for (int i = 0; i < n; i++) x[i] += rhs[i];
#ifndef SINGLE
        solves++;
        break;
#endif
    }
    double solve = now() - t;
    multiply(nnz, row, col, a, x, ax, n);
    for (int i = 0; i < n; i++) r[i] = b[i] - ax[i];
    residual = norm(r, n) / b_norm;
    double error = 0;
    for (int i = 0; i < n; i++)
        if (fabs(x[i] - 1) > error) error = fabs(x[i] - 1);
    const char *names[] = {"amd", "given", "amf", "scotch", "pord", "metis", "qamd", "auto"};
    int used = id.INFOG(7);
    /* INFOG(29): entries in the factors; a negative value counts millions */
    double entries = id.INFOG(29) >= 0 ? id.INFOG(29) : -1e6 * id.INFOG(29);
    printf("{\"solver\": \"mumps\", \"version\": \"%s\", \"equations\": %d, \"ordering\": \"%s\", "
           "\"precision\": \"%s\", \"read_s\": %.6f, \"analyse_s\": %.6f, \"factorize_s\": %.6f, "
           "\"solve_s\": %.6f, \"solves\": %d, \"factor_entries\": %.0f, \"mumps_memory_mb\": %d, "
           "\"residual\": %.3e, \"max_error\": %.3e, \"peak_rss_mb\": %.1f}\n",
           id.version_number, n, used >= 0 && used < 8 ? names[used] : "?", PRECISION, read, analyse, factorize,
           solve, solves, entries, id.INFOG(22), residual, error, peak_rss_mb());
    id.job = -2;
    RUN_MUMPS(&id);
    return 0;
}
