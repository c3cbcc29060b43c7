/* What the C drivers of compare.sh measure with: a monotonic clock and the peak resident
 * memory of the process. */
#ifndef STICTION_BENCH_MEASURE_H
#define STICTION_BENCH_MEASURE_H
#include <sys/resource.h>
#include <time.h>

static double now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

/* Peak resident memory in MB (Linux reports kilobytes). */
static double peak_rss_mb(void) {
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return u.ru_maxrss / 1024.0;
}
#endif
