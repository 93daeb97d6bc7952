/*
 * An objective of tvo_tracking_add's terms: the law evaluates it by its tracking path alone, and the
 * objective does not reference the general path (a firmware that adds nothing else does not link it).
 * The same terms added through tvo_objective_add (closed form, general path linked) are the reference:
 * on random states, times and every target kind, both give the same command, gradient rows and
 * regularisation to the bit, and for every input the law refuses, the same status with y_k zeroed.
 * The one difference, an output no term covers, is refused here where the general path regularises.
 */
#include <stdint.h>
#include <string.h>

#include "test_support.h"
#include "tvo/law.h"
#include "tvo/tracking.h"
#include "internal/law.h"
#include "unity.h"

void setUp(void);
void tearDown(void);
void setUp(void) {}
void tearDown(void) {}

#define TARGET_KINDS 4u
#define TICK_HZ 1000u

typedef struct {
    tvo_target_t target[TVO_MAX_ROBOTS];
    tvo_tracking_term_t term[TVO_MAX_ROBOTS];
    tvo_objective_t tracking_only; /* terms by tvo_tracking_add */
    tvo_objective_t general;       /* the same terms by tvo_objective_add, closed form */
    tvo_law_t law;
} pair_t;

static pair_t pair;
static tvo_law_workspace_t work;

static uint32_t lcg_state = 12345u;
static double uniform(double lo, double hi)
{
    lcg_state = lcg_state * 1664525u + 1013904223u;
    return lo + (hi - lo) * (double)(lcg_state >> 8) / (double)(1u << 24);
}

/* A target of the given kind (0 polynomial, 1 ellipse, 2 circle, 3 streamed with one sample at t = 0). */
static void make_target(tvo_target_t *target, unsigned kind)
{
    switch (kind) {
    case 0u:
        fx_line_target(target, uniform(-2.0, 2.0), uniform(-2.0, 2.0), uniform(-1.0, 1.0), uniform(-1.0, 1.0));
        break;
    case 1u: {
        const tvo_target_ellipse_t ellipse = {{test_r(uniform(-1.0, 1.0)), test_r(uniform(-1.0, 1.0))},
                                              {test_r(uniform(0.5, 2.0)), test_r(uniform(0.5, 2.0))},
                                              test_r(uniform(-1.0, 1.0)), test_r(uniform(-3.0, 3.0)),
                                              test_r(uniform(-1.0, 1.0)), 0u};
        ASSERT_STATUS(TVO_OK, tvo_target_init_ellipse(target, &ellipse));
        break;
    }
    case 2u:
        fx_circle_target(target, uniform(-1.0, 1.0), uniform(-1.0, 1.0), uniform(0.5, 2.0), uniform(-2.0, 2.0));
        break;
    default: {
        tvo_real_t deriv[TVO_STREAM_MAX_DERIV + 1][2];
        for (unsigned j = 0; j <= TVO_STREAM_MAX_DERIV; ++j) {
            deriv[j][0] = test_r(uniform(-1.0, 1.0));
            deriv[j][1] = test_r(uniform(-1.0, 1.0));
        }
        ASSERT_STATUS(TVO_OK, tvo_target_init_streamed(target));
        ASSERT_STATUS(TVO_OK, tvo_target_stream_update(target, 0u, TEST_CONST_STREAM(deriv)));
        break;
    }
    }
}

/* Both objectives over `robots` robots (targets of kind `kind`, random weights) and a law of order k. */
static void make_pair(uint8_t robots, unsigned kind, uint8_t k)
{
    memset(&pair, 0, sizeof(pair));
    const uint8_t m = (uint8_t)(2u * robots);
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&pair.tracking_only, m));
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&pair.general, m));
    for (uint8_t r = 0; r < robots; ++r) {
        const tvo_real_t w[2] = {test_r(uniform(0.2, 5.0)), test_r(uniform(0.2, 5.0))};
        make_target(&pair.target[r], kind);
        ASSERT_STATUS(TVO_OK, tvo_tracking_init(&pair.term[r], &pair.target[r], w, (uint8_t)(2u * r)));
        ASSERT_STATUS(TVO_OK, tvo_tracking_add(&pair.tracking_only, &pair.term[r]));
        const tvo_term_t spec = {tvo_tracking_gradient_jet, tvo_tracking_gradient_hessian, NULL, &pair.term[r], TVO_TERM_TRACKING};
        ASSERT_STATUS(TVO_OK, tvo_objective_add(&pair.general, &spec));
    }
    TEST_ASSERT_NULL(pair.tracking_only.general_path);
    TEST_ASSERT_NOT_NULL(pair.general.general_path);
    const tvo_real_t gains[3] = {TVO_R(6.0), TVO_R(11.0), TVO_R(6.0)}; /* (s+1)(s+2)(s+3), Hurwitz for k <= 3 */
    const tvo_real_t gains2[2] = {TVO_R(25.0), TVO_R(10.0)};
    const tvo_real_t gains1[1] = {TVO_R(3.0)};
    const tvo_real_t *gain = k == 3u ? gains : (k == 2u ? gains2 : gains1);
    tvo_law_init(&pair.law, k, m, gain);
}

