/*
 * The block solve (tvo/linsolve.h's plan, internal/block_solve.h): the plans tvo_solve_plan_build makes
 * (least fill on a ring, chain, star, any graph; multipliers last), and the law's solve through a plan
 * (tvo_saddle_solve_split on a matrix whose blocks the plan names) against the residual of the system in
 * double and against the dense solve of the same matrix: random symmetric positive definite block
 * systems of each pattern, with formation offsets' multipliers, with stiff parts kept apart; the
 * regularisation ladder and the Gershgorin fallback (the dense solve's shift, to the bit); an
 * indefinite Schur complement (dependent equalities); entries that are not finite; and the limits (the
 * most nodes a build holds, fully coupled, and one more).
 */
#include "test_support.h"

#include "tvo/linsolve.h"
#include "internal/block_solve.h"
#include "internal/jet.h"
#include "internal/linsolve.h"

void setUp(void) {}
void tearDown(void) {}

#if TVO_BLOCK_SOLVE

#define MAX_PAIRS (TVO_PLAN_MAX_BLOCKS + 2u * (TVO_MAX_EQUALITIES / 2u))

static uint32_t rng_state = 0x1D872B41u;

static double uniform(double lo, double hi)
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return lo + (hi - lo) * (double)(rng_state >> 8) / 16777216.0;
}

/* A system: robots and offsets (multipliers robots + i, each coupling robots offset_pair[i]), the
 * robots' couplings as pairs of nodes. */
typedef struct {
    uint8_t robots;
    uint8_t offsets;
    uint16_t pair_count;
    uint8_t pairs[2u * MAX_PAIRS];
    uint8_t offset_pair[TVO_ARRAY_LEN(TVO_MAX_EQUALITIES / 2)][2];
} pattern_t;

static void add_pair(pattern_t *p, unsigned a, unsigned b)
{
    TEST_ASSERT_TRUE(p->pair_count < MAX_PAIRS);
    p->pairs[2u * p->pair_count] = (uint8_t)a;
    p->pairs[2u * p->pair_count + 1u] = (uint8_t)b;
    p->pair_count++;
}

static void pattern_ring(pattern_t *p, unsigned robots)
{
    memset(p, 0, sizeof(*p));
    p->robots = (uint8_t)robots;
    for (unsigned r = 0; r < robots; ++r) {
        add_pair(p, r, (r + 1u) % robots);
    }
}

static void pattern_chain(pattern_t *p, unsigned robots)
{
    memset(p, 0, sizeof(*p));
    p->robots = (uint8_t)robots;
    for (unsigned r = 0; r + 1u < robots; ++r) {
        add_pair(p, r, r + 1u);
    }
}

static void pattern_star(pattern_t *p, unsigned robots)
{
    memset(p, 0, sizeof(*p));
    p->robots = (uint8_t)robots;
    for (unsigned r = 1; r < robots; ++r) {
        add_pair(p, 0u, r);
    }
}

static void pattern_complete(pattern_t *p, unsigned robots)
{
    memset(p, 0, sizeof(*p));
    p->robots = (uint8_t)robots;
    for (unsigned a = 0; a < robots; ++a) {
        for (unsigned b = a + 1u; b < robots; ++b) {
            add_pair(p, a, b);
        }
    }
}

/* Each pair of robots coupled with probability 1/3, and robot 1 left without any. */
static void pattern_random(pattern_t *p, unsigned robots)
{
    memset(p, 0, sizeof(*p));
    p->robots = (uint8_t)robots;
    for (unsigned a = 0; a < robots; ++a) {
        for (unsigned b = a + 1u; b < robots; ++b) {
            if (a != 1u && b != 1u && uniform(0.0, 3.0) < 1.0) {
                add_pair(p, a, b);
            }
        }
    }
}

/* Offset i couples robots (2i, 2i + 1) through multipliers robots + i, as tvo_problem_init's. */
static void pattern_add_offsets(pattern_t *p, unsigned offsets)
{
    for (unsigned i = 0; i < offsets; ++i) {
        p->offset_pair[i][0] = (uint8_t)(2u * i);
        p->offset_pair[i][1] = (uint8_t)(2u * i + 1u);
        add_pair(p, 2u * i, p->robots + i);
        add_pair(p, 2u * i + 1u, p->robots + i);
    }
    p->offsets = (uint8_t)offsets;
}

