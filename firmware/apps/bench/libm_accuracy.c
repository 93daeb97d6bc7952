/*
 * Accuracy of the core's own float32 functions against the exact values and against glibc's
 * (tools/agree --accuracy; host only, x86-64's 80-bit long double as the reference):
 *   tvo_expf, tvo_logf  every one of the 2^32 floats
 *   tvo_atan2f          2^26 argument pairs (random bits, the exponents within 2^-40 .. 2^40 of each
 *                       other's half of the time) and 2^20 directions at six radii
 * The exact value is glibc's expl, logl, atan2l (within an ulp of 2^-63); the float nearest it is the
 * correctly rounded result unless it lies within 2^-60 of a midpoint between two floats ("undecided":
 * not counted either way). Prints one JSON object:
 *   per function: arguments, not_nearest (results other than the nearest float), undecided, max_ulp
 *   (the largest |result - exact| in ulps of the result's binade), the same for glibc's expf, logf,
 *   atan2f, and differ_from_glibc; for expf also integer_path_differs (tvo_expf_integer, what
 *   soft-float targets run alone, against tvo_expf over its whole domain).
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "internal/exp_log.h"
#include "internal/trig.h"
#include "internal/real_bits.h"

#if LDBL_MANT_DIG < 64
#error "the reference needs a long double of 64 bits of precision or more (x86-64's)"
#endif

typedef struct {
    const char *name;
    unsigned long long arguments, not_nearest, undecided, glibc_not_nearest, differ_from_glibc, integer_path_differs;
    long double max_ulp, glibc_max_ulp;
} tally_t;

/* The spacing of floats at |nearest| (the nearest float to the exact value), subnormals included. */
static long double ulp_at(float nearest)
{
    const float magnitude = fabsf(nearest);
    const float next = nextafterf(magnitude, INFINITY);
    return (long double)next - (long double)magnitude;
}

/* 1 when exact lies within 2^-60 of a midpoint between nearest and a neighbour. */
static int undecided_at(long double exact, float nearest)
{
    if (nearest == 0.0f || isinf(nearest)) {
        return 0; /* far below half the smallest subnormal, or beyond overflow: decided */
    }
    const long double up = ((long double)nearest + (long double)nextafterf(nearest, INFINITY)) / 2.0L;
    const long double down = ((long double)nearest + (long double)nextafterf(nearest, -INFINITY)) / 2.0L;
    const long double distance = fminl(fabsl(exact - up), fabsl(exact - down));
    return distance < ldexpl(fabsl(exact), -60);
}

/* One result and glibc's against the exact value (not NaN). */
static void tally(tally_t *t, long double exact, float own, float glibc)
{
    ++t->arguments;
    const float nearest = (float)exact; /* one rounding of the long double: the nearest float to it */
    if (undecided_at(exact, nearest)) {
        ++t->undecided;
    } else {
        t->not_nearest += (float_bits(own) != float_bits(nearest)) ? 1u : 0u;
        t->glibc_not_nearest += (float_bits(glibc) != float_bits(nearest)) ? 1u : 0u;
    }
    t->differ_from_glibc += (float_bits(own) != float_bits(glibc)) ? 1u : 0u;
    if (isfinite(nearest) && isfinite(own) && isfinite(glibc)) {
        const long double ulp = ulp_at(nearest);
        const long double own_ulps = fabsl((long double)own - exact) / ulp;
        const long double glibc_ulps = fabsl((long double)glibc - exact) / ulp;
        t->max_ulp = own_ulps > t->max_ulp ? own_ulps : t->max_ulp;
        t->glibc_max_ulp = glibc_ulps > t->glibc_max_ulp ? glibc_ulps : t->glibc_max_ulp;
    } else {
        /* overflow: the nearest is inf; both must say so */
        t->not_nearest += (float_bits(own) != float_bits(nearest)) ? 1u : 0u;
    }
}

/* A NaN result where one is due (a NaN argument, log of a negative number). */
static void tally_nan(tally_t *t, float own, float glibc)
{
    ++t->arguments;
    t->not_nearest += isnan(own) ? 0u : 1u;
    t->glibc_not_nearest += isnan(glibc) ? 0u : 1u;
    t->differ_from_glibc += (isnan(own) != isnan(glibc)) ? 1u : 0u;
}