typedef struct {
    tvo_status_t status;
    tvo_real_t y_k[TVO_MAX_Z_DIM];
    tvo_real_t gradient[TVO_MAX_Z_DIM];
    tvo_real_t gradient_rate[TVO_MAX_Z_DIM];
    tvo_real_t regularization;
} outcome_t;

/* The controllers' entry, with y_k preset to garbage so a refusal must zero it. */
static outcome_t evaluate(const tvo_objective_t *objective, const tvo_output_derivs_t *y, const tvo_time_jet_t *t)
{
    outcome_t out;
    memset(&out, 0, sizeof(out));
    for (unsigned i = 0; i < TVO_MAX_Z_DIM; ++i) {
        out.y_k[i] = TVO_R(123.0);
    }
    tvo_law_report_t report = {out.gradient, out.gradient_rate, objective->primal_dim, TVO_R(-1.0)};
    out.status = tvo_law_evaluate_report(&pair.law, objective, y, t, out.y_k, &report, &work);
    out.regularization = report.regularization;
    return out;
}

static void assert_same_outcome(const outcome_t *a, const outcome_t *b, uint8_t m)
{
    ASSERT_STATUS(b->status, a->status);
    TEST_ASSERT_EQUAL_MEMORY(b->y_k, a->y_k, m * sizeof(tvo_real_t));
    TEST_ASSERT_EQUAL_MEMORY(&b->regularization, &a->regularization, sizeof(tvo_real_t));
    if (a->status == TVO_OK) {
        TEST_ASSERT_EQUAL_MEMORY(b->gradient, a->gradient, m * sizeof(tvo_real_t));
        TEST_ASSERT_EQUAL_MEMORY(b->gradient_rate, a->gradient_rate, m * sizeof(tvo_real_t));
    } else {
        for (unsigned i = 0; i < m; ++i) {
            ASSERT_NEAR(0.0, a->y_k[i], 0.0); /* a refusal leaves a safe (zero) output */
        }
    }
}

static void random_state(tvo_output_derivs_t *y, uint8_t m)
{
    memset(y, 0, sizeof(*y));
    for (unsigned j = 0; j < TVO_MAX_RELATIVE_DEGREE; ++j) {
        for (unsigned i = 0; i < m; ++i) {
            y->d[j][i] = test_r(uniform(-3.0, 3.0));
        }
    }
}

static tvo_time_jet_t random_time(void)
{
    const uint64_t ticks = (uint64_t)uniform(0.0, 100000.0);
    return test_time_jet(test_r((double)ticks / TICK_HZ), TVO_R(1.0), TICK_HZ, ticks);
}

/* A unit circle's tracking term for robot 0. */
static void circle_term(tvo_target_t *target, tvo_tracking_term_t *term)
{
    const tvo_real_t w[2] = {TVO_R(1.0), TVO_R(2.0)};
    fx_circle_target(target, 0.0, 0.0, 1.0, 0.5);
    ASSERT_STATUS(TVO_OK, tvo_tracking_init(term, target, w, 0u));
}

