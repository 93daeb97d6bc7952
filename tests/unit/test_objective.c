/*
 * The objective as a sum of gradient-jet terms, and the tick -> seconds conversion.
 */
#include "test_support.h"
#include "internal/jet.h"
#include "internal/objective.h"
#include "tvo/tracking.h"

void setUp(void) {}
void tearDown(void) {}

/* Term adding a constant vector (k, 2k, ...) to the value coefficient of each gradient component. */
typedef struct {
    tvo_real_t k;
} const_term_t;

static tvo_status_t const_gradient_jet(const void *term, const tvo_jet_t *y, uint8_t dim, const tvo_time_jet_t *t,
                                       uint8_t order, tvo_jet_t *grad)
{
    const const_term_t *c = (const const_term_t *)term;
    (void)y;
    (void)t;
    (void)order;
    for (uint8_t i = 0; i < dim; ++i) {
        grad[i].c[0] += c->k * (tvo_real_t)(i + 1u);
    }
    return TVO_OK;
}

/* Term adding y(tau) itself (gradient of |y|^2 / 2). */
static tvo_status_t identity_gradient_jet(const void *term, const tvo_jet_t *y, uint8_t dim, const tvo_time_jet_t *t,
                                          uint8_t order, tvo_jet_t *grad)
{
    (void)term;
    (void)t;
    for (uint8_t i = 0; i < dim; ++i) {
        tvo_jet_add(&grad[i], &y[i], order, &grad[i]);
    }
    return TVO_OK;
}

static tvo_status_t failing_gradient_jet(const void *term, const tvo_jet_t *y, uint8_t dim, const tvo_time_jet_t *t,
                                         uint8_t order, tvo_jet_t *grad)
{
    (void)term;
    (void)y;
    (void)dim;
    (void)t;
    (void)order;
    (void)grad;
    return TVO_ERR_NOT_INITIALIZED;
}

static tvo_status_t inf_gradient_jet(const void *term, const tvo_jet_t *y, uint8_t dim, const tvo_time_jet_t *t,
                                     uint8_t order, tvo_jet_t *grad)
{
    (void)term;
    (void)y;
    (void)dim;
    (void)t;
    grad[dim - 1u].c[order] = TEST_INF;
    return TVO_OK;
}

static tvo_time_jet_t t_now(void)
{
    tvo_time_jet_t t = test_time_jet(TVO_R(0.5), TVO_R(1.0), 1000, 500);
    return t;
}

static void test_init_rejects_dimension_zero_and_above_maximum(void)
{
    tvo_objective_t obj;
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_objective_init(&obj, 0));
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_objective_init(&obj, (uint8_t)(TVO_MAX_OUTPUT_DIM + 1)));
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&obj, (uint8_t)TVO_MAX_OUTPUT_DIM));
    TEST_ASSERT_EQUAL_UINT8(TVO_MAX_OUTPUT_DIM, obj.dim);
    TEST_ASSERT_EQUAL_UINT8(0, obj.term_count);
}

static void test_add_term_stops_at_capacity(void)
{
    tvo_objective_t obj;
    const_term_t c = {TVO_R(1.0)};
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&obj, 2));
    for (int i = 0; i < TVO_MAX_TERMS; ++i) {
        ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&obj, const_gradient_jet, &c));
    }
    ASSERT_STATUS(TVO_ERR_CAPACITY, tvo_objective_add_term(&obj, const_gradient_jet, &c));
    TEST_ASSERT_EQUAL_UINT8(TVO_MAX_TERMS, obj.term_count);
}

static void test_add_term_rejects_null(void)
{
    tvo_objective_t obj;
    const_term_t c = {TVO_R(1.0)};
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&obj, 2));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_objective_add_term(NULL, const_gradient_jet, &c));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_objective_add_term(&obj, NULL, &c));
    TEST_ASSERT_EQUAL_UINT8(0, obj.term_count);
}

