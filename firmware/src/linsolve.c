/* Fixed-size Cholesky solve; see tvo/linsolve.h. */
#include "tvo/linsolve.h"

tvo_status_t tvo_cholesky_solve(tvo_real_t a[TVO_MAX_OUTPUT_DIM][TVO_MAX_OUTPUT_DIM], uint8_t n,
                                const tvo_real_t *b, tvo_real_t *x)
{
    if (a == NULL || b == NULL || x == NULL) {
        return TVO_ERR_NULL;
    }
    if (n == 0u || n > TVO_MAX_OUTPUT_DIM) {
        return TVO_ERR_DIMENSION;
    }
    /* A pivot must exceed this fraction of the largest diagonal entry: a relative test, so
     * the verdict does not depend on the objective's scale. */
    tvo_real_t max_diag = TVO_R(0.0);
    for (uint8_t i = 0; i < n; ++i) {
        if (!isfinite(a[i][i])) {
            return TVO_ERR_NOT_FINITE;
        }
        if (a[i][i] > max_diag) {
            max_diag = a[i][i];
        }
    }
    const tvo_real_t pivot_floor = max_diag * TVO_R(64.0) * TVO_EPSILON;
    if (!(max_diag > TVO_R(0.0))) {
        return TVO_ERR_NOT_POSITIVE_DEFINITE;
    }
    for (uint8_t j = 0; j < n; ++j) {
        tvo_real_t d = a[j][j];
        for (uint8_t k = 0; k < j; ++k) {
            d -= a[j][k] * a[j][k];
        }
        if (!(d > pivot_floor)) {
            return TVO_ERR_NOT_POSITIVE_DEFINITE;
        }
        const tvo_real_t l_jj = TVO_SQRT(d);
        a[j][j] = l_jj;
        for (uint8_t i = (uint8_t)(j + 1u); i < n; ++i) {
            tvo_real_t s = a[i][j];
            for (uint8_t k = 0; k < j; ++k) {
                s -= a[i][k] * a[j][k];
            }
            a[i][j] = s / l_jj;
        }
    }
    /* Forward (L z = b) then backward (L^T x = z) substitution, in place in x. */
    for (uint8_t i = 0; i < n; ++i) {
        tvo_real_t s = b[i];
        for (uint8_t k = 0; k < i; ++k) {
            s -= a[i][k] * x[k];
        }
        x[i] = s / a[i][i];
    }
    for (uint8_t ii = n; ii > 0u; --ii) {
        const uint8_t i = (uint8_t)(ii - 1u);
        tvo_real_t s = x[i];
        for (uint8_t k = (uint8_t)(i + 1u); k < n; ++k) {
            s -= a[k][i] * x[k];
        }
        x[i] = s / a[i][i];
    }
    for (uint8_t i = 0; i < n; ++i) {
        if (!isfinite(x[i])) {
            return TVO_ERR_NUMERIC;
        }
    }
    return TVO_OK;
}