static void test_tracking_add_checks_its_inputs_and_writes_nothing_when_it_refuses(void)
{
    tvo_objective_t objective;
    tvo_target_t target;
    tvo_tracking_term_t term;
    circle_term(&target, &term);

    memset(&objective, 0, sizeof(objective));
    ASSERT_STATUS(TVO_ERR_NOT_INITIALIZED, tvo_tracking_add(&objective, &term)); /* objective not initialised */
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&objective, 2u));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_tracking_add(NULL, &term));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_tracking_add(&objective, NULL));
    tvo_tracking_term_t blank;
    memset(&blank, 0, sizeof(blank));
    ASSERT_STATUS(TVO_ERR_NOT_INITIALIZED, tvo_tracking_add(&objective, &blank)); /* no target */
    blank = term;
    blank.weight[1] = TEST_NAN;
    ASSERT_STATUS(TVO_ERR_NOT_INITIALIZED, tvo_tracking_add(&objective, &blank)); /* not by tvo_tracking_init */
    blank = term;
    blank.weight[0] = TVO_R(0.0);
    ASSERT_STATUS(TVO_ERR_NOT_INITIALIZED, tvo_tracking_add(&objective, &blank));
    blank = term;
    blank.offset = 2u; /* a second robot's output in a one-robot objective */
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_tracking_add(&objective, &blank));
    TEST_ASSERT_EQUAL_UINT8(0u, objective.term_count);
    TEST_ASSERT_EQUAL_UINT8(0u, objective.tracking_only);

    for (unsigned n = 0; n < TVO_MAX_TERMS; ++n) {
        ASSERT_STATUS(TVO_OK, tvo_tracking_add(&objective, &term));
    }
    ASSERT_STATUS(TVO_ERR_CAPACITY, tvo_tracking_add(&objective, &term));
    TEST_ASSERT_EQUAL_UINT8(TVO_MAX_TERMS, objective.term_count);
    TEST_ASSERT_EQUAL_UINT8(1u, objective.tracking_only);
    TEST_ASSERT_NULL(objective.general_path); /* nothing added it */
}

static void test_the_general_add_functions_link_the_general_path(void)
{
    tvo_objective_t objective;
    tvo_target_t target;
    tvo_tracking_term_t term;
    circle_term(&target, &term);
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&objective, 2u));
    ASSERT_STATUS(TVO_OK, tvo_tracking_add(&objective, &term));
    TEST_ASSERT_NULL(objective.general_path);
    ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&objective, tvo_tracking_gradient_jet, &term));
    TEST_ASSERT_NOT_NULL(objective.general_path);
    TEST_ASSERT_EQUAL_UINT8(0u, objective.tracking_only); /* a term without its closed form */
    /* A refused add links nothing. */
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&objective, 2u));
    TEST_ASSERT_NULL(objective.general_path);
    ASSERT_STATUS(TVO_ERR_NULL, tvo_objective_add_term(&objective, NULL, &term));
    TEST_ASSERT_NULL(objective.general_path);
}

/* Random states and times, every target kind, each order the build holds, one robot and (where the
 * build allows) two: the same outcome to the bit. */
static void test_tracking_terms_alone_evaluate_as_the_general_add_does_bit_for_bit(void)
{
    tvo_output_derivs_t y;
    unsigned compared = 0u;
    for (uint8_t robots = 1u; robots <= 2u && robots <= TVO_MAX_ROBOTS; ++robots) {
        for (uint8_t k = 1u; k <= TVO_MAX_RELATIVE_DEGREE; ++k) {
            for (unsigned kind = 0u; kind < TARGET_KINDS; ++kind) {
                make_pair(robots, kind, k);
                for (unsigned n = 0; n < 40u; ++n) {
                    random_state(&y, pair.law.dim);
                    const tvo_time_jet_t t = random_time();
                    const outcome_t a = evaluate(&pair.tracking_only, &y, &t);
                    const outcome_t b = evaluate(&pair.general, &y, &t);
                    ASSERT_STATUS(TVO_OK, b.status);
                    assert_same_outcome(&a, &b, pair.law.dim);
                    ++compared;
                }
            }
        }
    }
    TEST_ASSERT_TRUE(compared >= 40u * TVO_MAX_RELATIVE_DEGREE * TARGET_KINDS);
}