static tvo_solve_plan_t plan;
static tvo_hessian_t blocks;      /* the system through the plan */
static tvo_hessian_t dense;       /* the same matrix, solved dense */
static double exact[TVO_MAX_Z_DIM][TVO_MAX_Z_DIM];

static void put(unsigned i, unsigned j, double v)
{
    blocks.matrix[i][j] = test_r(v);
    blocks.matrix[j][i] = test_r(v);
    dense.matrix[i][j] = test_r(v);
    dense.matrix[j][i] = test_r(v);
    exact[i][j] = test_d(test_r(v));
    exact[j][i] = exact[i][j];
}

static void add(unsigned i, unsigned j, double v)
{
    put(i, j, exact[i][j] + v);
}

/* The plan of p, and the matrix: each robot's 2 x 2 block positive definite, each robot pair's coupling
 * a random w v v^T over their four outputs (positive semidefinite, so P stays positive definite), and
 * each offset's constraint rows [I, -I]. Entries off the plan's blocks hold garbage, which must not be
 * read. */
static void build_system(const pattern_t *p)
{
    const unsigned primal = 2u * p->robots;
    ASSERT_STATUS(TVO_OK, tvo_solve_plan_build(&plan, p->robots, p->offsets, (uint8_t)primal, p->pairs, p->pair_count));
    for (unsigned i = 0; i < TVO_MAX_Z_DIM; ++i) {
        for (unsigned j = 0; j < TVO_MAX_Z_DIM; ++j) {
            blocks.matrix[i][j] = TVO_R(1.0e30); /* garbage */
            dense.matrix[i][j] = TVO_R(0.0);
            exact[i][j] = 0.0;
        }
    }
    tvo_hessian_clear_blocks(&blocks, &plan);
    TEST_ASSERT_TRUE(blocks.plan == &plan);
    dense.rank_one_count = 0u;
    dense.plan = NULL;
    for (unsigned r = 0; r < p->robots; ++r) {
        put(2u * r, 2u * r, uniform(1.0, 3.0));
        put(2u * r + 1u, 2u * r + 1u, uniform(1.0, 3.0));
        put(2u * r, 2u * r + 1u, uniform(-0.5, 0.5));
    }
    for (unsigned k = 0; k < p->pair_count; ++k) {
        const unsigned a = p->pairs[2u * k];
        const unsigned b = p->pairs[2u * k + 1u];
        if (a >= p->robots || b >= p->robots) {
            continue; /* an offset's: its rows below */
        }
        const unsigned idx[4] = {2u * a, 2u * a + 1u, 2u * b, 2u * b + 1u};
        double v[4];
        for (unsigned i = 0; i < 4u; ++i) {
            v[i] = uniform(-1.0, 1.0);
        }
        const double w = uniform(0.1, 2.0);
        for (unsigned i = 0; i < 4u; ++i) {
            for (unsigned j = i; j < 4u; ++j) {
                add(idx[i], idx[j], w * v[i] * v[j]);
            }
        }
    }
    for (unsigned q = 0; q < p->offsets; ++q) {
        for (unsigned axis = 0; axis < 2u; ++axis) {
            const unsigned nu = primal + 2u * q + axis;
            put(nu, 2u * p->offset_pair[q][0] + axis, 1.0);
            put(nu, 2u * p->offset_pair[q][1] + axis, -1.0);
            put(nu, nu, 0.0);
        }
        put(primal + 2u * q, primal + 2u * q + 1u, 0.0);
    }
}

/* max_i |((A + shift I_primal) x - b)_i| over scale_i = sum_j |A_ij x_j| + |b_i|, in double. */
static double relative_residual(unsigned primal, unsigned n, double shift, const tvo_real_t *x, const tvo_real_t *b)
{
    double worst = 0.0;
    for (unsigned i = 0; i < n; ++i) {
        double r = -test_d(b[i]);
        double s = fabs(test_d(b[i]));
        for (unsigned j = 0; j < n; ++j) {
            const double aij = exact[i][j] + ((i == j && i < primal) ? shift : 0.0);
            r += aij * test_d(x[j]);
            s += fabs(aij * test_d(x[j]));
        }
        if (fabs(r) / s > worst) {
            worst = fabs(r) / s;
        }
    }
    return worst;
}