/* A term says what it is: a general term needs its gradient jet, a tracking term none (its slot keeps
 * the kind and the term, callbacks NULL, and the objective its target, which a step checks before its
 * law); another kind is refused, and nothing is appended then. */
static void test_add_dispatches_on_the_term_kind(void)
{
    tvo_objective_t obj;
    const_term_t c = {TVO_R(1.0)};
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&obj, 2));
    const tvo_term_t no_callback = {NULL, NULL, NULL, &c, TVO_TERM_GENERAL};
    ASSERT_STATUS(TVO_ERR_NULL, tvo_objective_add(&obj, &no_callback));
    const tvo_term_t unknown = {const_gradient_jet, NULL, NULL, &c, (uint8_t)(TVO_TERM_TRACKING + 1)};
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_objective_add(&obj, &unknown));
    TEST_ASSERT_EQUAL_UINT8(0, obj.term_count);
    tvo_target_t target;
    ASSERT_STATUS(TVO_OK, tvo_target_init_streamed(&target));
    tvo_tracking_term_t tracked;
    const tvo_real_t w[2] = {TVO_R(1.0), TVO_R(1.0)};
    ASSERT_STATUS(TVO_OK, tvo_tracking_init(&tracked, &target, w, 0u));
    const tvo_term_t tracking = {const_gradient_jet, NULL, NULL, &tracked, TVO_TERM_TRACKING};
    ASSERT_STATUS(TVO_OK, tvo_objective_add(&obj, &tracking));
    TEST_ASSERT_EQUAL_UINT8(TVO_TERM_TRACKING, obj.terms[0].kind);
    TEST_ASSERT_NULL(obj.terms[0].gradient_jet);
    TEST_ASSERT_EQUAL_PTR(&tracked, obj.terms[0].term);
    TEST_ASSERT_EQUAL_UINT8(1, obj.target_count);
    TEST_ASSERT_EQUAL_PTR(&target, obj.targets[0]);
    TEST_ASSERT_EQUAL_UINT8(1, obj.tracking_only);
    TEST_ASSERT_NOT_NULL(obj.general_path); /* the public add links the law's general path */
    const tvo_term_t general = {const_gradient_jet, NULL, NULL, &c, TVO_TERM_GENERAL};
    ASSERT_STATUS(TVO_OK, tvo_objective_add(&obj, &general));
    TEST_ASSERT_EQUAL_UINT8(TVO_TERM_GENERAL, obj.terms[1].kind);
    TEST_ASSERT_EQUAL_PTR(const_gradient_jet, obj.terms[1].gradient_jet);
    TEST_ASSERT_EQUAL_UINT8(0, obj.tracking_only);
    TEST_ASSERT_EQUAL_UINT8(1, obj.target_count); /* a term by its callbacks declares no target */
}

static void test_gradient_is_the_sum_of_the_terms(void)
{
    /* grad = y(tau) + (1, 2, 3) * 0.5 + (1, 2, 3) * -2 = y(tau) - 1.5 (1, 2, 3) in the value coefficient. */
    tvo_objective_t obj;
    const_term_t c1 = {TVO_R(0.5)};
    const_term_t c2 = {TVO_R(-2.0)};
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&obj, 3));
    ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&obj, const_gradient_jet, &c1));
    ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&obj, identity_gradient_jet, &c1));
    ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&obj, const_gradient_jet, &c2));
    tvo_jet_t y[3], g[3];
    for (int i = 0; i < 3; ++i) {
        tvo_jet_constant(TVO_R(0.0), &y[i]);
        for (int j = 0; j <= TVO_JET_MAX_ORDER; ++j) {
            y[i].c[j] = test_r(10.0 * i + j);
        }
        for (int j = 0; j <= TVO_JET_MAX_ORDER; ++j) {
            g[i].c[j] = TVO_R(999.0); /* must be cleared before summing */
        }
    }
    const tvo_time_jet_t t = t_now();
    ASSERT_STATUS(TVO_OK, tvo_objective_gradient_jet(&obj, y, &t, TVO_JET_MAX_ORDER, g));
    for (int i = 0; i < 3; ++i) {
        ASSERT_NEAR(10.0 * i - 1.5 * (i + 1), g[i].c[0], TEST_TOL(4, 30.0));
        for (int j = 1; j <= TVO_JET_MAX_ORDER; ++j) {
            ASSERT_NEAR(10.0 * i + j, g[i].c[j], TEST_TOL(4, 30.0));
        }
    }
}

