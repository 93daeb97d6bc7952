/*
 * Negative control for the allocation check: this program does call the allocator, so the check
 * must report it. If the check passes on this, the check itself is broken.
 */
#include <stdlib.h>

int main(void);

static volatile size_t canary_size = 16u;

int main(void)
{
    char *p = malloc(canary_size);
    if (p == NULL) {
        return 1;
    }
    p[0] = 1;
    int result = p[0];
    free(p);
    return result - 1;
}
