/*
 * Linked with -Wl,--wrap=expf (tvo_agree*_same_expf, tvo_bench_same_expf): every expf call, the core's
 * barrier schedule among them, becomes double exp rounded once to float. glibc's and newlib's double
 * exp are both within an ulp of exact, so rounded to float they give the same bits but for arguments
 * whose exp lies within about 2^-29 of a float halfway point: the experiment that tells whether
 * expf alone makes two machines' commands differ (tools/agree).
 */
#include <math.h>

float __wrap_expf(float x);

float __wrap_expf(float x)
{
    return (float)exp((double)x);
}