static void test_gradient_reports_the_first_failing_term(void)
{
    tvo_objective_t obj;
    const_term_t c = {TVO_R(1.0)};
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&obj, 2));
    ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&obj, const_gradient_jet, &c));
    ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&obj, failing_gradient_jet, &c));
    ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&obj, inf_gradient_jet, &c));
    tvo_jet_t y[2], g[2];
    tvo_jet_constant(TVO_R(0.0), &y[0]);
    tvo_jet_constant(TVO_R(0.0), &y[1]);
    const tvo_time_jet_t t = t_now();
    ASSERT_STATUS(TVO_ERR_NOT_INITIALIZED, tvo_objective_gradient_jet(&obj, y, &t, 2, g));
}

static void test_gradient_reports_non_finite_sum(void)
{
    tvo_objective_t obj;
    const_term_t c = {TVO_R(1.0)};
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&obj, 2));
    ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&obj, const_gradient_jet, &c));
    ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&obj, inf_gradient_jet, &c));
    tvo_jet_t y[2], g[2];
    tvo_jet_constant(TVO_R(0.0), &y[0]);
    tvo_jet_constant(TVO_R(0.0), &y[1]);
    const tvo_time_jet_t t = t_now();
    ASSERT_STATUS(TVO_ERR_NUMERIC, tvo_objective_gradient_jet(&obj, y, &t, 2, g));
}

static void test_ticks_to_seconds_exact_cases(void)
{
    ASSERT_NEAR(2.5, tvo_ticks_to_seconds(2500u, 1000u), 0.0);
    ASSERT_NEAR(0.0, tvo_ticks_to_seconds(0u, 1000000u), 0.0);
    ASSERT_NEAR(0.005, tvo_ticks_to_seconds(5000u, 1000000u), TEST_TOL(1, 0.005));
    ASSERT_NEAR(3.0, tvo_ticks_to_seconds(3u, 1u), 0.0);
}

static void test_ticks_to_seconds_keeps_relative_precision_for_long_runs(void)
{
    /* 2^40 + 123456 ticks at 1 MHz = 1099511.751232 s: one rounding of the result at most. */
    const uint64_t ticks = (1ull << 40) + 123456u;
    const double expected = (double)ticks / 1e6;
    ASSERT_NEAR(expected, tvo_ticks_to_seconds(ticks, 1000000u), 1.0 * TEST_EPS * expected);
    /* Beyond 2^32 ticks (uint32 plant clock wrapped): still monotone and exact where representable. */
    ASSERT_NEAR(4294967.296, tvo_ticks_to_seconds(1ull << 32, 1000u), 1.0 * TEST_EPS * 4294967.296);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_init_rejects_dimension_zero_and_above_maximum);
    RUN_TEST(test_add_term_stops_at_capacity);
    RUN_TEST(test_add_term_rejects_null);
    RUN_TEST(test_add_dispatches_on_the_term_kind);
    RUN_TEST(test_gradient_is_the_sum_of_the_terms);
    RUN_TEST(test_gradient_reports_the_first_failing_term);
    RUN_TEST(test_gradient_reports_non_finite_sum);
    RUN_TEST(test_ticks_to_seconds_exact_cases);
    RUN_TEST(test_ticks_to_seconds_keeps_relative_precision_for_long_runs);
    return UNITY_END();
}