/* The system of p solved through its plan and dense: both solve it, to the same shift. */
static void solve_and_compare(const pattern_t *p, unsigned ulps)
{
    const unsigned primal = 2u * p->robots;
    const unsigned n = primal + 2u * p->offsets;
    tvo_real_t b[TVO_MAX_Z_DIM];
    for (unsigned i = 0; i < n; ++i) {
        b[i] = test_r(uniform(-2.0, 2.0));
    }
    tvo_real_t x_blocks[TVO_MAX_Z_DIM];
    tvo_real_t x_dense[TVO_MAX_Z_DIM];
    tvo_real_t shift_blocks = TVO_R(-1.0);
    tvo_real_t shift_dense = TVO_R(-1.0);
    ASSERT_STATUS(TVO_OK, tvo_saddle_solve_split(&blocks, (uint8_t)primal, (uint8_t)(n - primal), b, NULL, x_blocks,
                                                 &shift_blocks));
    ASSERT_STATUS(TVO_OK, tvo_saddle_solve_split(&dense, (uint8_t)primal, (uint8_t)(n - primal), b, NULL, x_dense,
                                                 &shift_dense));
    ASSERT_NEAR(test_d(shift_dense), test_d(shift_blocks), 0.0);
    ASSERT_LE(relative_residual(primal, n, test_d(shift_blocks), x_blocks, b), (double)ulps * TEST_EPS,
              "relative residual of the block solve");
    double size = 0.0;
    for (unsigned i = 0; i < n; ++i) {
        size = fmax(size, fabs(test_d(x_dense[i])));
    }
    for (unsigned i = 0; i < n; ++i) {
        ASSERT_NEAR(test_d(x_dense[i]), test_d(x_blocks[i]), TEST_TOL(64 * ulps, size));
    }
}

static unsigned sizes[3]; /* 3 robots, the build's most, and one between */

static void set_sizes(void)
{
    sizes[0] = 3u;
    sizes[1] = TVO_MAX_ROBOTS > 4 ? TVO_MAX_ROBOTS / 2u + 1u : TVO_MAX_ROBOTS;
    sizes[2] = TVO_MAX_ROBOTS;
}

static void test_plans_follow_the_coupling_with_least_fill(void)
{
    pattern_t p;
    set_sizes();
    for (unsigned s = 0; s < 3u; ++s) {
        const unsigned n = sizes[s];
        /* A ring: eliminating a robot couples its two neighbours, one fill block each until three are
         * left (2n - 3 blocks); a chain and a star: their ends and leaves first, no fill (n - 1). */
        pattern_ring(&p, n);
        ASSERT_STATUS(TVO_OK, tvo_solve_plan_build(&plan, p.robots, 0u, (uint8_t)(2u * n), p.pairs, p.pair_count));
        TEST_ASSERT_EQUAL_UINT8(n, plan.node_count);
        TEST_ASSERT_EQUAL_UINT8(n, plan.primal_nodes);
        TEST_ASSERT_EQUAL_UINT16(2u * n - 3u, plan.below_start[n]);
        pattern_chain(&p, n);
        ASSERT_STATUS(TVO_OK, tvo_solve_plan_build(&plan, p.robots, 0u, (uint8_t)(2u * n), p.pairs, p.pair_count));
        TEST_ASSERT_EQUAL_UINT16(n - 1u, plan.below_start[n]);
        pattern_star(&p, n);
        ASSERT_STATUS(TVO_OK, tvo_solve_plan_build(&plan, p.robots, 0u, (uint8_t)(2u * n), p.pairs, p.pair_count));
        TEST_ASSERT_EQUAL_UINT16(n - 1u, plan.below_start[n]);
        /* The hub after every leaf but the last (it ties with that one, and the lower index goes first). */
        TEST_ASSERT_TRUE(plan.first[n - 1u] == 0u || plan.first[n - 2u] == 0u);
        pattern_complete(&p, n);
        ASSERT_STATUS(TVO_OK, tvo_solve_plan_build(&plan, p.robots, 0u, (uint8_t)(2u * n), p.pairs, p.pair_count));
        TEST_ASSERT_EQUAL_UINT16(n * (n - 1u) / 2u, plan.below_start[n]);
    }
    /* Every robot once, every position's blocks later positions' first coordinates, ascending. */
    pattern_random(&p, TVO_MAX_ROBOTS);
    ASSERT_STATUS(TVO_OK, tvo_solve_plan_build(&plan, p.robots, 0u, (uint8_t)(2u * p.robots), p.pairs, p.pair_count));
    unsigned seen = 0u;
    for (unsigned q = 0; q < plan.node_count; ++q) {
        TEST_ASSERT_EQUAL_UINT8(0u, plan.first[q] % 2u);
        seen |= 1u << (plan.first[q] / 2u % 32u);
        unsigned previous = 0u;
        for (unsigned k = plan.below_start[q]; k < plan.below_start[q + 1u]; ++k) {
            unsigned later = TVO_PLAN_MAX_NODES;
            for (unsigned r = q + 1u; r < plan.node_count; ++r) {
                later = plan.first[r] == plan.below[k] ? r : later;
            }
            TEST_ASSERT_TRUE(later < plan.node_count && later > previous);
            previous = later;
        }
    }
    TEST_ASSERT_EQUAL_UINT32(TVO_MAX_ROBOTS >= 32 ? 0xFFFFFFFFu : (1u << TVO_MAX_ROBOTS) - 1u, seen);
}

