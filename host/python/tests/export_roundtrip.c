/*
 * The C side of test_export_c.py: builds the problem and the controller settings of an exported
 * header (tvo.export_c, included as "scenario_export.h", name "scenario") through the core, and
 * prints the bytes of the tvo_problem_desc_t and tvo_controller_config_t it filled, for the test to
 * compare with those the `tvo` module built from the same Python description.
 */
#include <stdio.h>
#include <string.h>

#include "scenario_export.h"

static void print_bytes(const char *label, const void *p, size_t n)
{
    const unsigned char *b = (const unsigned char *)p;
    printf("%s ", label);
    for (size_t i = 0; i < n; ++i) {
        printf("%02x", b[i]);
    }
    printf("\n");
}

int main(void)
{
    static tvo_problem_desc_t desc;
    static tvo_problem_t problem;
    static tvo_controller_t controller;
    static tvo_controller_config_t cfg;
    memset(&desc, 0, sizeof desc);
    memset(&cfg, 0, sizeof cfg);
    tvo_status_t st = scenario_problem_desc(&desc);
    if (st != TVO_OK) {
        fprintf(stderr, "export_roundtrip: scenario_problem_desc: %s\n", tvo_status_str(st));
        return 1;
    }
    tvo_problem_culprit_t part;
    st = tvo_problem_init(&problem, &desc, 2u, &part);
    if (st != TVO_OK) {
        fprintf(stderr, "export_roundtrip: tvo_problem_init: %s (part %u, entry %d)\n", tvo_status_str(st),
                (unsigned)part.part, (int)part.index);
        return 1;
    }
    st = scenario_controller_config(&cfg);
    tvo_param_t bad = TVO_PARAM_NONE;
    if (st == TVO_OK) {
        st = tvo_controller_init(&controller, &cfg, &problem.objective, 0u, &bad);
    }
    if (st != TVO_OK) {
        fprintf(stderr, "export_roundtrip: controller: %s (%s)\n", tvo_status_str(st), tvo_param_str(bad));
        return 1;
    }
    print_bytes("desc", &desc, sizeof desc);
    print_bytes("config", &cfg, sizeof cfg);
    print_bytes("start", scenario_start, sizeof scenario_start);
    return 0;
}