/* Every refusal the law makes for such an objective: the general path's status, y_k zeroed. */
static void test_tracking_terms_alone_refuse_what_the_general_path_refuses_with_its_status(void)
{
    tvo_output_derivs_t y;
    const uint8_t k = 2u;
    make_pair(1u, 2u, k);
    const tvo_time_jet_t good = random_time();
    random_state(&y, 2u);

    tvo_time_jet_t t = good;
    t.t_s = TEST_NAN;
    outcome_t a = evaluate(&pair.tracking_only, &y, &t);
    outcome_t b = evaluate(&pair.general, &y, &t);
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, b.status);
    assert_same_outcome(&a, &b, 2u);
    t = good;
    t.rate = TEST_INF;
    a = evaluate(&pair.tracking_only, &y, &t);
    b = evaluate(&pair.general, &y, &t);
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, b.status);
    assert_same_outcome(&a, &b, 2u);

    for (unsigned j = 0; j < k; ++j) { /* a derivative that is not finite, at each order the law reads */
        random_state(&y, 2u);
        y.d[j][1] = TEST_INF;
        a = evaluate(&pair.tracking_only, &y, &good);
        b = evaluate(&pair.general, &y, &good);
        ASSERT_STATUS(TVO_ERR_NOT_FINITE, b.status);
        assert_same_outcome(&a, &b, 2u);
    }

    /* A term whose target went missing, and the same with a non-finite state: the state is checked first. */
    random_state(&y, 2u);
    pair.term[0].target = NULL;
    a = evaluate(&pair.tracking_only, &y, &good);
    b = evaluate(&pair.general, &y, &good);
    ASSERT_STATUS(TVO_ERR_NULL, b.status);
    assert_same_outcome(&a, &b, 2u);
    y.d[0][0] = TEST_NAN;
    a = evaluate(&pair.tracking_only, &y, &good);
    b = evaluate(&pair.general, &y, &good);
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, b.status);
    assert_same_outcome(&a, &b, 2u);
    pair.term[0].target = &pair.target[0];

    /* A term moved past the objective's outputs. */
    random_state(&y, 2u);
    pair.term[0].offset = 2u;
    a = evaluate(&pair.tracking_only, &y, &good);
    b = evaluate(&pair.general, &y, &good);
    ASSERT_STATUS(TVO_ERR_DIMENSION, b.status);
    assert_same_outcome(&a, &b, 2u);
    pair.term[0].offset = 0u;

    /* A gradient that overflows: weights and a state near the type's range. */
    const tvo_real_t big = (tvo_real_t)(sizeof(tvo_real_t) == sizeof(float) ? 1e30 : 1e200);
    pair.term[0].weight[0] = big;
    y.d[0][0] = big;
    a = evaluate(&pair.tracking_only, &y, &good);
    b = evaluate(&pair.general, &y, &good);
    ASSERT_STATUS(TVO_ERR_NUMERIC, b.status);
    assert_same_outcome(&a, &b, 2u);

    /* A slot whose term was set to NULL by hand: refused by the term's checks, not called through. */
    random_state(&y, 2u);
    pair.term[0].weight[0] = TVO_R(1.0);
    pair.tracking_only.terms[0].term = NULL;
    pair.general.terms[0].term = NULL;
    a = evaluate(&pair.tracking_only, &y, &good);
    b = evaluate(&pair.general, &y, &good);
    ASSERT_STATUS(TVO_ERR_NULL, b.status);
    assert_same_outcome(&a, &b, 2u);
    pair.tracking_only.terms[0].term = &pair.term[0];
    pair.general.terms[0].term = &pair.term[0];

    /* A curvature that overflows with a finite gradient: two terms near the type's largest weight on
     * the same output, the state exactly on a still target (every error 0). */
    tvo_objective_t heavy_alone;
    tvo_objective_t heavy_general;
    tvo_tracking_term_t heavy;
    const tvo_real_t huge = (tvo_real_t)(sizeof(tvo_real_t) == sizeof(float) ? 2.5e38 : 1.3e308);
    const tvo_real_t huge_w[2] = {huge, huge};
    fx_line_target(&pair.target[0], 0.5, -0.25, 0.0, 0.0);
    ASSERT_STATUS(TVO_OK, tvo_tracking_init(&heavy, &pair.target[0], huge_w, 0u));
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&heavy_alone, 2u));
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&heavy_general, 2u));
    const tvo_term_t heavy_spec = {tvo_tracking_gradient_jet, tvo_tracking_gradient_hessian, NULL, &heavy, TVO_TERM_TRACKING};
    for (unsigned n = 0; n < 2u; ++n) {
        ASSERT_STATUS(TVO_OK, tvo_tracking_add(&heavy_alone, &heavy));
        ASSERT_STATUS(TVO_OK, tvo_objective_add(&heavy_general, &heavy_spec));
    }
    memset(&y, 0, sizeof(y));
    y.d[0][0] = TVO_R(0.5);
    y.d[0][1] = TVO_R(-0.25);
    a = evaluate(&heavy_alone, &y, &good);
    b = evaluate(&heavy_general, &y, &good);
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, b.status);
    assert_same_outcome(&a, &b, 2u);

    /* A streamed target without a sample yet: misuse of the law (a step checks its targets first). */
    make_pair(1u, 3u, k);
    ASSERT_STATUS(TVO_OK, tvo_target_init_streamed(&pair.target[0]));
    random_state(&y, 2u);
    a = evaluate(&pair.tracking_only, &y, &good);
    b = evaluate(&pair.general, &y, &good);
    ASSERT_STATUS(TVO_ERR_NOT_INITIALIZED, b.status);
    assert_same_outcome(&a, &b, 2u);
}