static void test_multipliers_come_last(void)
{
#if TVO_MAX_EQUALITIES >= 2
    pattern_t p;
    pattern_ring(&p, TVO_MAX_ROBOTS);
    pattern_add_offsets(&p, TVO_MAX_EQUALITIES / 2u);
    ASSERT_STATUS(TVO_OK, tvo_solve_plan_build(&plan, p.robots, p.offsets, (uint8_t)(2u * p.robots), p.pairs,
                                               p.pair_count));
    TEST_ASSERT_EQUAL_UINT8(p.robots + p.offsets, plan.node_count);
    TEST_ASSERT_EQUAL_UINT8(p.robots, plan.primal_nodes);
    for (unsigned q = 0; q < plan.node_count; ++q) {
        TEST_ASSERT_EQUAL_INT(q >= plan.primal_nodes, plan.first[q] >= 2u * p.robots);
    }
#else
    TEST_IGNORE_MESSAGE("a build without equalities");
#endif
}

static void test_random_spd_systems_of_each_pattern_solve_as_dense(void)
{
    pattern_t p;
    set_sizes();
    for (unsigned trial = 0; trial < 12u; ++trial) {
        const unsigned n = sizes[trial % 3u];
        switch (trial / 3u) {
        case 0u: pattern_ring(&p, n); break;
        case 1u: pattern_chain(&p, n); break;
        case 2u: pattern_star(&p, n); break;
        default: pattern_random(&p, n); break;
        }
        build_system(&p);
        solve_and_compare(&p, 64u);
    }
    pattern_complete(&p, TVO_MAX_ROBOTS);
    build_system(&p);
    solve_and_compare(&p, 64u);
}

static void test_formation_offsets_solve_as_dense(void)
{
#if TVO_MAX_EQUALITIES >= 2
    pattern_t p;
    for (unsigned trial = 0; trial < 6u; ++trial) {
        if (trial % 2u == 0u) {
            pattern_ring(&p, TVO_MAX_ROBOTS);
        } else {
            pattern_chain(&p, TVO_MAX_ROBOTS);
        }
        pattern_add_offsets(&p, 1u + trial % (TVO_MAX_EQUALITIES / 2u));
        build_system(&p);
        solve_and_compare(&p, 256u);
    }
#else
    TEST_IGNORE_MESSAGE("a build without equalities");
#endif
}

static void test_indefinite_primal_takes_the_dense_ladder_step(void)
{
    pattern_t p;
    pattern_ring(&p, TVO_MAX_ROBOTS);
    build_system(&p);
    /* One robot's block indefinite (eigenvalue about -0.5): the ladder's first shift above it, the same
     * as the dense solve's, and the result solves the shifted system. */
    put(2u, 2u, -0.5);
    put(2u, 3u, 0.0);
    solve_and_compare(&p, 64u);
    tvo_real_t b[TVO_MAX_Z_DIM] = {TVO_R(1.0)};
    tvo_real_t x[TVO_MAX_Z_DIM];
    tvo_real_t shift = TVO_R(0.0);
    build_system(&p);
    put(2u, 2u, -0.5);
    put(2u, 3u, 0.0);
    ASSERT_STATUS(TVO_OK, tvo_saddle_solve_split(&blocks, (uint8_t)(2u * p.robots), 0u, b, NULL, x, &shift));
    TEST_ASSERT_TRUE(shift > TVO_R(0.0));
}