static void exp_every_float(tally_t *t)
{
    for (uint64_t u = 0; u <= 0xFFFFFFFFu; ++u) {
        const float x = float_from_bits((uint32_t)u);
        const float own = tvo_expf(x);
        if (isnan(x)) {
            tally_nan(t, own, expf(x));
            continue;
        }
        tally(t, expl((long double)x), own, expf(x));
        const uint32_t magnitude = (uint32_t)u & 0x7FFFFFFFu;
        if (magnitude >= 0x32800000u && magnitude < 0x42D00000u) { /* 2^-26 <= |x| < 104 */
            t->integer_path_differs += (float_bits(tvo_expf_integer(x)) != float_bits(own)) ? 1u : 0u;
        }
    }
}

static void log_every_float(tally_t *t)
{
    for (uint64_t u = 0; u <= 0xFFFFFFFFu; ++u) {
        const float x = float_from_bits((uint32_t)u);
        const float own = tvo_logf(x);
        if (isnan(x) || (x < 0.0f)) {
            tally_nan(t, own, logf(x));
            continue;
        }
        tally(t, logl((long double)x), own, logf(x));
    }
}

static uint32_t xorshift(uint32_t *state)
{
    *state ^= *state << 13;
    *state ^= *state >> 17;
    *state ^= *state << 5;
    return *state;
}

static void atan2_sweep(tally_t *t)
{
    uint32_t state = 2463534242u;
    for (uint32_t k = 0; k < (1u << 26); ++k) {
        uint32_t y_bits = xorshift(&state);
        uint32_t x_bits = xorshift(&state);
        if ((k & 1u) != 0u) { /* exponents near each other's: angles away from the axes */
            x_bits = (x_bits & 0x807FFFFFu) | ((((y_bits >> 23) & 0xFFu) + (x_bits % 9u) - 4u) & 0xFFu) << 23;
        }
        const float y = float_from_bits(y_bits);
        const float x = float_from_bits(x_bits);
        const float own = tvo_atan2f(y, x);
        if (isnan(y) || isnan(x)) {
            tally_nan(t, own, atan2f(y, x));
            continue;
        }
        tally(t, atan2l((long double)y, (long double)x), own, atan2f(y, x));
    }
    static const long double radii[6] = {1e-30L, 1e-3L, 1.0L, 7.5L, 1e4L, 1e30L};
    for (uint32_t i = 0; i < 6u; ++i) {
        for (uint32_t k = 0; k < (1u << 20); ++k) {
            const long double theta = ((long double)k / (long double)(1u << 20) - 0.5L) * 6.283185307179586476925L;
            const float y = (float)(radii[i] * sinl(theta));
            const float x = (float)(radii[i] * cosl(theta));
            tally(t, atan2l((long double)y, (long double)x), tvo_atan2f(y, x), atan2f(y, x));
        }
    }
}

static void print_tally(const tally_t *t, int last)
{
    (void)printf("    \"%s\": {\"arguments\": %llu, \"not_nearest\": %llu, \"undecided\": %llu, \"max_ulp\": %.4Lf, "
                 "\"glibc_not_nearest\": %llu, \"glibc_max_ulp\": %.4Lf, \"differ_from_glibc\": %llu",
                 t->name, t->arguments, t->not_nearest, t->undecided, t->max_ulp, t->glibc_not_nearest,
                 t->glibc_max_ulp, t->differ_from_glibc);
    if (strcmp(t->name, "tvo_expf") == 0) {
        (void)printf(", \"integer_path_differs\": %llu", t->integer_path_differs);
    }
    (void)printf("}%s\n", last ? "" : ",");
}

int main(void)
{
    tally_t exp_tally = {.name = "tvo_expf"};
    tally_t log_tally = {.name = "tvo_logf"};
    tally_t atan2_tally = {.name = "tvo_atan2f"};
    exp_every_float(&exp_tally);
    log_every_float(&log_tally);
    atan2_sweep(&atan2_tally);
    (void)printf("{\n  \"reference\": \"glibc's expl, logl, atan2l in x86-64's 80-bit long double; tvo_expf and "
                 "tvo_logf over all 2^32 floats, tvo_atan2f over %u argument pairs\",\n  \"functions\": {\n",
                 (unsigned)atan2_tally.arguments);
    print_tally(&exp_tally, 0);
    print_tally(&log_tally, 0);
    print_tally(&atan2_tally, 1);
    (void)printf("  }\n}\n");
    const unsigned long long wrong = exp_tally.not_nearest + log_tally.not_nearest + exp_tally.integer_path_differs;
    return wrong == 0u ? 0 : 1;
}