/* jets_only (the reference switch) asks for the general path: without it the step refuses; the
 * tools' entry, tvo_law_evaluate, always has it. */
static void test_jets_only_needs_the_general_path_which_the_tools_entry_always_has(void)
{
    tvo_output_derivs_t y;
    make_pair(1u, 1u, 2u);
    random_state(&y, 2u);
    const tvo_time_jet_t t = random_time();
    pair.tracking_only.jets_only = 1u;
    pair.general.jets_only = 1u;
    const outcome_t a = evaluate(&pair.tracking_only, &y, &t);
    ASSERT_STATUS(TVO_ERR_NOT_INITIALIZED, a.status);
    for (unsigned i = 0; i < 2u; ++i) {
        ASSERT_NEAR(0.0, a.y_k[i], 0.0);
    }
    tvo_real_t by_tools[TVO_MAX_Z_DIM] = {TVO_R(0.0)};
    tvo_real_t by_general[TVO_MAX_Z_DIM] = {TVO_R(0.0)};
    ASSERT_STATUS(TVO_OK, tvo_law_evaluate(&pair.law, &pair.tracking_only, &y, &t, by_tools, NULL));
    ASSERT_STATUS(TVO_OK, tvo_law_evaluate(&pair.law, &pair.general, &y, &t, by_general, NULL));
    TEST_ASSERT_EQUAL_MEMORY(by_general, by_tools, 2u * sizeof(tvo_real_t));
}

#if TVO_MAX_ROBOTS >= 2
/* An output no term covers has no curvature: the general path's solve regularises it, the tracking
 * path alone refuses (as tvo_tracking_add documents). */
static void test_an_output_without_a_term_is_refused_without_the_general_path(void)
{
    tvo_output_derivs_t y;
    make_pair(1u, 2u, 2u);
    tvo_objective_t tracking_only;
    tvo_objective_t general;
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&tracking_only, 4u));
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&general, 4u));
    ASSERT_STATUS(TVO_OK, tvo_tracking_add(&tracking_only, &pair.term[0]));
    const tvo_term_t spec = {tvo_tracking_gradient_jet, tvo_tracking_gradient_hessian, NULL, &pair.term[0], TVO_TERM_TRACKING};
    ASSERT_STATUS(TVO_OK, tvo_objective_add(&general, &spec));
    const tvo_real_t gains[2] = {TVO_R(25.0), TVO_R(10.0)};
    tvo_law_init(&pair.law, 2u, 4u, gains);
    random_state(&y, 4u);
    const tvo_time_jet_t t = random_time();
    const outcome_t a = evaluate(&tracking_only, &y, &t);
    const outcome_t b = evaluate(&general, &y, &t);
    ASSERT_STATUS(TVO_ERR_NOT_POSITIVE_DEFINITE, a.status);
    for (unsigned i = 0; i < 4u; ++i) {
        ASSERT_NEAR(0.0, a.y_k[i], 0.0);
    }
    ASSERT_STATUS(TVO_OK, b.status);
    TEST_ASSERT_TRUE(b.regularization > TVO_R(0.0));
    /* A derivative of the uncovered output that is not finite: refused for that first, as the
     * general path does. */
    y.d[1][3] = TEST_NAN;
    const outcome_t c = evaluate(&tracking_only, &y, &t);
    const outcome_t d = evaluate(&general, &y, &t);
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, d.status);
    assert_same_outcome(&c, &d, 4u);
}
#endif

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_tracking_add_checks_its_inputs_and_writes_nothing_when_it_refuses);
    RUN_TEST(test_the_general_add_functions_link_the_general_path);
    RUN_TEST(test_tracking_terms_alone_evaluate_as_the_general_add_does_bit_for_bit);
    RUN_TEST(test_tracking_terms_alone_refuse_what_the_general_path_refuses_with_its_status);
    RUN_TEST(test_jets_only_needs_the_general_path_which_the_tools_entry_always_has);
#if TVO_MAX_ROBOTS >= 2
    RUN_TEST(test_an_output_without_a_term_is_refused_without_the_general_path);
#endif
    return UNITY_END();
}