static void test_gershgorin_fallback_as_dense(void)
{
    pattern_t p;
    pattern_chain(&p, 3u);
    build_system(&p);
    /* Off-diagonal entries 1e4 on a unit diagonal: beyond the ladder's 1e2 s, so the Gershgorin shift. */
    put(0u, 2u, 1.0e4);
    put(1u, 3u, -1.0e4);
    put(2u, 4u, 1.0e4);
    const unsigned n = 6u;
    tvo_real_t b[6] = {TVO_R(1.0), TVO_R(-1.0), TVO_R(0.5), TVO_R(2.0), TVO_R(0.0), TVO_R(1.0)};
    tvo_real_t x_blocks[6];
    tvo_real_t x_dense[6];
    tvo_real_t shift_blocks = TVO_R(0.0);
    tvo_real_t shift_dense = TVO_R(0.0);
    ASSERT_STATUS(TVO_OK, tvo_saddle_solve_split(&blocks, (uint8_t)n, 0u, b, NULL, x_blocks, &shift_blocks));
    ASSERT_STATUS(TVO_OK, tvo_saddle_solve_split(&dense, (uint8_t)n, 0u, b, NULL, x_dense, &shift_dense));
    ASSERT_LE(1.0e4, test_d(shift_blocks), "beyond the ladder");
    ASSERT_NEAR(test_d(shift_dense), test_d(shift_blocks), 0.0);
    ASSERT_LE(relative_residual(n, n, test_d(shift_blocks), x_blocks, b), 64.0 * TEST_EPS, "(P + mu I) x = b");
}

static void test_dependent_equalities_are_refused(void)
{
#if TVO_MAX_EQUALITIES >= 4
    pattern_t p;
    pattern_ring(&p, TVO_MAX_ROBOTS);
    pattern_add_offsets(&p, 2u);
    /* The second offset couples the first's robots again: its rows repeat the first's, S is singular. */
    p.offset_pair[1][0] = 0u;
    p.offset_pair[1][1] = 1u;
    p.pairs[2u * (p.pair_count - 2u)] = 0u;
    p.pairs[2u * (p.pair_count - 1u)] = 1u;
    build_system(&p);
    const unsigned n = 2u * p.robots + 4u;
    tvo_real_t b[TVO_MAX_Z_DIM] = {TVO_R(1.0)};
    tvo_real_t x[TVO_MAX_Z_DIM];
    ASSERT_STATUS(TVO_ERR_NOT_POSITIVE_DEFINITE,
                  tvo_saddle_solve_split(&blocks, (uint8_t)(2u * p.robots), 4u, b, NULL, x, NULL));
    ASSERT_STATUS(TVO_ERR_NOT_POSITIVE_DEFINITE,
                  tvo_saddle_solve_split(&dense, (uint8_t)(2u * p.robots), 4u, b, NULL, x, NULL));
    (void)n;
#else
    TEST_IGNORE_MESSAGE("a build with fewer than two offsets");
#endif
}

static void test_stiff_parts_kept_apart_solve_as_dense(void)
{
    pattern_t p;
    pattern_ring(&p, TVO_MAX_ROBOTS);
    build_system(&p);
    /* A maximum bound's part between robots 0 and 1, 1e7 stiffer than the rest: kept apart and solved by
     * Woodbury on the blocks' factor, as on the dense one. */
    tvo_rank_one_t part;
    memset(&part, 0, sizeof(part));
    part.weight = TVO_R(4.0e7);
    part.count = 4u;
    const uint8_t index[4] = {0u, 1u, 2u, 3u};
    const tvo_real_t value[4] = {TVO_R(0.6), TVO_R(0.8), TVO_R(-0.6), TVO_R(-0.8)};
    memcpy(part.index, index, sizeof(index));
    memcpy(part.value, value, sizeof(value));
    tvo_hessian_add_part(&blocks, &part, NULL, 0u);
    tvo_hessian_add_part(&dense, &part, NULL, 0u);
    TEST_ASSERT_EQUAL_UINT8(1u, blocks.rank_one_count);
    const unsigned n = 2u * p.robots;
    tvo_real_t b[TVO_MAX_Z_DIM];
    for (unsigned i = 0; i < n; ++i) {
        b[i] = test_r(uniform(-1.0, 1.0));
    }
    const tvo_real_t gamma[1] = {TVO_R(1.3e9)};
    tvo_real_t x_blocks[TVO_MAX_Z_DIM];
    tvo_real_t x_dense[TVO_MAX_Z_DIM];
    ASSERT_STATUS(TVO_OK, tvo_saddle_solve_split(&blocks, (uint8_t)n, 0u, b, gamma, x_blocks, NULL));
    ASSERT_STATUS(TVO_OK, tvo_saddle_solve_split(&dense, (uint8_t)n, 0u, b, gamma, x_dense, NULL));
    for (unsigned i = 0; i < n; ++i) {
        ASSERT_NEAR(test_d(x_dense[i]), test_d(x_blocks[i]), TEST_TOL(4096, x_dense[i]));
    }
}

static void test_entries_that_are_not_finite_are_named(void)
{
    pattern_t p;
    pattern_ring(&p, TVO_MAX_ROBOTS);
    const unsigned n = 2u * TVO_MAX_ROBOTS;
    tvo_real_t b[TVO_MAX_Z_DIM] = {TVO_R(1.0)};
    tvo_real_t x[TVO_MAX_Z_DIM];
    build_system(&p);
    put(0u, 2u, (double)NAN); /* a coupled pair's block */
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_saddle_solve_split(&blocks, (uint8_t)n, 0u, b, NULL, x, NULL));
    build_system(&p);
    put(5u, 5u, (double)INFINITY); /* a diagonal entry */
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_saddle_solve_split(&blocks, (uint8_t)n, 0u, b, NULL, x, NULL));
    build_system(&p);
    b[3] = TEST_NAN;
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_saddle_solve_split(&blocks, (uint8_t)n, 0u, b, NULL, x, NULL));
    /* A plan of another size than the call's: refused, nothing solved. */
    b[3] = TVO_R(0.0);
    build_system(&p);
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_saddle_solve_split(&blocks, (uint8_t)(n - 2u), 0u, b, NULL, x, NULL));
}

static void test_the_limits(void)
{
    /* The most nodes a build holds, every pair coupled: the full factor fits, and solves. */
    pattern_t p;
    pattern_complete(&p, TVO_MAX_ROBOTS);
#if TVO_MAX_EQUALITIES >= 2
    pattern_add_offsets(&p, TVO_MAX_EQUALITIES / 2u);
#endif
    build_system(&p);
    TEST_ASSERT_EQUAL_UINT8(TVO_PLAN_MAX_NODES, plan.node_count);
    ASSERT_LE(plan.below_start[plan.node_count], TVO_PLAN_MAX_BLOCKS, "blocks within the limit");
    solve_and_compare(&p, 256u);
    /* One node more, a pair naming a node twice or one that does not exist: refused, the plan empty. */
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_solve_plan_build(&plan, TVO_MAX_ROBOTS + 1u, TVO_MAX_EQUALITIES / 2u,
                                                          (uint8_t)(2u * TVO_MAX_ROBOTS + 2u), p.pairs, 0u));
    TEST_ASSERT_EQUAL_UINT8(0u, plan.node_count);
    const uint8_t self[2] = {1u, 1u};
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_solve_plan_build(&plan, 3u, 0u, 6u, self, 1u));
    TEST_ASSERT_EQUAL_UINT8(0u, plan.node_count);
    const uint8_t beyond[2] = {0u, 3u};
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_solve_plan_build(&plan, 3u, 0u, 6u, beyond, 1u));
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_solve_plan_build(&plan, 0u, 0u, 0u, NULL, 0u));
}

#endif /* TVO_BLOCK_SOLVE */

int main(void)
{
    UNITY_BEGIN();
#if TVO_BLOCK_SOLVE
    RUN_TEST(test_plans_follow_the_coupling_with_least_fill);
    RUN_TEST(test_multipliers_come_last);
    RUN_TEST(test_random_spd_systems_of_each_pattern_solve_as_dense);
    RUN_TEST(test_formation_offsets_solve_as_dense);
    RUN_TEST(test_indefinite_primal_takes_the_dense_ladder_step);
    RUN_TEST(test_gershgorin_fallback_as_dense);
    RUN_TEST(test_dependent_equalities_are_refused);
    RUN_TEST(test_stiff_parts_kept_apart_solve_as_dense);
    RUN_TEST(test_entries_that_are_not_finite_are_named);
    RUN_TEST(test_the_limits);
#endif
    return UNITY_END();
}
